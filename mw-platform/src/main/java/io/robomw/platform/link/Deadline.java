package io.robomw.platform.link;

import java.time.Duration;
import java.util.Objects;

/**
 * A point in time on {@link System#nanoTime()}, computed once from a timeout so that a loop of
 * partial reads shares one deadline. I/O deadlines are always wall-clock time, never a simulated
 * {@link io.robomw.api.Clock}.
 */
final class Deadline {

    /** Timeouts are capped here (about 73 years) so that adding them to nanoTime cannot overflow. */
    private static final long MAX_NANOS = Long.MAX_VALUE / 4;

    private final long deadlineNanos;

    private Deadline(long deadlineNanos) {
        this.deadlineNanos = deadlineNanos;
    }

    /**
     * @param timeout how long from now; zero means "only what is already there"
     * @return the deadline
     * @throws IllegalArgumentException if the timeout is negative
     */
    static Deadline after(Duration timeout) {
        Objects.requireNonNull(timeout, "timeout");
        if (timeout.isNegative()) {
            throw new IllegalArgumentException("timeout must not be negative, timeout=" + timeout);
        }
        long nanos = timeout.compareTo(Duration.ofNanos(MAX_NANOS)) > 0 ? MAX_NANOS : timeout.toNanos();
        return new Deadline(System.nanoTime() + nanos);
    }

    /** @return nanoseconds left, never negative */
    long remainingNanos() {
        return Math.max(0, deadlineNanos - System.nanoTime());
    }

    /** @return whether the deadline has passed */
    boolean expired() {
        return deadlineNanos - System.nanoTime() <= 0;
    }

    /** @return milliseconds left rounded up (so a wait never ends early), at most {@code Integer.MAX_VALUE} */
    int remainingMillisRoundedUp() {
        return millisRoundedUp(remainingNanos());
    }

    /**
     * @param nanos a non-negative duration in nanoseconds
     * @return it in milliseconds rounded up, at most {@code Integer.MAX_VALUE}
     */
    static int millisRoundedUp(long nanos) {
        long millis = nanos / 1_000_000 + (nanos % 1_000_000 == 0 ? 0 : 1);
        return (int) Math.min(Integer.MAX_VALUE, millis);
    }

    /**
     * @param timeout a timeout
     * @return it for messages, e.g. {@code "200 ms"}
     */
    static String format(Duration timeout) {
        return timeout.toMillis() + " ms";
    }
}
