package io.robomw.platform.link;

import io.robomw.api.Clock;

import java.time.Duration;
import java.util.Objects;

/**
 * A point in time on a {@link Clock}, computed once from a timeout so that a loop of partial reads
 * (or of polls of a brick) shares one deadline. I/O deadlines are on the wall clock
 * ({@link Clock#system()}, the default): a link's bytes take real time even when the robot runs in
 * a simulation; a driver whose wait depends on the robot's own time gives its platform's clock.
 */
public final class Deadline {

    /** Timeouts are capped here (about 73 years) so that adding them to nanoTime cannot overflow. */
    private static final long MAX_NANOS = Long.MAX_VALUE / 4;

    private final Clock clock;
    private final long deadlineNanos;

    private Deadline(Clock clock, long deadlineNanos) {
        this.clock = clock;
        this.deadlineNanos = deadlineNanos;
    }

    /**
     * @param timeout how long from now; zero means "only what is already there"
     * @return the deadline
     * @throws IllegalArgumentException if the timeout is negative
     */
    public static Deadline after(Duration timeout) {
        return after(Clock.system(), timeout);
    }

    /**
     * @param clock   the clock it is on
     * @param timeout how long from now; zero means "only what is already there"
     * @return the deadline
     * @throws IllegalArgumentException if the timeout is negative
     */
    public static Deadline after(Clock clock, Duration timeout) {
        Objects.requireNonNull(clock, "clock");
        Objects.requireNonNull(timeout, "timeout");
        if (timeout.isNegative()) {
            throw new IllegalArgumentException("timeout must not be negative, timeout=" + timeout);
        }
        long nanos = timeout.compareTo(Duration.ofNanos(MAX_NANOS)) > 0 ? MAX_NANOS : timeout.toNanos();
        return new Deadline(clock, clock.nanoTime() + nanos);
    }

    /** @return nanoseconds left, never negative */
    public long remainingNanos() {
        return Math.max(0, deadlineNanos - clock.nanoTime());
    }

    /** @return the time left, never negative */
    public Duration remaining() {
        return Duration.ofNanos(remainingNanos());
    }

    /** @return whether the deadline has passed */
    public boolean expired() {
        return deadlineNanos - clock.nanoTime() <= 0;
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
