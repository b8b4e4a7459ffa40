package io.robomw.api;

import org.junit.jupiter.api.Test;

import java.time.Duration;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicReference;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertSame;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

class FuturesTest {

    @Test
    void shouldCancelTheCommandWhenTheDeadlinePasses() {
        CompletableFuture<Void> command = new CompletableFuture<>();
        RobotException e = assertThrows(RobotException.class, () -> Futures.await(command, Duration.ofMillis(20), "move(1.000, 0.100)"));
        assertTrue(e.getMessage().startsWith("move(1.000, 0.100) did not complete within 20 ms"), e.getMessage());
        assertTrue(command.isCancelled(), "the command was ended");
    }

    @Test
    void shouldCancelTheCommandAndKeepTheInterruptWhenTheWaitingThreadIsInterrupted() throws Exception {
        CompletableFuture<Void> command = new CompletableFuture<>();
        AtomicReference<Throwable> thrown = new AtomicReference<>();
        AtomicReference<Boolean> interrupted = new AtomicReference<>();
        CountDownLatch done = new CountDownLatch(1);
        Thread caller = new Thread(() -> {
            try {
                Futures.await(command, Duration.ofMinutes(1), "move(1.000, 0.100)");
            } catch (Throwable t) {
                thrown.set(t);
                interrupted.set(Thread.currentThread().isInterrupted());
            }
            done.countDown();
        });
        caller.start();
        caller.interrupt();
        assertTrue(done.await(10, TimeUnit.SECONDS));
        assertTrue(thrown.get() instanceof RobotException r && r.getMessage().startsWith("interrupted while waiting for move"), String.valueOf(thrown.get()));
        assertTrue(interrupted.get());
        assertTrue(command.isCancelled());
    }

    @Test
    void shouldRethrowTheCommandsOwnFailure() {
        CommandPreemptedException preempted = new CommandPreemptedException("move", "turn");
        assertSame(preempted, assertThrows(CommandPreemptedException.class,
                () -> Futures.await(CompletableFuture.failedFuture(preempted), Duration.ofSeconds(1), "move")));
    }

    @Test
    void shouldCancelTheSourceWhenADerivedFutureIsCancelled() {
        CompletableFuture<Void> source = new CompletableFuture<>();
        CompletableFuture<Void> derived = Futures.cancelling(source.thenApply(v -> v), source);
        derived.cancel(true);
        assertTrue(source.isCancelled());
    }

    @Test
    void shouldGiveMotionsThreeTimesTheirDurationPlusSlack() {
        assertEquals(Duration.ofSeconds(25), Futures.motionTimeout(5));
        assertEquals(Futures.DEFAULT_TIMEOUT, Futures.motionTimeout(Double.NaN));
    }
}
