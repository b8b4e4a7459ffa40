package io.robomw.api;

/**
 * The source of time for everything that runs in cycles. Real robots use {@link #system()};
 * a simulation steps a {@link ManualClock}, so a run can go faster than real time and repeat
 * exactly.
 */
public interface Clock {

    /** @return nanoseconds from an arbitrary origin, never decreasing */
    long nanoTime();

    /** @return the wall clock ({@link System#nanoTime()}) */
    static Clock system() {
        return SystemClock.INSTANCE;
    }

    /** The wall clock; stateless. */
    enum SystemClock implements Clock {
        /** The one instance. */
        INSTANCE;

        @Override
        public long nanoTime() {
            return System.nanoTime();
        }
    }
}
