package io.robomw.console.rosbridge.robot;

import java.util.concurrent.ScheduledFuture;
import java.util.concurrent.TimeUnit;

/**
 * A sample taken at a fixed rate while someone wants it ({@link #demand}): started when a topic
 * gets its first subscriber, stopped when it loses its last. A tick that throws is reported to
 * the failure policy and the next tick comes as usual (a failure the VM cannot survive ends it).
 * Ticks a loaded machine delayed are not caught up back to back: one that comes less than half a
 * period after the last is skipped, as a ROS node's timer does not burst either.
 */
final class Periodic {

    private final Threads threads;
    private final long periodNanos;
    private final Runnable tick;
    private final String what;
    private ScheduledFuture<?> running;
    /** Touched only by the ticks, which a fixed-rate schedule runs one at a time. */
    private long lastRun;
    private boolean ranOnce;

    /**
     * @param threads where it runs
     * @param hz      ticks per second
     * @param tick    the sample; must not block
     * @param what    what it samples, as failures name it ({@code rosbridge nxt odometry})
     */
    Periodic(Threads threads, double hz, Runnable tick, String what) {
        this.threads = threads;
        this.periodNanos = Math.max(1, Math.round(1e9 / hz));
        this.tick = tick;
        this.what = what;
    }

    /** @param wanted whether someone wants the samples now */
    synchronized void demand(boolean wanted) {
        if (wanted && running == null) {
            running = threads.feeds().scheduleAtFixedRate(this::run, 0, periodNanos, TimeUnit.NANOSECONDS);
        } else if (!wanted && running != null) {
            running.cancel(false);
            running = null;
        }
    }

    private void run() {
        long now = System.nanoTime();
        if (ranOnce && now - lastRun < periodNanos / 2) {
            return; // a tick the loaded machine delayed, run back to back with the next: publishing the same sample twice helps no one
        }
        ranOnce = true;
        lastRun = now;
        try {
            tick.run();
        } catch (Throwable t) {
            threads.failures().surviveOrRethrow(what, t);
        }
    }
}
