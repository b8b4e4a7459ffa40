package io.robomw.api;

import java.time.Duration;
import java.util.concurrent.atomic.AtomicLong;

/**
 * A clock that moves only when told: the simulator's clock, and the clock of tests that call a
 * cycle directly. Thread-safe.
 */
public final class ManualClock implements Clock {

    private final AtomicLong nanos = new AtomicLong();

    @Override
    public long nanoTime() {
        return nanos.get();
    }

    /**
     * Moves the clock forwards.
     *
     * @param duration how far; must not be negative
     */
    public void advance(Duration duration) {
        advanceNanos(duration.toNanos());
    }

    /**
     * Moves the clock forwards.
     *
     * @param delta nanoseconds; must not be negative
     */
    public void advanceNanos(long delta) {
        if (delta < 0) {
            throw new IllegalArgumentException("a clock only moves forwards, got delta=" + delta + " ns");
        }
        nanos.addAndGet(delta);
    }
}
