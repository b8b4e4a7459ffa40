package io.robomw.agents.net;

import org.slf4j.Logger;

import java.time.Duration;
import java.util.Arrays;

/**
 * Warnings about what peers send, at most a few lines per interval: a flood of bad input must not
 * flood the log. The first warnings of an interval (its burst, one by default) are logged at once;
 * the rest of the interval's go to debug level and are counted, and the next logged line says how
 * many there were. Thread-safe.
 */
public final class ThrottledWarnings {

    private final Logger log;
    private final long intervalNanos;
    private final int burst;
    /** Guarded by this: when the current interval began, how many lines it logged, how many it did not. */
    private long intervalStart;
    private int logged;
    private long unlogged;

    /**
     * @param log      where the lines go
     * @param interval the least time between two warning lines
     */
    public ThrottledWarnings(Logger log, Duration interval) {
        this(log, interval, 1);
    }

    /**
     * @param log      where the lines go
     * @param interval how long a burst of lines lasts
     * @param burst    how many lines an interval logs at most, &gt; 0: a few distinct refusals in a
     *                 row are all told, a flood is not
     */
    public ThrottledWarnings(Logger log, Duration interval, int burst) {
        if (burst <= 0) {
            throw new IllegalArgumentException("a burst of " + burst + " warning lines per interval logs nothing; give 1 or more");
        }
        this.log = log;
        this.intervalNanos = interval.toNanos();
        this.burst = burst;
        this.intervalStart = System.nanoTime() - 2 * intervalNanos;
    }

    /**
     * @param format an SLF4J format (no throwable among the arguments)
     * @param args   its arguments
     */
    public void warn(String format, Object... args) {
        long now = System.nanoTime();
        long more;
        synchronized (this) {
            if (now - intervalStart >= intervalNanos) {
                intervalStart = now;
                logged = 0;
            }
            if (logged >= burst) {
                unlogged++;
                more = -1;
            } else {
                logged++;
                more = unlogged;
                unlogged = 0;
            }
        }
        if (more < 0) {
            log.debug(format, args);
        } else if (more == 0) {
            log.warn(format, args);
        } else {
            Object[] withCount = Arrays.copyOf(args, args.length + 1);
            withCount[args.length] = more;
            log.warn(format + " (and {} more like it since the last line)", withCount);
        }
    }
}
