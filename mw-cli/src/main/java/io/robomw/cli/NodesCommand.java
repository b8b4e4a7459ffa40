package io.robomw.cli;

import io.robomw.agents.messaging.discovery.BeaconRecord;
import io.robomw.agents.messaging.discovery.Discovery;
import picocli.CommandLine.Command;
import picocli.CommandLine.Mixin;
import picocli.CommandLine.Model.CommandSpec;
import picocli.CommandLine.Option;
import picocli.CommandLine.Spec;

import java.io.PrintWriter;
import java.time.Duration;
import java.util.List;
import java.util.concurrent.Callable;
import java.util.concurrent.locks.LockSupport;

/**
 * {@code mw nodes}: the messaging nodes that announce themselves on the discovery group (every
 * node {@code mw host} and {@code mw msg} start does, once a second), like {@code ros2 node list}.
 */
@Command(mixinStandardHelpOptions = true, name = "nodes", description = {"List the messaging nodes announced on the discovery group (mw host, mw msg...),",
        "with where they receive, their agent host and the robots they serve. Like ros2 node list."})
final class NodesCommand implements Callable<Integer> {

    @Mixin
    BeaconOption beacon;

    @Option(names = "--wait", defaultValue = "2500ms", description = "how long to listen for beacons (default ${DEFAULT-VALUE}; nodes announce once a second)")
    Duration wait;

    @Spec
    CommandSpec spec;

    /** Listens for {@code wait} and returns what was heard; shared with {@code mw topics}. */
    static List<BeaconRecord> listen(BeaconOption beacon, Duration wait) {
        if (beacon.off()) {
            throw new IllegalArgumentException("--beacon off: there is no discovery group to listen to");
        }
        try (Discovery d = Discovery.listen(beacon.group)) {
            long end = System.nanoTime() + wait.toNanos();
            for (long left; (left = end - System.nanoTime()) > 0; ) {
                LockSupport.parkNanos(left);
            }
            return d.nodes();
        }
    }

    @Override
    public Integer call() {
        PrintWriter out = spec.commandLine().getOut();
        List<BeaconRecord> nodes = listen(beacon, wait);
        out.printf("%d node%s on %s%n", nodes.size(), nodes.size() == 1 ? "" : "s", beacon.group);
        for (BeaconRecord n : nodes) {
            out.printf("%s  %s%s%s%n", n.node(), n.messaging().isEmpty() ? "(connects only)" : String.join(" ", n.messaging()),
                    n.host() == null ? "" : "  host " + n.host() + " " + n.hostAddress(),
                    n.robots().isEmpty() ? "" : "  robots " + String.join(",", n.robots()));
        }
        out.flush();
        return 0;
    }
}
