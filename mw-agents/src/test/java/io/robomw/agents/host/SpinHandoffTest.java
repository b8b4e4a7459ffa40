package io.robomw.agents.host;

import io.robomw.agents.host.visit.SpinHandoff;
import io.robomw.testkit.Await;
import org.junit.jupiter.api.Test;

import java.time.Duration;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.ThreadPoolExecutor;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicInteger;
import java.util.concurrent.atomic.AtomicLong;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

class SpinHandoffTest {

    @Test
    void anIdleThreadSpinsNoLongerThanItsBoundThenParksAndStillGetsTheNextTask() throws Exception {
        // The handoff's own clock, moved by the test: the thread spins until the clock passes its
        // bound, however seldom a loaded machine lets the test thread look.
        AtomicLong now = new AtomicLong(1_000_000_000L);
        SpinHandoff<String> q = new SpinHandoff<>(Duration.ofMillis(2), now::get);
        CompletableFuture<String> got = CompletableFuture.supplyAsync(() -> {
            try {
                return q.poll(30, TimeUnit.SECONDS);
            } catch (InterruptedException e) {
                throw new IllegalStateException(e);
            }
        });
        Await.until("the idle thread spins", Duration.ofSeconds(10), () -> q.spinning() == 1);
        now.addAndGet(Duration.ofMillis(1).toNanos());
        assertEquals(1, q.spinning(), "within its bound it spins on");
        now.addAndGet(Duration.ofMillis(1).toNanos());
        Await.until("the idle thread stops spinning once its bound has passed, and parks", Duration.ofSeconds(10), () -> q.spinning() == 0);
        assertFalse(got.isDone(), "it waits on, parked");
        Await.until("the parked thread takes the task", Duration.ofSeconds(10), () -> q.offer("task"));
        assertEquals("task", got.get(10, TimeUnit.SECONDS));
    }

    @Test
    void aThreadToldToParkNextWaitsParkedOnceAndSpinsAgainAfterwards() throws Exception {
        // The clock never moves: a thread that spins would spin until a task comes.
        AtomicLong now = new AtomicLong(1_000_000_000L);
        SpinHandoff<String> q = new SpinHandoff<>(Duration.ofMillis(1), now::get);
        CompletableFuture<String> first = new CompletableFuture<>();
        CompletableFuture<String> second = new CompletableFuture<>();
        Thread runner = new Thread(() -> {
            try {
                q.parkNext(); // as a runner does after sending a large agent on
                first.complete(q.poll(30, TimeUnit.SECONDS));
                second.complete(q.poll(30, TimeUnit.SECONDS));
            } catch (Throwable t) {
                first.completeExceptionally(t);
                second.completeExceptionally(t);
            }
        }, "spin-handoff-park-next");
        runner.start();
        q.parkNext(); // another thread's flag: must not keep the runner from spinning later
        Await.until("the thread told to park takes the first task, parked", Duration.ofSeconds(10), () -> {
            assertEquals(0, q.spinning(), "a thread told to park next does not spin");
            return q.offer("first");
        });
        assertEquals("first", first.get(10, TimeUnit.SECONDS));
        Await.until("its next wait spins again", Duration.ofSeconds(10), () -> q.spinning() == 1);
        assertTrue(q.offer("second"), "the spinning thread takes the task");
        assertEquals("second", second.get(10, TimeUnit.SECONDS));
        runner.join(10_000);
    }

