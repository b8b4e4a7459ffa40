package io.robomw.api.spi;

import io.robomw.api.Clock;

import java.time.Duration;
import java.util.Objects;
import java.util.concurrent.locks.LockSupport;

/**
 * How an {@link OwnerThread} waits between two rounds of its work (after Agrona's
 * {@code IdleStrategy}): fed by the work count each round returns, so a thread with work keeps its
 * pace and a thread without any waits longer. An {@link OwnerThread#wake() unpark} of the thread
 * ends a wait for work early (a command was submitted).
 *
 * <p>Called only on the owner thread.
 */
@FunctionalInterface
public interface IdleStrategy {

    /**
     * Waits after a round of work.
     *
     * @param workCount what the round did; 0 when there was nothing to do
     */
    void idle(int workCount);

    /**
     * A fixed-rate loop that sleeps while it has nothing to do, as an execution action thread
     * cycles: after a round with work, it waits until the next period boundary (missed boundaries
     * are dropped, not caught up, and an unpark does not shorten it: the pace is the period); after
     * a round without work, it waits until the thread is woken, at most {@code idleWait}, and the
     * next round starts a new period at once.
     *
     * @param clock    the time periods are measured in (an injected wall clock)
     * @param period   the period of rounds with work, &gt; 0
     * @param idleWait the longest wait after a round without work, &gt; 0
     * @return a new strategy (it keeps the next boundary: one per thread)
     */
    static IdleStrategy periodic(Clock clock, Duration period, Duration idleWait) {
        return new Periodic(clock, period, idleWait, false);
    }

    /**
     * {@link #periodic}, except that an unpark ends any wait, with work or without: for a thread
     * that another one hands work to and that should take it at once (a link thread, woken when
     * the action thread publishes new motor states), while still coming round once a period on its
     * own (to poll) while it has work.
     *
     * @param clock    the time periods are measured in
     * @param period   the period of rounds with work, &gt; 0
     * @param idleWait the longest wait after a round without work, &gt; 0
     * @return a new strategy (one per thread)
     */
    static IdleStrategy wakeable(Clock clock, Duration period, Duration idleWait) {
        return new Periodic(clock, period, idleWait, true);
    }

    /** {@link IdleStrategy#periodic} and {@link IdleStrategy#wakeable}. */
    final class Periodic implements IdleStrategy {

        private final Clock clock;
        private final long periodNanos;
        private final long idleWaitNanos;
        private final boolean wakeable;
        /** The next period boundary, or {@link Long#MIN_VALUE} when the last round had no work. */
        private long next = Long.MIN_VALUE;

        private Periodic(Clock clock, Duration period, Duration idleWait, boolean wakeable) {
            this.wakeable = wakeable;
            this.clock = Objects.requireNonNull(clock, "clock");
            this.periodNanos = period.toNanos();
            this.idleWaitNanos = idleWait.toNanos();
            if (periodNanos <= 0 || idleWaitNanos <= 0) {
                throw new IllegalArgumentException("period and idleWait must be > 0, got " + period + " and " + idleWait);
            }
        }

        @Override
        public void idle(int workCount) {
            if (workCount <= 0) {
                next = Long.MIN_VALUE;
                LockSupport.parkNanos(this, idleWaitNanos);
                return;
            }
            long now = clock.nanoTime();
            next = next == Long.MIN_VALUE ? now + periodNanos : next + periodNanos;
            if (next < now) {
                next = now; // overran: start the next round now, without catching up
            }
            for (long left = next - now; left > 0; left = next - clock.nanoTime()) {
                LockSupport.parkNanos(this, left);
                if (wakeable || Thread.currentThread().isInterrupted()) {
                    return; // woken with work, or closing: the loop looks at its flag
                }
            }
        }
    }
}
