package io.robomw.sim;

import java.lang.invoke.MethodHandles;
import java.lang.invoke.VarHandle;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicInteger;
import java.util.concurrent.locks.LockSupport;
import java.util.concurrent.locks.ReentrantLock;
import java.util.function.IntConsumer;

/**
 * Runs per-robot work of one simulation step on the simulation's worker threads (named
 * {@code sim-worker-N}), split into contiguous index ranges that the workers claim in turn, and
 * waits for all of it (the calling thread blocks: it does not take a share itself, which on a
 * loaded machine costs it its place with the scheduler; see docs/benchmarks.md). Work on
 * different robots must be independent; results then do not depend on the threads. Small batches
 * run on the calling thread, where handing them over would cost more than it saves.
 *
 * <p>How work is handed over: the workers are this class's own threads, not a pool's. A pass is
 * published in a few fields and a generation number; each worker, between passes, watches the
 * generation for a few microseconds ({@link #SPIN_NANOS}: the stepping thread's serial work
 * between two passes of one step is often shorter than a thread's wake-up) and then parks until
 * the caller unparks it. The work is split into many small ranges (about
 * {@value #CHUNKS_PER_THREAD} a worker), and each worker has a region of them, the same at every pass:
 * it claims its own from the front, and then the others' from their backs. A robot is then handled
 * by the same worker pass after pass (its data stays in that processor's caches: with the ranges
 * dealt from one counter, half of them moved between the processors at every pass, 10-25 % more
 * processor time a step at 10,000 robots in two A/B pairs on a loaded machine), and the workers still end a pass within a
 * small range of each other whatever else the machine runs. The last worker to finish unparks the
 * caller. A pass allocates nothing.
 */
public final class Parallel implements AutoCloseable {

    private static final int MIN_PARALLEL = 64;
    /** Ranges a pass is split into, per worker: the workers finish within one range of each other. */
    private static final int CHUNKS_PER_THREAD = 32;
    /** The fewest items a range of {@link #forEach} holds (claiming one is an atomic increment). */
    private static final int MIN_CHUNK = 32;
    /**
     * How long a worker watches for the next pass before it parks, nanoseconds: a few microseconds, bounded, so that a
     * loaded machine loses little to it (a worker that spins takes a processor from whatever else would run).
     */
    private static final long SPIN_NANOS = 5_000;
    /** How often the waiting caller checks that the workers are still alive, nanoseconds. */
    private static final long LIVENESS_CHECK_NANOS = TimeUnit.MILLISECONDS.toNanos(100);

    private final int threads;
    private final Worker[] workers;
    /** One pass at a time: a second caller waits for the first's pass to end. */
    private final ReentrantLock passes = new ReentrantLock();

    // the pass being run: written by the caller before it bumps the generation, read by the workers after they see it
    private IntConsumer body;
    private int items;
    private int chunks;
    private volatile int generation;
    private volatile boolean closed;
    /**
     * Per worker, its region of the pass: the ranges it takes first, from the front, so that a robot is handled by the
     * same worker pass after pass (its data stays in that processor's caches), while the others take what is left at
     * the back once theirs are done.
     */
    private final Region[] regions;
    /** Workers still working on the pass. */
    private final AtomicInteger working = new AtomicInteger();
    /** The caller waiting for the pass. */
    private volatile Thread waiter;
    /** The first failure of the pass, rethrown by the caller. */
    private volatile Throwable failure;

    /**
     * @param threads worker threads; 1 runs everything on the calling thread
     */
    public Parallel(int threads) {
        this.threads = Math.max(1, threads);
        this.workers = new Worker[this.threads == 1 ? 0 : this.threads];
        this.regions = new Region[workers.length];
        for (int t = 0; t < workers.length; t++) {
            regions[t] = new Region();
        }
        for (int t = 0; t < workers.length; t++) {
            workers[t] = new Worker(this, t, "sim-worker-" + (t + 1));
            workers[t].setDaemon(true);
            workers[t].start();
        }
    }

