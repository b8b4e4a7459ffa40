package io.robomw.api.spi;

import java.util.Objects;
import java.util.concurrent.atomic.LongAdder;

/**
 * The one policy for whatever an <em>owner thread</em> catches: a thread that owns motors, a
 * link, agents, a file watch or a simulation's clock (after Agrona's {@code ErrorHandler} and
 * error counter, which its {@code AgentRunner} is given). Every owner thread catches
 * {@link Throwable} in one place and hands it here, instead of a catch list of its own:
 * <ul>
 *   <li>a failure it can survive ({@link #survivable}): one unit of its work failed (a command's
 *   action, one link service, one file event, one agent's callback); the thread reports it with
 *   {@link #survived}, ends that unit (a command fails with it), and goes on;</li>
 *   <li>any other ({@link VirtualMachineError}s but {@link StackOverflowError}: out of memory, an
 *   internal error of the VM): the thread stops its motors (hands the last stop to its link), ends
 *   every command it holds with an error naming it, reports it with {@link #died}, and ends
 *   cleanly; later commands fail at once saying why.</li>
 * </ul>
 * A thread ended on purpose (closed, interrupted while closing) reports nothing.
 *
 * <p>Programs that compose a robot, a host or a simulation inject one policy into all of them
 * ({@link PlatformConfig#failures()}), so one counter and one report see every owner thread of
 * the process; {@link #logging()} is the default. Implementations are thread-safe and must not
 * throw.
 */
public interface FailurePolicy {

    /**
     * A failure the owner thread survived: one unit of its work ended with it, the thread goes on.
     *
     * @param owner   the owner thread's role, as its name gives it ({@code nxt-1-action})
     * @param failure what was thrown
     */
    void survived(String owner, Throwable failure);

    /**
     * The owner thread is ending because of a failure it cannot survive; it has stopped what it
     * owns (its motors, its link) as far as it could.
     *
     * @param owner   the owner thread's role
     * @param failure what was thrown
     */
    void died(String owner, Throwable failure);

    /** @return failures reported so far, survived or not (the error counter) */
    long count();

    /**
     * @param failure something an owner thread caught
     * @return whether the thread may go on after it: everything but the VM's own errors
     *         ({@link VirtualMachineError}, except {@link StackOverflowError}, which one unit of
     *         work can cause and which unwinds cleanly)
     */
    static boolean survivable(Throwable failure) {
        return !(failure instanceof VirtualMachineError) || failure instanceof StackOverflowError;
    }

    /**
     * For code that handles one unit of work's failure itself (fails a command with it): reports
     * it if survivable, and re-throws it otherwise, so the owner thread's loop ends.
     *
     * @param owner   the owner thread's role
     * @param failure what was thrown
     * @throws VirtualMachineError the failure itself, if it is not survivable
     */
    default void surviveOrRethrow(String owner, Throwable failure) {
        if (!survivable(failure)) {
            throw (VirtualMachineError) failure;
        }
        survived(owner, failure);
    }

    /**
     * The default policy: counts, and logs through {@link System.Logger} (which the distribution
     * routes to SLF4J): a survived failure with its stack trace the first time and then at every
     * power of two of the count (a failure repeated every cycle does not flood the log; the count
     * says how many), the rest at debug level; a death always, at error level.
     *
     * @return a new logging policy with its own counter
     */
    static FailurePolicy logging() {
        return new Logging(System.getLogger(FailurePolicy.class.getName()));
    }

    /** The default policy: counts, and logs through {@link System.Logger}. */
    final class Logging implements FailurePolicy {

        private final System.Logger log;
        private final LongAdder count = new LongAdder();
        private final LongAdder survivedCount = new LongAdder();

        /**
         * @param log where the lines go
         */
        public Logging(System.Logger log) {
            this.log = Objects.requireNonNull(log, "log");
        }

        @Override
        public void survived(String owner, Throwable failure) {
            count.increment();
            survivedCount.increment();
            long n = survivedCount.sum();
            try {
                if (Long.bitCount(n) == 1) {
                    log.log(System.Logger.Level.ERROR, owner + ": " + failure + " (" + n + " survived failures so far in this process)", failure);
                } else {
                    log.log(System.Logger.Level.DEBUG, owner + ": " + failure);
                }
            } catch (Throwable ignored) {
                // logging itself failed (out of memory): the count still says it happened
            }
        }

        @Override
        public void died(String owner, Throwable failure) {
            count.increment();
            try {
                log.log(System.Logger.Level.ERROR, owner + ": the thread died of " + failure
                        + "; what it owned was stopped and its commands failed", failure);
            } catch (Throwable ignored) {
                // logging itself failed (out of memory): the count still says it happened
            }
        }

        @Override
        public long count() {
            return count.sum();
        }
    }
}
