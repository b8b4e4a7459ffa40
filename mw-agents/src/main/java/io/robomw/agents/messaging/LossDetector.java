package io.robomw.agents.messaging;

import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.util.LinkedHashMap;
import java.util.Map;

/**
 * Detects lost and reordered frames on datagram transports from the stream sequence numbers each
 * link writes (1, 2, 3, ... per sending link). A jump counts the missing numbers as lost; a number
 * below the next expected counts as reordered (it is still delivered). Streams are remembered for
 * the {@value #MAX_STREAMS} most recently active peers. Losses are logged at most once a second.
 *
 * <p>Stream sequence numbers are not covered by the MAC: the counts are diagnostics, and a forger
 * can distort them. Thread-safe.
 */
final class LossDetector {

    private static final Logger LOG = LoggerFactory.getLogger(LossDetector.class);
    static final int MAX_STREAMS = 4096;

    private record StreamKey(String peer, long source) {
    }

    private final NodeCounters counters;
    private final java.util.concurrent.atomic.AtomicLong lastLog = new java.util.concurrent.atomic.AtomicLong(System.nanoTime() - 2_000_000_000L);
    private final Map<StreamKey, long[]> next = new LinkedHashMap<>(64, 0.75f, true) {
        private static final long serialVersionUID = 1L;

        @Override
        protected boolean removeEldestEntry(Map.Entry<StreamKey, long[]> eldest) {
            return size() > MAX_STREAMS;
        }
    };

    LossDetector(NodeCounters counters) {
        this.counters = counters;
    }

    /**
     * @param peer     where the frame came from
     * @param source   its source node
     * @param sequence its stream sequence
     */
    void observe(String peer, long source, long sequence) {
        long missing;
        synchronized (next) {
            long[] expected = next.computeIfAbsent(new StreamKey(peer, source), k -> new long[] {sequence});
            if (sequence < expected[0]) {
                counters.reordered();
                return;
            }
            missing = sequence - expected[0];
            expected[0] = sequence + 1;
        }
        if (missing > 0) {
            counters.lost(missing);
            long now = System.nanoTime();
            long last = lastLog.get();
            if (now - last > 1_000_000_000L && lastLog.compareAndSet(last, now)) {
                LOG.info("{} frames lost from {} (source {}) before stream sequence {}; {} lost in all (UDP and multicast do not resend)",
                        missing, peer, Long.toHexString(source), sequence, counters.snapshot().framesLost());
            }
        }
    }
}