    /**
     * Calls {@code body} for every index in [0, n), in parallel when worth it.
     *
     * @param n    the number of items
     * @param body the work for one item
     */
    public void forEach(int n, IntConsumer body) {
        if (workers.length == 0 || n < MIN_PARALLEL || onOwnWorker()) {
            for (int i = 0; i < n; i++) {
                body.accept(i);
            }
            return;
        }
        run(n, Math.max(1, Math.min(threads * CHUNKS_PER_THREAD, n / MIN_CHUNK)), body);
    }

    /**
     * Calls {@code batch} for every batch number in [0, batches), in parallel whenever there are
     * worker threads and more than one batch (the caller sized each batch to be worth a hand-over).
     *
     * @param batches the number of batches
     * @param batch   the work for one batch
     */
    public void forEachBatch(int batches, IntConsumer batch) {
        if (workers.length == 0 || batches < 2 || onOwnWorker()) {
            for (int i = 0; i < batches; i++) {
                batch.accept(i);
            }
            return;
        }
        run(batches, Math.min(threads * CHUNKS_PER_THREAD, batches), batch);
    }

    private void run(int n, int chunkCount, IntConsumer work) {
        passes.lock();
        try {
            if (closed) {
                throw new IllegalStateException("the simulation's worker threads were stopped");
            }
            body = work;
            items = n;
            chunks = chunkCount;
            failure = null;
            for (int r = 0; r < regions.length; r++) {
                // region r: ranges [c * r / T, c * (r + 1) / T), worker r's own
                long front = (long) chunkCount * r / regions.length;
                long back = (long) chunkCount * (r + 1) / regions.length;
                regions[r].range = (front << 32) | back;
            }
            working.set(workers.length);
            Thread me = Thread.currentThread();
            waiter = me;
            generation++; // publishes the fields above
            for (Worker w : workers) {
                LockSupport.unpark(w);
            }
            boolean interrupted = false;
            long checked = System.nanoTime();
            while (working.get() != 0) {
                LockSupport.parkNanos(this, LIVENESS_CHECK_NANOS);
                if (Thread.interrupted()) {
                    interrupted = true; // the workers are in the middle of the pass: it ends first
                }
                long now = System.nanoTime();
                if (now - checked >= LIVENESS_CHECK_NANOS && working.get() != 0) {
                    checked = now;
                    for (Worker w : workers) {
                        if (!w.isAlive()) {
                            throw new IllegalStateException("simulation worker thread " + w.getName() + " ended in the middle of a pass");
                        }
                    }
                }
            }
            waiter = null;
            body = null;
            Throwable t = failure;
            failure = null;
            if (interrupted) {
                me.interrupt();
                throw new IllegalStateException("interrupted during a simulation step");
            }
            if (t instanceof RuntimeException r) {
                throw r;
            }
            if (t instanceof Error err) {
                throw err;
            }
            if (t != null) {
                throw new IllegalStateException(t);
            }
        } finally {
            passes.unlock();
        }
    }

    /**
     * Worker {@code w}'s share of the pass of the generation it saw: the ranges of its own region from its front, then
     * the other regions' ranges from their backs (what a slower or descheduled worker has not reached yet).
     */
    private void work(int w) {
        IntConsumer b = body;
        int n = items;
        int c = chunks;
        try {
            for (int k; (k = claimFront(w)) >= 0; ) {
                runChunk(b, n, c, k);
            }
            for (int d = 1; d < regions.length; d++) {
                int r = (w + d) % regions.length;
                for (int k; (k = claimBack(r)) >= 0; ) {
                    runChunk(b, n, c, k);
                }
            }
        } catch (Throwable t) {
            if (failure == null) {
                failure = t; // the first wins; the other workers claim what is left
            }
        } finally {
            if (working.decrementAndGet() == 0) {
                LockSupport.unpark(waiter);
            }
        }
    }

    private static void runChunk(IntConsumer b, int n, int c, int k) {
        int from = (int) ((long) n * k / c);
        int to = (int) ((long) n * (k + 1) / c);
        for (int i = from; i < to; i++) {
            b.accept(i);
        }
    }

