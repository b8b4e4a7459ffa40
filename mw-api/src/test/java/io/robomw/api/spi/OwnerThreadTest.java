package io.robomw.api.spi;

import org.junit.jupiter.api.Test;

import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicInteger;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertInstanceOf;
import static org.junit.jupiter.api.Assertions.assertTrue;

class OwnerThreadTest {

    /** A policy that records what it is told. */
    static final class Recording implements FailurePolicy {
        final List<String> survived = new ArrayList<>();
        final List<Throwable> died = new ArrayList<>();
        final CountDownLatch death = new CountDownLatch(1);

        @Override
        public synchronized void survived(String owner, Throwable failure) {
            survived.add(owner + ": " + failure.getMessage());
        }

        @Override
        public synchronized void died(String owner, Throwable failure) {
            died.add(failure);
            death.countDown();
        }

        @Override
        public synchronized long count() {
            return survived.size() + died.size();
        }
    }

    private static final IdleStrategy NO_WAIT = work -> Thread.onSpinWait();

    @Test
    void shouldReportASurvivableFailureAndGoOn() throws Exception {
        Recording policy = new Recording();
        AtomicInteger rounds = new AtomicInteger();
        CountDownLatch fifth = new CountDownLatch(1);
        OwnerThread t = OwnerThread.start("robot-action", Thread.NORM_PRIORITY, () -> {
            int n = rounds.incrementAndGet();
            if (n == 2) {
                throw new IllegalStateException("round two failed");
            }
            if (n == 3) {
                throw new StackOverflowError("deep");
            }
            if (n == 5) {
                fifth.countDown();
            }
            return 1;
        }, NO_WAIT, policy);
        assertTrue(fifth.await(10, TimeUnit.SECONDS), "the loop went on after the failures");
        t.close();
        synchronized (policy) {
            assertEquals(List.of("robot-action: round two failed", "robot-action: deep"), policy.survived);
            assertTrue(policy.died.isEmpty());
        }
        assertTrue(t.death().isEmpty());
    }

    @Test
    void shouldStopWhatItOwnsAndReportTheDeathOfAFailureItCannotSurvive() throws Exception {
        Recording policy = new Recording();
        List<String> calls = new java.util.concurrent.CopyOnWriteArrayList<>();
        OwnerThread t = OwnerThread.start("robot-link", Thread.NORM_PRIORITY, new OwnerThread.Duty() {
            @Override
            public int doWork() {
                throw new OutOfMemoryError("heap");
            }

            @Override
            public void onDeath(Throwable failure) {
                calls.add("onDeath " + failure.getMessage());
            }

            @Override
            public void onClose() {
                calls.add("onClose");
            }
        }, NO_WAIT, policy);
        assertTrue(policy.death.await(10, TimeUnit.SECONDS));
        t.close();
        assertEquals(List.of("onDeath heap", "onClose"), calls);
        assertInstanceOf(OutOfMemoryError.class, t.death().orElseThrow());
        assertFalse(t.running());
    }

    @Test
    void shouldEndABlockedRoundWhenClosedAndReportNothing() throws Exception {
        Recording policy = new Recording();
        CountDownLatch blocked = new CountDownLatch(1);
        OwnerThread t = OwnerThread.start("robot-reload", Thread.NORM_PRIORITY, () -> {
            blocked.countDown();
            new CountDownLatch(1).await(); // blocks until interrupted
            return 0;
        }, NO_WAIT, policy);
        assertTrue(blocked.await(10, TimeUnit.SECONDS));
        t.close();
        assertFalse(t.running());
        assertEquals(0, policy.count(), "a thread ended on purpose reports nothing");
    }

    @Test
    void shouldSleepWhileIdleUntilWoken() throws Exception {
        Recording policy = new Recording();
        AtomicInteger rounds = new AtomicInteger();
        CountDownLatch second = new CountDownLatch(2);
        OwnerThread t = OwnerThread.start("idle", Thread.NORM_PRIORITY, () -> {
            rounds.incrementAndGet();
            second.countDown();
            return 0;
        }, IdleStrategy.periodic(io.robomw.api.Clock.system(), Duration.ofMillis(1), Duration.ofHours(1)), policy);
        // The first round found nothing to do: the thread waits (an hour at most) until woken.
        while (rounds.get() < 1) {
            Thread.onSpinWait();
        }
        assertFalse(second.await(200, TimeUnit.MILLISECONDS), "an idle thread does not come round on its own");
        t.wake();
        assertTrue(second.await(10, TimeUnit.SECONDS), "a wake starts the next round");
        t.close();
    }

    @Test
    void shouldTellSurvivableFromFatal() {
        assertTrue(FailurePolicy.survivable(new RuntimeException()));
        assertTrue(FailurePolicy.survivable(new AssertionError()));
        assertTrue(FailurePolicy.survivable(new NoClassDefFoundError()));
        assertTrue(FailurePolicy.survivable(new StackOverflowError()));
        assertFalse(FailurePolicy.survivable(new OutOfMemoryError()));
        assertFalse(FailurePolicy.survivable(new InternalError()));
    }
}
