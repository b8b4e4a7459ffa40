package io.robomw.platform.exec;

import io.robomw.api.Clock;
import io.robomw.api.RobotException;
import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.Test;

import java.time.Duration;
import java.util.List;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.CopyOnWriteArrayList;
import java.util.concurrent.ExecutionException;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicInteger;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertInstanceOf;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * The execution action thread, run on its own thread on the wall clock, when what it runs throws
 * an error rather than an exception: an error a container can cause ends that container and the
 * loop goes on; one the loop cannot survive ends the thread, never silently: every command is
 * stopped, the motors get a last flush, the caller is told, later commands fail saying why, and
 * close() returns only once the thread has ended.
 */
class ActionThreadFailureTest {

    private final ExecutionActionThread thread = new ExecutionActionThread("failing-robot", Clock.system(), Duration.ofMillis(5));

    @AfterEach
    void close() {
        thread.close();
    }

    private static Throwable cause(CompletableFuture<Void> f) {
        ExecutionException e = assertThrows(ExecutionException.class, () -> f.get(10, TimeUnit.SECONDS));
        return e.getCause();
    }

    @Test
    void aStackOverflowInOneCommandsLogicEndsThatCommandAndTheLoopGoesOn() throws Exception {
        thread.start();
        CompletableFuture<Void> bad = thread.submit(Container.builder("recursing").requires("B").logic(now -> {
            throw new StackOverflowError("logic recursed");
        }).build());
        assertInstanceOf(StackOverflowError.class, cause(bad));
        AtomicInteger polls = new AtomicInteger();
        CompletableFuture<Void> next = thread.submit(Container.builder("next").requires("B").logic(now -> polls.incrementAndGet() > 2).build());
        next.get(10, TimeUnit.SECONDS);
        assertTrue(thread.failure().isEmpty());
        assertEquals(1, thread.errors());
    }

    @Test
    void aLinkageErrorInAnActionEndsThatCommandAndRunsItsEndAction() throws Exception {
        thread.start();
        List<String> ended = new CopyOnWriteArrayList<>();
        CompletableFuture<Void> bad = thread.submit(Container.builder("agent code").requires("C").action(now -> {
            throw new NoClassDefFoundError("org/example/Gone");
        }).onEnd(interrupted -> ended.add("stopped C")).build());
        assertInstanceOf(NoClassDefFoundError.class, cause(bad));
        assertEquals(List.of("stopped C"), ended);
        assertTrue(thread.failure().isEmpty());
    }

    @Test
    void anErrorTheLoopCannotSurviveStopsEveryCommandFlushesTheMotorsTellsTheCallerAndFailsLaterCommands() throws Exception {
        List<String> seen = new CopyOnWriteArrayList<>();
        CompletableFuture<RobotException> told = new CompletableFuture<>();
        thread.addFailureListener(told::complete);
        // The listener before the thread starts: added after, it could come too late for the failure's flush on a loaded machine.
        thread.addCycleListener(() -> {
            if (thread.failure().isPresent()) {
                seen.add("last flush after the failure");
            }
        });
        thread.start();
        CompletableFuture<Void> driving = thread.submit(Container.builder("drive").requires("B").logic(now -> false)
                .onEnd(interrupted -> seen.add("drive stopped")).build());
        CompletableFuture<Void> dying = thread.submit(Container.builder("broken").requires("C").logic(now -> {
            throw new InternalError("the JVM is in trouble");
        }).build());

        RobotException why = told.get(10, TimeUnit.SECONDS);
        assertTrue(why.getMessage().contains("execution action thread died of java.lang.InternalError: the JVM is in trouble"), why.getMessage());
        assertEquals(why, cause(driving));
        assertEquals(why, cause(dying));
        assertTrue(seen.containsAll(List.of("drive stopped", "last flush after the failure")), seen.toString());
        assertTrue(seen.indexOf("drive stopped") < seen.indexOf("last flush after the failure"), "motors flushed after every command ended: " + seen);

        Throwable later = cause(thread.submit(Container.builder("later").requires("B").logic(now -> true).build()));
        assertTrue(later.getMessage().contains("robot 'failing-robot' has failed") && later.getMessage().contains("InternalError"), later.getMessage());
    }

    @Test
    void closeReturnsOnlyOnceTheThreadHasEndedEvenWhenACycleIsBlocked() throws Exception {
        CompletableFuture<Void> blocked = new CompletableFuture<>();
        CompletableFuture<Thread> cycling = new CompletableFuture<>();
        thread.start();
        thread.submit(Container.builder("blocking").requires("B").logic(now -> {
            cycling.complete(Thread.currentThread());
            try {
                blocked.get(); // a driver blocked on its link: only an interrupt ends it
            } catch (InterruptedException e) {
                Thread.currentThread().interrupt();
            } catch (ExecutionException e) {
                throw new IllegalStateException(e);
            }
            return true;
        }).build());
        Thread t = cycling.get(10, TimeUnit.SECONDS);
        thread.close();
        assertTrue(!t.isAlive(), "close() returned while the cycling thread still ran");
    }
}
