package io.robomw.sim;

import java.util.concurrent.atomic.AtomicInteger;
import java.util.concurrent.atomic.AtomicReference;
import java.util.concurrent.locks.LockSupport;
import java.util.function.IntConsumer;

/**
 * Runs per-robot work of one simulation step on the calling thread and the world's worker threads
 * (named {@code sim-worker-N}), and returns when all of it is done. Work on different robots must
 * be independent; results then do not depend on the threads.
 *
 * <p>How: the calling thread (the one stepping the world) publishes the work and takes part in it.
 * Every thread claims chunks of consecutive indices from a shared counter until none are left, so a
 * worker that wakes late, or is held up by another process, simply takes fewer chunks; the caller
 * then waits only for chunks already claimed. An idle worker spins briefly before it parks (a
 * step's next batch usually follows within tens of microseconds, while waking a parked thread
 * costs about as much on a virtual machine); the caller wakes a parked worker when it publishes,
 * and a worker that finishes the last chunk wakes a parked caller. Small batches run on the
 * calling thread alone, where handing them over would cost more than it saves.
 *
 * <p>Not for concurrent use: one thread calls {@link #forEach} at a time (the stepping thread).
 */
public final class Parallel implements AutoCloseable {

    /** Below this many items a batch runs on the calling thread. */
    private static final int MIN_PARALLEL = 64;
    /**
     * Chunks per participating thread: small, so that the caller seldom waits long for a chunk a
     * worker claimed last (or a worker another process holds up), and still a few dozen robots each,
     * so claiming costs nothing to speak of.
     */
    private static final int CHUNKS_PER_THREAD = 32;
    /**
     * {@link Thread#onSpinWait()} rounds an idle worker spins before it parks: about 50 µs (a
     * round is 50 ns on the project's machine), enough for the gaps within a step (the range
     * index, the hand-over of completions), not for dyn4j's step, during which it parks. A longer
     * spin is free on an idle machine but takes processor time from everything else on a loaded
     * one (spinning through dyn4j's step made a loaded machine's samples 2-4 times slower).
     */
    private static final int WORKER_SPINS = 1 << 10;
    /** Rounds the caller spins for the last claimed chunks before it parks (about 25 µs). */
    private static final int CALLER_SPINS = 1 << 9;

    private final int threads;
    private final Worker[] workers;
    /** The batch being worked on, or the last one; workers compare it with the last they took part in. */
    private volatile Batch batch;
    private volatile boolean closed;

    /** One call of {@link #forEach}: its items, the claim counter and what is left to do. */
    private static final class Batch {
        private final IntConsumer body;
        private final int n;
        private final int chunk;
        private final AtomicInteger next = new AtomicInteger();
        /** Items not yet done; the thread that brings it to 0 wakes the caller if it waits. */
        private final AtomicInteger left;
        private final AtomicReference<Throwable> failure = new AtomicReference<>();
        private final Thread caller;
        private volatile boolean callerParked;

        Batch(IntConsumer body, int n, int chunk, Thread caller) {
            this.body = body;
            this.n = n;
            this.chunk = chunk;
            this.left = new AtomicInteger(n);
            this.caller = caller;
        }

        /** Claims and runs chunks until none are left. */
        void work() {
            int from;
            while ((from = next.getAndAdd(chunk)) < n) {
                int to = Math.min(n, from + chunk);
                try {
                    for (int i = from; i < to; i++) {
                        body.accept(i);
                    }
                } catch (Throwable t) {
                    failure.compareAndSet(null, t);
                } finally {
                    if (left.addAndGet(from - to) == 0 && callerParked) {
                        LockSupport.unpark(caller);
                    }
                }
            }
        }

        /** On the caller: waits until every claimed chunk is done. */
        void await() {
            for (int spin = 0; left.get() != 0; spin++) {
                if (spin < CALLER_SPINS) {
                    Thread.onSpinWait();
                } else {
                    callerParked = true;
                    if (left.get() != 0) {
                        LockSupport.park(this);
                    }
                    callerParked = false;
                }
            }
        }
    }

    /** A worker thread: takes part in every batch published after it went idle. */
    private final class Worker implements Runnable {
        private final Thread thread;
        private volatile boolean parked;

        Worker(int number) {
            thread = new Thread(this, "sim-worker-" + number);
            thread.setDaemon(true);
        }

        @Override
        public void run() {
            Batch done = null;
            int spin = 0;
            while (!closed) {
                Batch b = batch;
                if (b != null && b != done) {
                    done = b;
                    b.work();
                    spin = 0;
                } else if (spin < WORKER_SPINS) {
                    spin++;
                    Thread.onSpinWait();
                } else {
                    parked = true;
                    if (batch == done && !closed) {
                        LockSupport.park(Parallel.this);
                    }
                    parked = false;
                    spin = 0;
                }
            }
        }

        void wake() {
            if (parked) {
                LockSupport.unpark(thread);
            }
        }
    }

    /**
     * @param threads threads that work on a batch, the calling thread included; 1 runs everything
     *                on the calling thread
     */
    public Parallel(int threads) {
        this.threads = Math.max(1, threads);
        this.workers = new Worker[this.threads - 1];
        for (int i = 0; i < workers.length; i++) {
            workers[i] = new Worker(i + 1);
            workers[i].thread.start();
        }
    }

    /** @return the threads that work on a batch, the calling thread included */
    public int threads() {
        return threads;
    }

    /**
     * Calls {@code body} for every index in [0, n), in parallel when worth it, and returns when
     * every call has returned. If calls throw, the first throwable is rethrown (the other chunks
     * still run).
     *
     * @param n    the number of items
     * @param body the work for one item
     */
    public void forEach(int n, IntConsumer body) {
        if (workers.length == 0 || n < MIN_PARALLEL || closed) {
            for (int i = 0; i < n; i++) {
                body.accept(i);
            }
            return;
        }
        int chunk = Math.max(1, n / (threads * CHUNKS_PER_THREAD));
        Batch b = new Batch(body, n, chunk, Thread.currentThread());
        batch = b;
        for (Worker w : workers) {
            w.wake();
        }
        b.work();
        b.await();
        Throwable t = b.failure.get();
        if (t instanceof RuntimeException r) {
            throw r;
        }
        if (t instanceof Error e) {
            throw e;
        }
        if (t != null) {
            throw new IllegalStateException(t);
        }
    }

    /** Stops the worker threads. */
    @Override
    public void close() {
        closed = true;
        for (Worker w : workers) {
            LockSupport.unpark(w.thread);
        }
    }
}