    /** @return the next range at the front of region {@code r}, or -1 if none is left */
    private int claimFront(int r) {
        Region region = regions[r];
        while (true) {
            long v = region.range;
            int front = (int) (v >>> 32);
            int back = (int) v;
            if (front >= back) {
                return -1;
            }
            if (region.claim(v, ((long) (front + 1) << 32) | (back & 0xffffffffL))) {
                return front;
            }
        }
    }

    /** @return the last range left at the back of region {@code r}, or -1 if none is left */
    private int claimBack(int r) {
        Region region = regions[r];
        while (true) {
            long v = region.range;
            int front = (int) (v >>> 32);
            int back = (int) v;
            if (front >= back) {
                return -1;
            }
            if (region.claim(v, ((long) front << 32) | ((back - 1) & 0xffffffffL))) {
                return back - 1;
            }
        }
    }

    /** @return how many {@linkplain #slot() slots} there are: one a worker thread, and one for the thread that calls the passes */
    public int slots() {
        return workers.length + 1;
    }

    /**
     * The calling thread's slot, for scratch kept per thread: a pass's work runs on this pool's workers, each with a slot
     * of its own, or inline on the thread that asked for it, and every other thread shares the last slot. So scratch
     * indexed by it is one thread's at a time if the passes that use it are asked for by one thread at a time (as a
     * world's steps are, under its step lock): it does the job of a ThreadLocal without the look-up (once a robot, that
     * took 2 % of a step's processor time at 10,000 robots).
     *
     * @return the index of the calling worker of this pool, or {@code slots() - 1} on any other thread
     */
    public int slot() {
        return Thread.currentThread() instanceof Worker w && w.owner == this ? w.index : workers.length;
    }

    /** @return whether the calling thread is one of this pool's workers (work it hands over runs on it) */
    private boolean onOwnWorker() {
        return Thread.currentThread() instanceof Worker w && w.owner == this;
    }

    /** A worker's region of a pass: its ranges not claimed yet, front and back packed in one long (front << 32 | back). */
    private static final class Region {
        // padding on both sides: each region's counter in a cache line of its own, as the workers claim from them at once
        long p01, p02, p03, p04, p05, p06, p07;
        volatile long range;
        long p11, p12, p13, p14, p15, p16, p17;

        static final VarHandle RANGE;

        static {
            try {
                RANGE = MethodHandles.lookup().findVarHandle(Region.class, "range", long.class);
            } catch (ReflectiveOperationException e) {
                throw new ExceptionInInitializerError(e);
            }
        }

        boolean claim(long expected, long next) {
            return RANGE.compareAndSet(this, expected, next);
        }
    }

    /** A world's worker thread. */
    private static final class Worker extends Thread {
        private final Parallel owner;
        private final int index;

        Worker(Parallel owner, int index, String name) {
            super(name);
            this.owner = owner;
            this.index = index;
        }

        @Override
        public void run() {
            Parallel p = owner;
            int seen = 0; // the generation before the first pass (not read here: a pass may be published before this thread runs)
            while (true) {
                int g = p.generation;
                if (g == seen) {
                    if (p.closed) {
                        return; // a pass published before the close has been done
                    }
                    // the next pass often follows within microseconds: watch a little before parking
                    long until = System.nanoTime() + SPIN_NANOS;
                    while (p.generation == seen && !p.closed && System.nanoTime() < until) {
                        Thread.onSpinWait();
                    }
                    while (p.generation == seen && !p.closed) {
                        LockSupport.park(p);
                    }
                    continue;
                }
                seen = g;
                p.work(index);
            }
        }
    }

    /** @return whether the calling thread is one of a simulation's worker threads (of any world) */
    static boolean onWorker() {
        return Thread.currentThread() instanceof Worker;
    }

    /** Stops the worker threads (after the pass under way, if any). */
    @Override
    public void close() {
        closed = true;
        for (Worker w : workers) {
            LockSupport.unpark(w);
        }
    }
}
