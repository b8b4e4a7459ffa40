package io.robomw.platform;

import io.robomw.api.Clock;
import org.slf4j.Logger;

import java.time.Duration;
import java.util.Arrays;
import java.util.concurrent.atomic.AtomicLong;
import java.util.concurrent.atomic.LongAdder;

/**
 * Warnings about bad input (a brick's refusals, garbage on an emulator's link), at most one line
 * per interval: a flood of them must not flood the log. The first warning is logged at once; those within the interval after it go to
 * debug level and are counted, and the next logged line says how many there were. Thread-safe.
 * (The messaging layer has its own, in {@code mw-agents}, which may not depend on this module.)
 */
public final class ThrottledWarnings {

    private final Logger log;
    private final Clock clock;
    private final long intervalNanos;
    private final AtomicLong lastLogged;
    private final LongAdder unlogged = new LongAdder();

    /**
     * @param log      where the lines go
     * @param interval the least time between two warning lines
     * @param clock    the time the interval is measured in (the platform's injected clock)
     */
    public ThrottledWarnings(Logger log, Duration interval, Clock clock) {
        this.log = log;
        this.clock = clock;
        this.intervalNanos = interval.toNanos();
        this.lastLogged = new AtomicLong(clock.nanoTime() - 2 * intervalNanos);
    }

    /**
     * @param format an SLF4J format (no throwable among the arguments)
     * @param args   its arguments
     */
    public void warn(String format, Object... args) {
        long now = clock.nanoTime();
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
