package io.robomw.cli;

import io.robomw.agents.net.OwnerThreads;
import io.robomw.agents.host.AgentHost;
import io.robomw.agents.host.AgentInfo;
import io.robomw.agents.messaging.MessagingNode;
import io.robomw.agents.messaging.MessagingSettings;

import java.util.List;
import java.util.concurrent.Executors;
import java.util.concurrent.ScheduledExecutorService;
import java.util.concurrent.TimeUnit;

/**
 * What {@code mw host} announces at a broker: the host (name and agent host address), the robot
 * it serves and, refreshed every second, its agents, as the presence of a messaging node there
 * ({@link io.robomw.agents.messaging.PresenceRecord}); the broker replaces it with the offline
 * version when the host is gone. {@code mw agents --cluster BROKER} reads it.
 */
final class HostPresence implements AutoCloseable {

    private static final long REFRESH_MILLIS = 1_000;

    private final MessagingNode node;
    private final boolean ownsNode;
    private final ScheduledExecutorService refresh;

    private HostPresence(MessagingNode node, boolean ownsNode, ScheduledExecutorService refresh) {
        this.node = node;
        this.ownsNode = ownsNode;
        this.refresh = refresh;
    }

    /**
     * @param host   the agent host
     * @param broker a broker to announce at besides those the node is at already, or {@code null}
     * @param node   the host's messaging node (or the node serving its robot), or {@code null} when it has none
     * @param seal   signs what it announces (the cluster key's), or {@code null} for a host without a key (TLS alone)
     * @return the running announcement
     */
    static HostPresence start(AgentHost host, String broker, MessagingNode node, io.robomw.agents.messaging.security.PresenceSeal seal) {
        boolean own = node == null;
        if (own) {
            node = MessagingNode.builder(host.name()).settings(MessagingSettings.defaults()).build();
        }
        MessagingNode announcing = node;
        // The host first, then the broker: the presence the node leaves as its will there (published when
        // the host is gone without closing, as after kill -9) is made when it joins, and must name the host.
        if (seal != null) {
            announcing.presence().seal(seal);
        }
        announcing.presence().host(host.name(), host.address());
        if (broker != null) {
            announcing.bind(broker);
        }
        ScheduledExecutorService refresh = Executors.newSingleThreadScheduledExecutor(
                r -> OwnerThreads.thread("mw-host-presence-" + host.name(), r, announcing.failures()));
        // a failed announcement is reported to the node's failure policy, and the next one comes
        refresh.scheduleWithFixedDelay(OwnerThreads.rounds(announcing.failures(), () -> announcing.presence().agents(describe(host.agents()))),
                0, REFRESH_MILLIS, TimeUnit.MILLISECONDS);
        return new HostPresence(announcing, own, refresh);
    }

    static List<String> describe(List<AgentInfo> agents) {
        return agents.stream().map(a -> a.id() + " " + a.className() + " " + a.status()).toList();
    }

    @Override
    public void close() {
        refresh.shutdownNow();
        if (ownsNode) {
            node.close();
        }
    }
}
