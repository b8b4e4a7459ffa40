package io.robomw.agents.messaging;

import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.util.EnumMap;
import java.util.Map;
import java.util.concurrent.atomic.AtomicLong;
import java.util.concurrent.atomic.LongAdder;

/**
 * A node's counters, and the log of dropped frames. Every drop is counted; the log gets one line
 * per reason per second at most ({@code "... (and 41 more dropped for BAD_MAC since the last line)"}),
 * so a flood of bad input cannot flood the log. Thread-safe.
 */
final class NodeCounters {

    private static final Logger LOG = LoggerFactory.getLogger(NodeCounters.class);
    private static final long LOG_INTERVAL_NANOS = 1_000_000_000L;

    private final String node;
    private final LongAdder framesIn = new LongAdder();
    private final LongAdder framesOut = new LongAdder();
    private final LongAdder lost = new LongAdder();
    private final LongAdder reordered = new LongAdder();
    private final LongAdder listenerErrors = new LongAdder();
    private final Map<DropReason, LongAdder> dropped = new EnumMap<>(DropReason.class);
    private final Map<DropReason, AtomicLong> lastLogged = new EnumMap<>(DropReason.class);
    private final Map<DropReason, LongAdder> unlogged = new EnumMap<>(DropReason.class);

    NodeCounters(String node) {
        this.node = node;
        for (DropReason r : DropReason.values()) {
            dropped.put(r, new LongAdder());
            lastLogged.put(r, new AtomicLong(System.nanoTime() - 2 * LOG_INTERVAL_NANOS));
            unlogged.put(r, new LongAdder());
        }
    }

    void in() {
        framesIn.increment();
    }

    void out() {
        framesOut.increment();
    }

    void lost(long n) {
        lost.add(n);
    }

    void reordered() {
        reordered.increment();
    }

    void listenerError() {
        listenerErrors.increment();
    }

    /** Counts a dropped frame and logs it, at most one line per reason per second. */
    void drop(DropReason reason, String where, String detail) {
        dropped.get(reason).increment();
        AtomicLong last = lastLogged.get(reason);
        long now = System.nanoTime();
        long before = last.get();
        if (now - before >= LOG_INTERVAL_NANOS && last.compareAndSet(before, now)) {
            long more = unlogged.get(reason).sumThenReset();
            LOG.warn("node '{}': dropped a frame from {}: {}: {}{}", node, where, reason, detail,
                    more > 0 ? " (and " + more + " more dropped for " + reason + " since the last line)" : "");
        } else {
            unlogged.get(reason).increment();
        }
    }

    /** Counts a dropped frame without a log line (publications on topics this node does not want). */
    void dropQuietly(DropReason reason) {
        dropped.get(reason).increment();
    }

    MessagingStats snapshot() {
        Map<DropReason, Long> d = new EnumMap<>(DropReason.class);
        dropped.forEach((r, n) -> d.put(r, n.sum()));
        return new MessagingStats(framesIn.sum(), framesOut.sum(), d, lost.sum(), reordered.sum(), listenerErrors.sum());
    }
}
