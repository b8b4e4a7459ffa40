package io.robomw.agents.messaging.discovery;

import io.robomw.agents.messaging.MessagingNode;
import io.robomw.agents.messaging.MessagingSettings;
import io.robomw.api.Message;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.nio.charset.StandardCharsets;
import java.util.Comparator;
import java.util.List;
import java.util.Map;
import java.util.concurrent.ConcurrentHashMap;
import java.util.concurrent.atomic.AtomicLong;

/**
 * Listens to the {@link Beacon}s of a multicast group and keeps the latest record of each node
 * heard (by name and addresses: two nodes may share a name), until it goes offline or is not heard for three of its periods. A beacon that
 * does not decode is counted and logged (naming its sender), and ignored.
 */
public final class Discovery implements AutoCloseable {

    private static final Logger LOG = LoggerFactory.getLogger(Discovery.class);

    /** A node heard, and when (System.nanoTime). */
    private record Heard(BeaconRecord record, long atNanos) {
    }

    private final MessagingNode listener;
    private final Map<String, Heard> nodes = new ConcurrentHashMap<>();
    private final AtomicLong bad = new AtomicLong();

    private Discovery(MessagingNode listener) {
        this.listener = listener;
    }

    /**
     * @param group the beacons' multicast group
     * @return listening
     */
    public static Discovery listen(String group) {
        MessagingNode n = MessagingNode.builder("mw-discovery-" + ProcessHandle.current().pid()).settings(MessagingSettings.defaults()).build();
        Discovery d = new Discovery(n);
        try {
            n.addMessageListener(BeaconRecord.TOPIC, null, d::heard);
            n.subscribeMessage(BeaconRecord.TOPIC, null);
            n.bind(group);
        } catch (RuntimeException e) {
            n.close();
            throw e;
        }
        return d;
    }

    private void heard(Message m) {
        BeaconRecord r;
        try {
            if (!(m.payload() instanceof String text)) {
                throw new IllegalArgumentException("'" + m.sender() + "': a beacon whose payload is no text");
            }
            r = BeaconRecord.decode(text.getBytes(StandardCharsets.UTF_8), "beacon from '" + m.sender() + "'");
        } catch (IllegalArgumentException e) {
            if (bad.incrementAndGet() <= 10) {
                LOG.warn("ignored a beacon: {}", e.getMessage());
            }
            return;
        }
        String key = r.node() + " " + r.messaging();
        if (r.online()) {
            nodes.put(key, new Heard(r, System.nanoTime()));
        } else {
            nodes.remove(key);
        }
    }

    /** @return the nodes heard and not gone, sorted by name */
    public List<BeaconRecord> nodes() {
        long now = System.nanoTime();
        nodes.values().removeIf(h -> now - h.atNanos() > 3 * h.record().periodMillis() * 1_000_000L);
        return nodes.values().stream().map(Heard::record).sorted(Comparator.comparing(BeaconRecord::node)).toList();
    }

    /** @return how many beacons did not decode */
    public long badBeacons() {
        return bad.get();
    }

    @Override
    public void close() {
        listener.close();
    }
}
