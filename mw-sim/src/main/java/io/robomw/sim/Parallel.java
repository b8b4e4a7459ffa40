package io.robomw.sim;

import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.Callable;
import java.util.concurrent.ExecutionException;
import java.util.concurrent.ExecutorService;
import java.util.concurrent.Executors;
import java.util.concurrent.Future;
import java.util.concurrent.atomic.AtomicInteger;
import java.util.function.IntConsumer;

/**
 * Runs per-robot work of one simulation step on the simulation's worker threads (named
 * {@code sim-worker-N}), split into contiguous index ranges that the workers claim in turn, and
 * waits for all of it (the calling thread blocks: it does not take a share itself, which on a
 * loaded machine costs it its place with the scheduler; see docs/benchmarks.md). Work on
 * different robots must be independent; results then do not depend on the threads. Small batches
 * run on the calling thread, where handing them over would cost more than it saves.
 */
public final class Parallel implements AutoCloseable {

    private static final int MIN_PARALLEL = 64;

    private final ExecutorService pool;
    private final int threads;

    /**
     * @param threads worker threads; 1 runs everything on the calling thread
     */
    public Parallel(int threads) {
        this.threads = Math.max(1, threads);
        AtomicInteger n = new AtomicInteger();
        this.pool = this.threads == 1 ? null : Executors.newFixedThreadPool(this.threads, r -> {
            Thread t = new Worker(r, "sim-worker-" + n.incrementAndGet());
            t.setDaemon(true);
            return t;
        });
    }

    /**
     * Calls {@code body} for every index in [0, n), in parallel when worth it.
     *
     * @param n    the number of items
     * @param body the work for one item
     */
    public void forEach(int n, IntConsumer body) {
        if (pool == null || n < MIN_PARALLEL) {
            for (int i = 0; i < n; i++) {
                body.accept(i);
            }
            return;
        }
        run(n, body);
    }

    /**
     * Calls {@code batch} for every batch number in [0, batches), in parallel whenever there are
     * worker threads and more than one batch (the caller sized each batch to be worth a hand-over).
     *
     * @param batches the number of batches
     * @param batch   the work for one batch
     */
    public void forEachBatch(int batches, IntConsumer batch) {
        if (pool == null || batches < 2) {
            for (int i = 0; i < batches; i++) {
                batch.accept(i);
            }
            return;
        }
        run(batches, batch);
    }

    private void run(int n, IntConsumer body) {
        // One task per worker, each claiming chunks (four per worker, for balance) from a shared
        // counter: one hand-over per worker instead of one per chunk (measured: 15-50 µs less per
        // pass of 1000 robots on the 2-core machine).
        int chunks = threads * 4;
        AtomicInteger next = new AtomicInteger();
        Callable<Void> claiming = () -> {
            for (int c; (c = next.getAndIncrement()) < chunks; ) {
                int from = (int) ((long) n * c / chunks);
                int to = (int) ((long) n * (c + 1) / chunks);
                for (int i = from; i < to; i++) {
                    body.accept(i);
                }
            }
            return null;
        };
        List<Callable<Void>> tasks = new ArrayList<>(threads);
        for (int t = 0; t < threads; t++) {
            tasks.add(claiming);
        }
        try {
            for (Future<Void> f : pool.invokeAll(tasks)) {
                f.get();
            }
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
            throw new IllegalStateException("interrupted during a simulation step", e);
        } catch (ExecutionException e) {
            Throwable cause = e.getCause();
            if (cause instanceof RuntimeException r) {
                throw r;
            }
            if (cause instanceof Error err) {
                throw err;
            }
            throw new IllegalStateException(cause);
        }
    }

    /** A world's worker thread. */
    private static final class Worker extends Thread {
        Worker(Runnable r, String name) {
            super(r, name);
        }
    }

    /** @return whether the calling thread is one of a simulation's worker threads (of any world) */
    static boolean onWorker() {
        return Thread.currentThread() instanceof Worker;
    }

    /** Stops the worker threads. */
    @Override
    public void close() {
        if (pool != null) {
            pool.shutdownNow();
        }
    }
}
