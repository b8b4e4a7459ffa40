package io.robomw.sim;

import io.robomw.testkit.BusyThreads;
import org.junit.jupiter.api.Test;

import java.util.concurrent.atomic.AtomicIntegerArray;
import java.util.concurrent.atomic.AtomicReference;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertSame;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * The world's worker threads: every item of a pass is handled exactly once, on a worker, pass after
 * pass (also on a loaded machine, where a worker may not run for a while), a failure reaches the caller,
 * and work a worker hands over runs on it.
 */
class ParallelTest {

    @Test
    void shouldHandleEveryItemExactlyOnceOnTheWorkersPassAfterPass() {
        try (Parallel parallel = new Parallel(2); BusyThreads busy = new BusyThreads(2)) {
            for (int pass = 0; pass < 2000; pass++) {
                int n = 64 + (pass * 37) % 5000;
                AtomicIntegerArray seen = new AtomicIntegerArray(n);
                AtomicReference<String> notWorker = new AtomicReference<>();
                parallel.forEach(n, i -> {
                    seen.incrementAndGet(i);
                    if (!Parallel.onWorker()) {
                        notWorker.set(Thread.currentThread().getName());
                    }
                });
                for (int i = 0; i < n; i++) {
                    assertEquals(1, seen.get(i), "pass " + pass + ": item " + i + " of " + n);
                }
                assertEquals(null, notWorker.get(), "pass " + pass + ": an item ran off the workers");
                int batches = 2 + pass % 300;
                AtomicIntegerArray batchSeen = new AtomicIntegerArray(batches);
                parallel.forEachBatch(batches, batchSeen::incrementAndGet);
                for (int b = 0; b < batches; b++) {
                    assertEquals(1, batchSeen.get(b), "pass " + pass + ": batch " + b + " of " + batches);
                }
            }
        }
    }

    @Test
    void shouldRunAPassHandedOverBeforeItsWorkersHaveStarted() throws Exception {
        // a pass published before a new worker first looks at the generation must still be done (not waited for forever)
        try (BusyThreads busy = new BusyThreads(2)) {
            for (int k = 0; k < 200; k++) {
                java.util.concurrent.CompletableFuture<Void> pass = java.util.concurrent.CompletableFuture.runAsync(() -> {
                    try (Parallel parallel = new Parallel(2)) {
                        parallel.forEach(200, i -> { });
                    }
                });
                pass.get(30, java.util.concurrent.TimeUnit.SECONDS);
            }
        }
    }

    @Test
    void shouldHandOnAFailureToTheCallerAndGoOnWithTheNextPass() {
        try (Parallel parallel = new Parallel(2)) {
            IllegalArgumentException thrown = new IllegalArgumentException("robot 500 failed");
            IllegalArgumentException caught = assertThrows(IllegalArgumentException.class, () -> parallel.forEach(1000, i -> {
                if (i == 500) {
                    throw thrown;
                }
            }));
            assertSame(thrown, caught);
            AtomicIntegerArray seen = new AtomicIntegerArray(1000);
            parallel.forEach(1000, seen::incrementAndGet);
            for (int i = 0; i < 1000; i++) {
                assertEquals(1, seen.get(i), "item " + i + " after the failed pass");
            }
        }
    }

    @Test
    void shouldRunWorkAWorkerHandsOverOnThatWorker() {
        try (Parallel parallel = new Parallel(2)) {
            AtomicIntegerArray inner = new AtomicIntegerArray(100);
            AtomicReference<String> wrongThread = new AtomicReference<>();
            parallel.forEach(100, i -> {
                Thread outer = Thread.currentThread();
                parallel.forEach(100, j -> {
                    if (Thread.currentThread() != outer) {
                        wrongThread.set(Thread.currentThread().getName());
                    }
                    if (i == 0) {
                        inner.incrementAndGet(j);
                    }
                });
            });
            assertEquals(null, wrongThread.get());
            for (int j = 0; j < 100; j++) {
                assertEquals(1, inner.get(j));
            }
        }
    }

    @Test
    void shouldRefusePassesOnceClosed() {
        Parallel parallel = new Parallel(2);
        parallel.forEach(100, i -> { });
        parallel.close();
        IllegalStateException e = assertThrows(IllegalStateException.class, () -> parallel.forEach(100, i -> { }));
        assertTrue(e.getMessage().contains("stopped"), e.getMessage());
    }
}
