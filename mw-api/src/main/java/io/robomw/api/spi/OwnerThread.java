package io.robomw.api.spi;

import java.nio.channels.ClosedByInterruptException;
import java.util.Objects;
import java.util.concurrent.atomic.AtomicBoolean;
import java.util.concurrent.locks.LockSupport;

/**
 * Runs a {@link Duty} on a named thread of its own, as Agrona's {@code AgentRunner} runs an
 * agent: {@code idleStrategy.idle(duty.doWork())} until closed, every {@link Throwable} caught in
 * this one place and handed to the injected {@link FailurePolicy}. A survivable failure of one
 * round is reported and the loop goes on; any other ends the thread cleanly: the duty's
 * {@link Duty#onDeath} stops what it owns (a motor platform hands its last stop to its link), the
 * policy is told, and {@link Duty#onClose} runs, so no owner thread dies silently.
 *
 * <p>Thread-safe. Start it once; {@link #close()} it once (later calls do nothing).
 */
public final class OwnerThread implements AutoCloseable {

    /** How long {@link #close()} joins the thread before it interrupts it and joins again. */
    private static final long CLOSE_JOIN_MILLIS = 1_000;

    /**
     * The work of an owner thread; every method is called on that thread only, one at a time.
     */
    public interface Duty {

        /**
         * Does one round of work. It may block, with a deadline.
         *
         * @return how much it did; 0 when there was nothing to do (the idle strategy waits longer)
         * @throws Exception what one round can fail with; reported, and the loop goes on
         */
        int doWork() throws Exception;

        /**
         * The thread is dying of a failure it cannot survive: stop what it owns (motors, a link)
         * and fail what waits on it. Must not throw; the default does nothing.
         *
         * @param failure what killed it
         */
        default void onDeath(Throwable failure) {
        }

        /** The thread is ending (closed, or after {@link #onDeath}); the default does nothing. */
        default void onClose() {
        }
    }

    private final String role;
    private final Duty duty;
    private final IdleStrategy idle;
    private final FailurePolicy failures;
    private final Thread thread;
    private final AtomicBoolean closed = new AtomicBoolean();
    private volatile boolean running = true;
    private volatile Throwable death;

    private OwnerThread(String role, int priority, Duty duty, IdleStrategy idle, FailurePolicy failures) {
        this.role = Objects.requireNonNull(role, "role");
        this.duty = Objects.requireNonNull(duty, "duty");
        this.idle = Objects.requireNonNull(idle, "idle");
        this.failures = Objects.requireNonNull(failures, "failures");
        this.thread = new Thread(this::run, role);
        thread.setDaemon(true);
        thread.setPriority(priority);
    }

    /**
     * Starts a duty on a daemon thread named {@code role}.
     *
     * @param role     the thread's name, which failures are reported under ({@code nxt-1-action})
     * @param priority the thread's priority ({@link Thread#NORM_PRIORITY}, or
     *                 {@link Thread#MAX_PRIORITY} for a real-time loop)
     * @param duty     its work
     * @param idle     how it waits between rounds
     * @param failures where what it catches goes
     * @return the started thread's runner
     */
    public static OwnerThread start(String role, int priority, Duty duty, IdleStrategy idle, FailurePolicy failures) {
        OwnerThread t = new OwnerThread(role, priority, duty, idle, failures);
        t.thread.start();
        return t;
    }

    private void run() {
        Throwable fatal = null;
        try {
            while (running) {
                int work;
                try {
                    work = duty.doWork();
                } catch (Throwable t) {
                    if (!running && endsOnPurpose(t)) {
                        break;
                    }
                    if (!FailurePolicy.survivable(t)) {
                        fatal = t;
                        break;
                    }
                    failures.survived(role, t);
                    work = 0;
                }
                idle.idle(work);
            }
        } catch (Throwable t) {
            fatal = t; // the idle strategy or the policy failed: nothing is left to trust
        }
        if (fatal != null) {
            death = fatal;
            running = false;
            try {
                duty.onDeath(fatal);
            } catch (Throwable ignored) {
                // onDeath must not throw; the policy below still hears of the death
            }
            failures.died(role, fatal);
        }
        try {
            duty.onClose();
        } catch (Throwable t) {
            if (FailurePolicy.survivable(t)) {
                failures.survived(role, t);
            }
        }
    }

    private static boolean endsOnPurpose(Throwable t) {
        return t instanceof InterruptedException || t instanceof ClosedByInterruptException || Thread.currentThread().isInterrupted();
    }

    /** @return the thread's name, its role */
    public String role() {
        return role;
    }

    /** Wakes the thread from an idle wait (work was handed to it). */
    public void wake() {
        LockSupport.unpark(thread);
    }

    /** @return whether the caller is this owner thread */
    public boolean isCurrentThread() {
        return Thread.currentThread() == thread;
    }

    /** @return whether the thread is still running its loop */
    public boolean running() {
        return running && thread.isAlive();
    }

    /** @return what killed the thread, if a failure it could not survive did */
    public java.util.Optional<Throwable> death() {
        return java.util.Optional.ofNullable(death);
    }

    /**
     * Stops the loop and waits until the thread has really ended, as Agrona's
     * {@code AgentRunner.close} does: wakes it, joins, and while it has not ended (a round blocked
     * on something) interrupts it and joins again, a second at a time, saying so every five
     * seconds. Called on the thread itself, it only stops the loop. Idempotent.
     */
    @Override
    public void close() {
        running = false;
        if (!closed.compareAndSet(false, true) || Thread.currentThread() == thread) {
            return;
        }
        boolean interrupted = false;
        long waited = 0;
        while (thread.isAlive()) {
            LockSupport.unpark(thread);
            try {
                thread.join(CLOSE_JOIN_MILLIS);
            } catch (InterruptedException e) {
                interrupted = true;
            }
            if (thread.isAlive()) {
                waited += CLOSE_JOIN_MILLIS;
                thread.interrupt();
                if (waited % 5_000 == 0) {
                    System.getLogger(OwnerThread.class.getName()).log(System.Logger.Level.WARNING,
                            role + ": still waiting for the thread to end (" + waited + " ms so far)");
                }
            }
        }
        if (interrupted) {
            Thread.currentThread().interrupt();
        }
    }
}
