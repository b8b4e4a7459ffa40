package io.robomw.platform.exec;

import io.robomw.api.Clock;
import io.robomw.api.spi.FailurePolicy;
import io.robomw.testkit.Await;
import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.Test;

import java.time.Duration;
import java.util.List;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.CopyOnWriteArrayList;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.ExecutionException;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicReference;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertInstanceOf;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * The execution action thread on its own thread, on the wall clock: its idle strategy is fed by
 * each cycle's work, so a robot with nothing to do does not cycle at all until something wakes it,
 * and then starts at once; what a command throws goes to the failure policy it was given.
 */
class ActionThreadIdleTest {

    /** A policy that keeps what it is told. */
    private static final class RecordingPolicy implements FailurePolicy {
        final List<String> survived = new CopyOnWriteArrayList<>();

        @Override
        public void survived(String owner, Throwable failure) {
            survived.add(owner + ": " + failure.getMessage());
        }

        @Override
        public void died(String owner, Throwable failure) {
            survived.add("DIED " + owner);
        }

        @Override
        public long count() {
            return survived.size();
        }
    }

    private final RecordingPolicy policy = new RecordingPolicy();
    private final ExecutionActionThread thread = new ExecutionActionThread("idle-robot", Clock.system(), Duration.ofMillis(10), policy);
    /** Counted down by the next cycle's listener, once a test arms it. */
    private final AtomicReference<CountDownLatch> nextCycle = new AtomicReference<>(new CountDownLatch(0));

    @AfterEach
    void close() {
        thread.close();
    }

    @Test
    void anIdleThreadRunsNoCycleUntilACommandWakesItAndThenStartsItAtOnce() throws Exception {
        thread.addCycleListener(() -> nextCycle.get().countDown());
        // Asleep for an hour unless woken: only a wake-up can start the command below in time.
        thread.start(Duration.ofHours(1));
        Await.until("the first cycle ran", Duration.ofSeconds(10), () -> thread.cycles() >= 1);
        long idle = thread.cycles();

        CountDownLatch another = new CountDownLatch(1);
        nextCycle.set(another);
        assertFalse(another.await(300, TimeUnit.MILLISECONDS), "an idle thread cycled (at 100 Hz it would have cycled 30 times by now)");
        assertEquals(idle, thread.cycles(), "no cycle ran while the robot had nothing to do");

        CompletableFuture<Void> started = new CompletableFuture<>();
        CompletableFuture<Void> done = thread.submit(Container.builder("move").requires("B")
                .action(now -> started.complete(null)).logic(now -> true).build());
        started.get(10, TimeUnit.SECONDS);
        done.get(10, TimeUnit.SECONDS);
    }

    @Test
    void aRunningCommandKeepsTheThreadCyclingAtItsPeriod() throws Exception {
        thread.start(Duration.ofHours(1));
        CompletableFuture<Void> ten = new CompletableFuture<>();
        int[] evaluations = new int[1];
        thread.submit(Container.builder("drive").requires("B").logic(now -> {
            if (++evaluations[0] == 10) {
                ten.complete(null);
            }
            return evaluations[0] >= 10;
        }).build());
        ten.get(10, TimeUnit.SECONDS); // ten cycles in a row, without any further wake-up
    }

    @Test
    void whatACommandThrowsGoesToTheInjectedPolicyNamingTheRobotAndTheCommand() throws Exception {
        thread.start();
        CompletableFuture<Void> bad = thread.submit(Container.builder("recursing").requires("B").logic(now -> {
            throw new IllegalStateException("logic failed");
        }).build());
        ExecutionException e = assertThrows(ExecutionException.class, () -> bad.get(10, TimeUnit.SECONDS));
        assertInstanceOf(IllegalStateException.class, e.getCause());
        assertEquals(List.of("idle-robot-action, command 'recursing': logic failed"), policy.survived);
        assertTrue(thread.failure().isEmpty(), "the thread goes on");
        thread.submit(Container.builder("next").requires("B").logic(now -> true).build()).get(10, TimeUnit.SECONDS);
    }
}