    @Test
    void anIdleThreadSpinsOnlyWhileItsConditionHoldsElseParksAtOnceAndStillGetsItsTask() throws Exception {
        // The clock never moves: a thread that spins would spin until a task comes.
        AtomicLong now = new AtomicLong(1_000_000_000L);
        java.util.concurrent.atomic.AtomicBoolean few = new java.util.concurrent.atomic.AtomicBoolean(false);
        SpinHandoff<String> q = new SpinHandoff<>(Duration.ofMillis(1), few::get, now::get);
        java.util.concurrent.BlockingQueue<String> got = new java.util.concurrent.LinkedBlockingQueue<>();
        Thread idle = new Thread(() -> {
            try {
                for (int i = 0; i < 2; i++) {
                    got.add(q.poll(30, TimeUnit.SECONDS));
                }
            } catch (InterruptedException e) {
                Thread.currentThread().interrupt();
            }
        }, "spin-handoff-conditional");
        idle.start();
        Await.until("the idle thread parks at once: many agents run (the condition says no)", Duration.ofSeconds(10),
                () -> idle.getState() == Thread.State.TIMED_WAITING);
        assertEquals(0, q.spinning(), "it did not spin");
        few.set(true);
        Await.until("the parked thread takes the task", Duration.ofSeconds(10), () -> q.offer("parked"));
        assertEquals("parked", got.poll(10, TimeUnit.SECONDS));
        Await.until("its next wait spins: few agents run now", Duration.ofSeconds(10), () -> q.spinning() == 1);
        assertTrue(q.offer("spun"), "the spinning thread takes the task");
        assertEquals("spun", got.poll(10, TimeUnit.SECONDS));
        idle.join(10_000);
    }

    @Test
    void aSpinOfZeroNeverSpinsAndAnOfferWithNobodyWaitingIsRefused() throws Exception {
        SpinHandoff<String> q = new SpinHandoff<>(Duration.ZERO, System::nanoTime);
        assertFalse(q.offer("nobody"), "no idle thread: the pool starts one");
        CompletableFuture<String> got = CompletableFuture.supplyAsync(() -> {
            try {
                return q.poll(30, TimeUnit.SECONDS);
            } catch (InterruptedException e) {
                throw new IllegalStateException(e);
            }
        });
        Await.until("the parked thread takes the task", Duration.ofSeconds(10), () -> {
            assertEquals(0, q.spinning(), "a spin of zero never spins");
            return q.offer("task");
        });
        assertEquals("task", got.get(10, TimeUnit.SECONDS));
        assertThrows(IllegalArgumentException.class, () -> new SpinHandoff<String>(Duration.ofNanos(-1), System::nanoTime));
    }

    @Test
    void aPoolOnItRunsEveryTaskWhileThreadsSpinPartAndComeAndGo() throws Exception {
        // Spins shorter than the gaps between bursts and longer than the tasks: tasks meet spinning,
        // parked and no idle threads, and threads that give up their spin as a task comes.
        ThreadPoolExecutor pool = new ThreadPoolExecutor(0, Integer.MAX_VALUE, 50, TimeUnit.MILLISECONDS,
                new SpinHandoff<>(Duration.ofNanos(20_000), System::nanoTime));
        int producers = 4;
        int each = 5_000;
        AtomicInteger ran = new AtomicInteger();
        CountDownLatch done = new CountDownLatch(producers * each);
        try {
            Thread[] threads = new Thread[producers];
            for (int p = 0; p < producers; p++) {
                threads[p] = new Thread(() -> {
                    for (int i = 0; i < each; i++) {
                        pool.execute(() -> {
                            ran.incrementAndGet();
                            done.countDown();
                        });
                        if (i % 100 == 0) {
                            java.util.concurrent.locks.LockSupport.parkNanos(30_000);
                        }
                    }
                }, "spin-handoff-producer-" + p);
                threads[p].start();
            }
            for (Thread t : threads) {
                t.join(TimeUnit.SECONDS.toMillis(60));
            }
            assertTrue(done.await(60, TimeUnit.SECONDS), "every task ran; ran " + ran.get() + " of " + producers * each);
        } finally {
            pool.shutdown();
            assertTrue(pool.awaitTermination(10, TimeUnit.SECONDS), "the pool ends: no thread is left spinning or waiting on a task");
        }
        assertEquals(producers * each, ran.get());
    }
}
