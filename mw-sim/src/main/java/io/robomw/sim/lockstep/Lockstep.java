package io.robomw.sim.lockstep;

import io.robomw.api.RobotException;

import java.util.Map;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.ConcurrentHashMap;
import java.util.concurrent.locks.LockSupport;

/**
 * Keeps simulated time and programs in step, so a fast simulation is exactly repeatable: the
 * world advances only while every registered program thread is blocked on a simulator future
 * ({@link SimFuture}) that is not yet done, or has finished. A program that computes holds time
 * still, however long it takes in wall-clock time; the same seed and the same program give the
 * same trajectory, bit for bit.
 *
 * <p>Completions that wake programs are deferred to the end of each step ({@link #defer}), so a
 * program never runs while a step is half done.
 *
 * <p>When the thread that steps the world dies ({@link #fail}), every wait on a simulator future,
 * from a registered program or from any other thread, ends at once with the failure, and so does
 * every later one: nothing waits for simulated time that will never come.
 *
 * <p>Thread-safe: program threads report blocking and waking; one driver thread (the one stepping
 * the world) waits for all of them, and alone calls {@link #beginStep} and {@link #endStep}.
 */
public final class Lockstep {

    private final Map<Thread, ProgramState> programs = new ConcurrentHashMap<>();
    /** Completions deferred to the end of the step; the worker threads add to it at once (lock-free). */
    private final java.util.Queue<Runnable> deferred = new java.util.concurrent.ConcurrentLinkedQueue<>();
    /** The simulator futures being waited on now, by any thread (so that {@link #fail} can end the waits). */
    private final java.util.Set<SimFuture<?>> waitedOn = ConcurrentHashMap.newKeySet();
    private volatile Thread driver;
    private volatile boolean stepping;
    /** Why simulated time stopped for good, once it has. */
    private volatile RobotException failure;

    /** What the driver knows of one program thread. */
    private static final class ProgramState {
        private volatile CompletableFuture<?> blockedOn;
        private volatile boolean finished;
    }

    /**
     * @param <T> the value type
     * @return a new incomplete future whose blocking waits are seen by this lockstep
     */
    public <T> SimFuture<T> newFuture() {
        return new SimFuture<>(this);
    }

    /**
     * Registers a program thread before it starts; until {@link #finished} it holds time still
     * whenever it is not blocked on a simulator future.
     *
     * @param thread the program's thread
     */
    public void register(Thread thread) {
        programs.put(thread, new ProgramState());
    }

    /**
     * Marks the calling program thread finished (call in a {@code finally} at the end of its run).
     */
    public void finished() {
        ProgramState s = programs.remove(Thread.currentThread());
        if (s != null) {
            s.finished = true;
        }
        wakeDriver();
    }

    /**
     * Marks the start of a world step on the calling thread: until {@link #endStep()}, completions
     * handed to {@link #defer} wait, so no program wakes in the middle of a step and what programs
     * do always happens between steps.
     */
    public void beginStep() {
        stepping = true;
    }

    /** Ends a step: runs the deferred completions, in the order they were deferred. */
    public void endStep() {
        stepping = false;
        for (Runnable r; (r = deferred.poll()) != null; ) {
            r.run();
        }
    }

    /**
     * Runs a completion that may wake a program: at the end of the current step when a step is under
     * way (whichever thread of the step calls it), at once otherwise.
     *
     * @param completion the completion
     */
    public void defer(Runnable completion) {
        if (stepping) {
            deferred.add(completion);
        } else {
            completion.run();
        }
    }

    /**
     * @return whether any program is registered and not finished. Looks at the programs themselves,
     *         as {@link #allWaiting} does, never at the map's size: a finishing thread's entry leaves
     *         the map before its size is counted down, and a thread held up in between (a busy
     *         machine) made the driver step on, with no program left to hold time, for as long as
     *         that thread waited for a processor (up to 7.6 simulated seconds, seen in a test).
     */
    public boolean hasPrograms() {
        for (ProgramState s : programs.values()) {
            if (!s.finished) {
                return true;
            }
        }
        return false;
    }

    /**
     * @param thread the thread that steps the world (it is woken when a program blocks); {@code null} when none
     */
    public void driver(Thread thread) {
        driver = thread;
    }

    /**
     * The calling thread is about to wait for a simulator future. Registered first, checked second
     * (as {@link #fail} sets the failure first and ends the registered waits second), so a wait
     * that begins while the world dies is ended by one or the other.
     */
    void blocking(SimFuture<?> future) {
        waitedOn.add(future);
        RobotException failed = failure;
        if (failed != null) {
            future.completeExceptionally(failed);
        }
        ProgramState s = programs.get(Thread.currentThread());
        if (s == null) {
            return;
        }
        s.blockedOn = future;
        wakeDriver();
    }

    void woke(SimFuture<?> future) {
        waitedOn.remove(future);
        ProgramState s = programs.get(Thread.currentThread());
        if (s != null) {
            s.blockedOn = null;
        }
    }

    /**
     * Simulated time has stopped for good (the thread stepping the world died): every wait on a
     * simulator future ends now with {@code why}, and every later one at once. Idempotent: the
     * first failure is kept.
     *
     * @param why the error the waiting programs get, naming what happened
     */
    public void fail(RobotException why) {
        if (failure == null) {
            failure = why;
        }
        RobotException first = failure;
        for (SimFuture<?> f : waitedOn) {
            f.completeExceptionally(first);
        }
        wakeDriver();
    }

    /** @return why simulated time stopped for good, if it did */
    public java.util.Optional<RobotException> failure() {
        return java.util.Optional.ofNullable(failure);
    }

    /**
     * @return whether the calling thread is a registered program, or the world is being stepped
     *         by some driver, so that a blocking wait on a simulator future can end
     */
    boolean canWait() {
        return failure != null || programs.containsKey(Thread.currentThread()) || driver != null;
    }

    private void wakeDriver() {
        Thread d = driver;
        if (d != null) {
            LockSupport.unpark(d);
        }
    }

    /** @return whether every program is blocked on an incomplete simulator future, or finished */
    public boolean allWaiting() {
        for (ProgramState s : programs.values()) {
            CompletableFuture<?> b = s.blockedOn;
            if (!s.finished && (b == null || b.isDone())) {
                return false;
            }
        }
        return true;
    }

    /**
     * Waits (on the driver thread) until every program is waiting or finished.
     *
     * @param stallNanos wall-clock time after which a program that neither blocks nor finishes is
     *                   reported as stuck
     * @throws RobotException naming the stuck program threads
     */
    public void awaitAllWaiting(long stallNanos) {
        long deadline = System.nanoTime() + stallNanos;
        while (!allWaiting()) {
            if (System.nanoTime() > deadline) {
                StringBuilder stuck = new StringBuilder();
                programs.forEach((t, s) -> {
                    if (!s.finished && (s.blockedOn == null || s.blockedOn.isDone())) {
                        stuck.append(' ').append(t.getName()).append(" (").append(t.getState()).append(')');
                    }
                });
                throw new RobotException("simulation stalled: program threads" + stuck + " neither finished nor waited for the robot for "
                        + stallNanos / 1_000_000_000 + " s; in a fast simulation programs must wait only on robot calls (no sleeps, no other locks)");
            }
            LockSupport.parkNanos(this, 50_000);
        }
    }
}
