package io.robomw.agents.net;

import org.slf4j.Logger;

import java.time.Duration;
import java.util.Arrays;
import java.util.concurrent.atomic.AtomicLong;
import java.util.concurrent.atomic.LongAdder;

/**
 * Warnings about what peers send, at most one line per interval: a flood of bad input must not
 * flood the log. The first warning is logged at once; those within the interval after it go to
 * debug level and are counted, and the next logged line says how many there were. Thread-safe.
 */
public final class ThrottledWarnings {

    private final Logger log;
    private final long intervalNanos;
    private final AtomicLong lastLogged;
    private final LongAdder unlogged = new LongAdder();

    /**
     * @param log      where the lines go
     * @param interval the least time between two warning lines
     */
    public ThrottledWarnings(Logger log, Duration interval) {
        this.log = log;
        this.intervalNanos = interval.toNanos();
        this.lastLogged = new AtomicLong(System.nanoTime() - 2 * intervalNanos);
    }

    /**
     * @param format an SLF4J format (no throwable among the arguments)
     * @param args   its arguments
     */
    public void warn(String format, Object... args) {
        long now = System.nanoTime();
        long before = lastLogged.get();
        if (now - before >= intervalNanos && lastLogged.compareAndSet(before, now)) {
            long more = unlogged.sumThenReset();
            if (more == 0) {
                log.warn(format, args);
            } else {
                Object[] withCount = Arrays.copyOf(args, args.length + 1);
                withCount[args.length] = more;
                log.warn(format + " (and {} more like it since the last line)", withCount);
            }
        } else {
            unlogged.increment();
            log.debug(format, args);
        }
    }
}
