package io.robomw.agents.messaging.discovery;

import io.robomw.agents.messaging.Address;
import io.robomw.agents.messaging.MessagingNode;
import io.robomw.agents.net.OwnerThreads;
import io.robomw.agents.messaging.MessagingSettings;
import io.robomw.agents.messaging.PresenceRecord;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.time.Duration;
import java.util.List;
import java.util.concurrent.Executors;
import java.util.concurrent.ScheduledExecutorService;
import java.util.concurrent.TimeUnit;

/**
 * A messaging node's discovery beacon: once a {@link #PERIOD}, a {@link BeaconRecord} of the node
 * (its name, addresses, topics, agent host and robots) published on topic
 * {@value BeaconRecord#TOPIC} of a multicast group, by a small node of its own joined to that
 * group; an offline record when it closes. {@link Discovery} listens. The group's address says
 * the interface and TTL ({@code multicast://239.255.77.77:7447?interface=lo&ttl=0}); without an
 * interface it is the loopback interface, so by default only this machine hears it.
 */
public final class Beacon implements AutoCloseable {

    /** The group beacons go to unless told otherwise (loopback unless the address names an interface). */
    public static final String DEFAULT_GROUP = "multicast://239.255.77.77:7447";
    /** How often a node announces itself. */
    public static final Duration PERIOD = Duration.ofSeconds(1);

    private static final Logger LOG = LoggerFactory.getLogger(Beacon.class);

    private final MessagingNode node;
    private final MessagingNode announcer;
    private final ScheduledExecutorService timer;
    private final Duration period;

    private Beacon(MessagingNode node, MessagingNode announcer, ScheduledExecutorService timer, Duration period) {
        this.node = node;
        this.announcer = announcer;
        this.timer = timer;
        this.period = period;
    }

    /**
     * @param node  the node to announce
     * @param group the multicast group, {@code multicast://GROUP:PORT[?interface=NIC&ttl=N]}
     * @return the running beacon; close it before the node
     * @throws io.robomw.api.MessagingException if the group cannot be joined
     */
    public static Beacon start(MessagingNode node, String group) {
        return start(node, group, PERIOD);
    }

    /**
     * @param node   the node to announce
     * @param group  the multicast group
     * @param period how often
     * @return the running beacon
     */
    public static Beacon start(MessagingNode node, String group, Duration period) {
        if (!Address.parse(group).scheme().equals("multicast")) {
            throw new IllegalArgumentException("a beacon goes to a multicast group (multicast://239.255.77.77:7447), not " + group);
        }
        MessagingNode announcer = MessagingNode.builder(node.name()).settings(MessagingSettings.defaults()).bind(group).build();
        ScheduledExecutorService timer = Executors.newSingleThreadScheduledExecutor(
                r -> OwnerThreads.thread("mw-beacon-" + node.name(), r, node.failures()));
        Beacon b = new Beacon(node, announcer, timer, period);
        timer.scheduleAtFixedRate(OwnerThreads.rounds(node.failures(), () -> b.announce(true)), 0, period.toMillis(), TimeUnit.MILLISECONDS);
        return b;
    }

    /** @return what the beacon says now */
    BeaconRecord record(boolean online) {
        PresenceRecord p = node.presence().now("", 0, announcer.boundAddresses().get(0).toString(), java.time.Instant.now());
        List<String> messaging = node.boundAddresses().stream().map(Address::toString).toList();
        List<String> listens = node.listenedTopics().stream().filter(t -> !t.equals(BeaconRecord.TOPIC)).toList();
        return new BeaconRecord(node.name(), online, period.toMillis(), p.host(), p.hostAddress(), messaging, listens, node.publishedTopics(),
                p.robots(), false);
    }

    private void announce(boolean online) {
        try {
            announcer.publishMessage(BeaconRecord.TOPIC, new String(record(online).encode(), java.nio.charset.StandardCharsets.UTF_8), "beacon", null);
        } catch (RuntimeException e) {
            LOG.warn("node '{}': its discovery beacon failed: {}", node.name(), e.toString());
        }
    }

    @Override
    public void close() {
        timer.shutdownNow();
        try {
            timer.awaitTermination(5, TimeUnit.SECONDS);
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
        }
        announce(false);
        announcer.close();
    }
}
