package io.robomw.cli;

import io.robomw.agents.messaging.MessagingNode;
import io.robomw.agents.messaging.discovery.Beacon;
import picocli.CommandLine.Option;

/**
 * The discovery beacon of the nodes {@code mw} commands start, and where {@code mw nodes},
 * {@code mw topics} and {@code mw msg echo} listen: {@code --beacon GROUP}, default the
 * {@code MW_BEACON} environment variable, else {@link Beacon#DEFAULT_GROUP} on the loopback
 * interface (this machine); {@code --beacon off} announces nothing.
 */
final class BeaconOption {

    @Option(names = "--beacon", paramLabel = "GROUP|off", defaultValue = "${env:MW_BEACON:-" + Beacon.DEFAULT_GROUP + "}",
            description = "the discovery group nodes announce themselves on, for mw nodes and mw topics (default ${DEFAULT-VALUE}: this machine;"
                    + " multicast://GROUP:PORT?interface=eth0&ttl=1 for a network); off: none")
    String group;

    boolean off() {
        return group == null || group.equals("off");
    }

    /**
     * @param node a node to announce
     * @return its beacon, or a no-op when off
     */
    AutoCloseable announce(MessagingNode node) {
        if (off()) {
            return () -> { };
        }
        try {
            return Beacon.start(node, group);
        } catch (RuntimeException e) {
            org.slf4j.LoggerFactory.getLogger(BeaconOption.class).warn("node '{}' is not announced on {}: {}", node.name(), group, e.getMessage());
            return () -> { };
        }
    }
}
