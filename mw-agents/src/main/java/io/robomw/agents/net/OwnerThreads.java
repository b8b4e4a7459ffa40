package io.robomw.agents.net;

import io.robomw.api.spi.FailurePolicy;

import java.util.Objects;
import java.util.concurrent.ThreadFactory;
import java.util.concurrent.atomic.AtomicInteger;

/**
 * The owner threads of hosts and messaging nodes (agent runners, accept, read and write loops,
 * deliveries, watchers): named daemon threads, each with one catch for whatever ends it, handed to
 * the injected {@link FailurePolicy}, so none dies silently and one counter sees them all. A loop
 * handles the failure of one unit of its work itself (a frame, a connection, an agent's callback)
 * ({@link FailurePolicy#surviveOrRethrow}); what escapes the loop ends the thread and is reported as its death.
 *
 * <p>For loops that are not an {@link io.robomw.api.spi.OwnerThread.Duty}: they block on sockets
 * or on a pool's queue rather than cycle.
 */
public final class OwnerThreads implements ThreadFactory {

    private final String prefix;
    private final FailurePolicy failures;
    private final AtomicInteger numbers = new AtomicInteger();

    /**
     * @param prefix   the threads' names, numbered from 1: {@code prefix-1}, {@code prefix-2}...
     * @param failures where what ends a thread goes
     */
    public OwnerThreads(String prefix, FailurePolicy failures) {
        this.prefix = Objects.requireNonNull(prefix, "prefix");
        this.failures = Objects.requireNonNull(failures, "failures");
    }

    @Override
    public Thread newThread(Runnable loop) {
        return thread(prefix + "-" + numbers.incrementAndGet(), loop, failures);
    }

    /**
     * @param name     the thread's name, which its failures are reported under
     * @param loop     what it runs
     * @param failures where what ends it goes
     * @return a daemon thread, not started, that reports whatever its loop lets escape as its
     *         death ({@link FailurePolicy#died}) and ends
     */
    public static Thread thread(String name, Runnable loop, FailurePolicy failures) {
        Objects.requireNonNull(loop, "loop");
        Objects.requireNonNull(failures, "failures");
        Thread t = new Thread(() -> {
            try {
                loop.run();
            } catch (Throwable e) {
                failures.died(Thread.currentThread().getName(), e);
            }
        }, name);
        t.setDaemon(true);
        return t;
    }

    /**
     * The rounds of a periodic task on a scheduled executor, whose future would keep a failure to
     * itself and cancel the task without a word: a survivable failure of a round is reported and
     * the next round comes; any other is reported as the thread's death and ends the task.
     *
     * @param failures where a failure goes
     * @param round    one round
     * @return the task to schedule
     */
    public static Runnable rounds(FailurePolicy failures, Runnable round) {
        Objects.requireNonNull(failures, "failures");
        Objects.requireNonNull(round, "round");
        return () -> {
            try {
                round.run();
            } catch (Throwable e) {
                if (!FailurePolicy.survivable(e)) {
                    failures.died(current(), e);
                    throw e;
                }
                failures.survived(current(), e);
            }
        };
    }

    /**
     * Re-throws a failure no thread survives, and does nothing with any other: for a loop that
     * handles expected failures of a unit of work (a peer that does not answer) itself, without
     * reporting them as failures.
     *
     * @param failure what was thrown
     * @throws VirtualMachineError the failure, if it is not survivable
     */
    public static void rethrowFatal(Throwable failure) {
        if (!FailurePolicy.survivable(failure)) {
            throw (VirtualMachineError) failure;
        }
    }

    /** @return the calling thread's name, the owner its failures are reported under */
    public static String current() {
        return Thread.currentThread().getName();
    }
}
