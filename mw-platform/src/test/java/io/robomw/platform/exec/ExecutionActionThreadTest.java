package io.robomw.platform.exec;

import io.robomw.api.CommandPreemptedException;
import io.robomw.api.ManualClock;
import io.robomw.api.RobotException;
import io.robomw.api.RobotLinkException;
import io.robomw.api.spi.CommandPriority;
import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.Test;

import java.io.IOException;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.Set;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.ExecutionException;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicBoolean;
import java.util.concurrent.atomic.AtomicInteger;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertInstanceOf;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

class ExecutionActionThreadTest {

    private static final Duration PERIOD = Duration.ofMillis(10);

    private final ManualClock clock = new ManualClock();
    private final ExecutionActionThread thread = new ExecutionActionThread("test-robot", clock, PERIOD);
    private final List<String> ended = new ArrayList<>();

    @AfterEach
    void close() {
        thread.close();
    }

    /** A container on the given actuators whose logic holds once {@code done} is set. */
    private Container container(String name, AtomicBoolean done, CommandPriority priority, InterruptionBehavior behavior, String... actuators) {
        return Container.builder(name).requires(actuators).priority(priority).interruptionBehavior(behavior)
                .logic(now -> done.get())
                .onEnd(interrupted -> ended.add(name + (interrupted ? ":interrupted" : ":finished")))
                .build();
    }

    private Container normal(String name, AtomicBoolean done, String... actuators) {
        return container(name, done, CommandPriority.NORMAL, InterruptionBehavior.CANCEL_SELF, actuators);
    }

    private static Throwable failure(CompletableFuture<Void> f) {
        ExecutionException e = assertThrows(ExecutionException.class, () -> f.get(0, TimeUnit.SECONDS));
        return e.getCause();
    }

    @Test
    void shouldStartContainerOnNextCycleAndFinishWhenItsLogicHolds() throws Exception {
        AtomicBoolean done = new AtomicBoolean();
        AtomicInteger starts = new AtomicInteger();
        Container c = Container.builder("move").requires("B", "C").action(now -> starts.incrementAndGet()).logic(now -> done.get()).build();
        CompletableFuture<Void> f = thread.submit(c);

        assertEquals(0, starts.get(), "nothing runs before a cycle");
        thread.cycle();
        assertEquals(1, starts.get());
        assertEquals(Set.of("B", "C"), thread.actuatorsInUse());
        assertFalse(f.isDone());

        done.set(true);
        thread.cycle();
        assertTrue(f.isDone());
        f.get(0, TimeUnit.SECONDS);
        assertEquals(Set.of(), thread.actuatorsInUse());
        thread.cycle();
        assertEquals(1, starts.get(), "actions run once");
    }

    @Test
    void aRefusalEndsTheContainersAdmittedUpToTheCycleItNamesAndNotThoseAdmittedLater() throws Exception {
        CompletableFuture<Void> early = thread.submit(normal("early", new AtomicBoolean(), "B"));
        thread.cycle();
        long refusedThrough = thread.cycles();
        CompletableFuture<Void> late = thread.submit(normal("late", new AtomicBoolean(), "C"));
        thread.cycle();

        RobotException refusal = new RobotException("NXT refused GETOUTPUTSTATE on port 1: status 0xC0");
        thread.driverFailed(refusal, refusedThrough);
        thread.cycle();

        assertEquals(refusal, failure(early));
        assertFalse(late.isDone(), "admitted after the refused exchange, it carries on");
        assertEquals(List.of("early:interrupted"), ended);

        thread.driverFailed(refusal);
        thread.cycle();
        assertEquals(refusal, failure(late), "a refusal naming no cycle ends every running container");
    }

    @Test
    void twoRefusalsBeforeACycleEndTheContainersOfBothWithTheFirstOnesException() throws Exception {
        CompletableFuture<Void> first = thread.submit(normal("first", new AtomicBoolean(), "B"));
        thread.cycle();
        CompletableFuture<Void> second = thread.submit(normal("second", new AtomicBoolean(), "C"));
        thread.cycle();
        CompletableFuture<Void> third = thread.submit(normal("third", new AtomicBoolean(), "A"));
        thread.cycle();

        RobotException earlier = new RobotException("refused first");
        thread.driverFailed(earlier, 2);
        thread.driverFailed(new RobotException("refused second"), 1);
        thread.cycle();

        assertEquals(earlier, failure(first));
        assertEquals(earlier, failure(second));
        assertFalse(third.isDone(), "admitted in cycle 3, after both refused exchanges");
    }

    @Test
    void shouldInterruptOlderContainerWhenNewerNeedsSameActuator() {
        CompletableFuture<Void> first = thread.submit(normal("first", new AtomicBoolean(), "B", "C"));
        thread.cycle();
        CompletableFuture<Void> second = thread.submit(normal("second", new AtomicBoolean(), "C"));
        thread.cycle();

        CommandPreemptedException e = assertInstanceOf(CommandPreemptedException.class, failure(first));
        assertTrue(e.getMessage().contains("'first' was interrupted by 'second'"), e.getMessage());
        assertEquals(List.of("first:interrupted"), ended);
        assertFalse(second.isDone());
        assertEquals(Set.of("C"), thread.actuatorsInUse());
    }

    @Test
    void shouldLetDisjointContainersRunTogether() {
        CompletableFuture<Void> a = thread.submit(normal("a", new AtomicBoolean(), "A"));
        CompletableFuture<Void> b = thread.submit(normal("b", new AtomicBoolean(), "B"));
        thread.cycle();
        assertFalse(a.isDone());
        assertFalse(b.isDone());
        assertEquals(Set.of("A", "B"), thread.actuatorsInUse());
    }

    @Test
    void shouldApplyMostRecentWinsWithinOneCycle() {
        CompletableFuture<Void> first = thread.submit(normal("first", new AtomicBoolean(), "B"));
        CompletableFuture<Void> second = thread.submit(normal("second", new AtomicBoolean(), "B"));
        thread.cycle();
        assertInstanceOf(CommandPreemptedException.class, failure(first));
        assertFalse(second.isDone());
    }

    @Test
    void shouldRefuseNormalContainerWhileSafetyContainerHoldsActuator() {
        CompletableFuture<Void> stop = thread.submit(container("stop", new AtomicBoolean(), CommandPriority.SAFETY, InterruptionBehavior.CANCEL_SELF, "B"));
        thread.cycle();
        CompletableFuture<Void> move = thread.submit(normal("move", new AtomicBoolean(), "B"));
        thread.cycle();

        CommandPreemptedException e = assertInstanceOf(CommandPreemptedException.class, failure(move));
        assertTrue(e.getMessage().contains("refused"), e.getMessage());
        assertFalse(stop.isDone(), "the safety container keeps running");
        assertEquals(List.of(), ended, "the refused container never started, so never ends");
    }

    /**
     * The race CI found (an Aibo's {@code stopAll().get()} then a walk, refused by the stop): a
     * platform whose stop is handed over at once, inside the cycle that admits it, and a caller
     * that moves again the moment the stop is over. Here the caller's move is submitted on the
     * cycling thread itself, while that cycle still admits: the stop must not be over yet.
     */
    @Test
    void aCommandSubmittedOnceAStopIsOverIsAdmittedNotRefusedByTheStop() throws Exception {
        CompletableFuture<Void> handed = new CompletableFuture<>();
        Container stop = Container.builder("stop").requires("B", "C").priority(CommandPriority.SAFETY)
                .action(now -> handed.complete(null)).logic(now -> true).build();
        List<CompletableFuture<Void>> next = new ArrayList<>();

        thread.submitStop(stop, handed, e -> new RobotLinkException("robot 'test-robot': " + e.getMessage(), e))
                .thenRun(() -> next.add(thread.submit(normal("move", new AtomicBoolean(), "B"))));
        thread.cycle();
        thread.cycle();

        assertEquals(1, next.size(), "the stop is over");
        assertFalse(next.get(0).isDone(), "the move after the stop runs: " + next.get(0));
        assertEquals(Set.of("B"), thread.actuatorsInUse());
    }

    @Test
    void aStopRefusedByAClosedThreadFailsWithThePlatformsLinkException() {
        thread.close();
        CompletableFuture<Void> handed = new CompletableFuture<>();
        Container stop = Container.builder("stop").requires("B").priority(CommandPriority.SAFETY).logic(now -> true).build();

        CompletableFuture<Void> over = thread.submitStop(stop, handed, e -> new RobotLinkException("robot 'test-robot': " + e.getMessage(), e));

        RobotLinkException e = assertInstanceOf(RobotLinkException.class, failure(over));
        assertTrue(e.getMessage().contains("robot 'test-robot'") && e.getMessage().contains("closed"), e.getMessage());
    }

    @Test
    void shouldLetSafetyContainerInterruptNormalOne() {
        CompletableFuture<Void> move = thread.submit(normal("move", new AtomicBoolean(), "B", "C"));
        thread.cycle();
        thread.submit(container("stop", new AtomicBoolean(), CommandPriority.SAFETY, InterruptionBehavior.CANCEL_SELF, "B", "C"));
        thread.cycle();
        assertInstanceOf(CommandPreemptedException.class, failure(move));
    }

    @Test
    void shouldRefuseIncomingWhenHolderCancelsIncoming() {
        CompletableFuture<Void> holder = thread.submit(container("calibrate", new AtomicBoolean(), CommandPriority.NORMAL, InterruptionBehavior.CANCEL_INCOMING, "A"));
        thread.cycle();
        CompletableFuture<Void> incoming = thread.submit(normal("grip", new AtomicBoolean(), "A"));
        thread.cycle();
        assertInstanceOf(CommandPreemptedException.class, failure(incoming));
        assertFalse(holder.isDone());
    }

    @Test
    void shouldStopContinuousContainerWhenWatchdogIsNotRefreshed() {
        Container drive = Container.builder("drive").requires("B").watchdog(Duration.ofMillis(500)).logic(now -> false)
                .onEnd(interrupted -> ended.add("drive:" + interrupted)).build();
        CompletableFuture<Void> f = thread.submit(drive);
        thread.cycle();
        clock.advance(Duration.ofMillis(500));
        thread.cycle();
        assertFalse(f.isDone(), "exactly at the timeout it still runs");

        clock.advance(Duration.ofMillis(10));
        thread.cycle();
        RobotException e = assertInstanceOf(RobotException.class, failure(f));
        assertTrue(e.getMessage().contains("watchdog"), e.getMessage());
        assertEquals(List.of("drive:true"), ended);
    }

    @Test
    void shouldKeepContinuousCommandAliveWhileItIsRefreshed() {
        for (int i = 0; i < 10; i++) {
            thread.submit(Container.builder("drive-" + i).requires("B").watchdog(Duration.ofMillis(500)).logic(now -> false).build());
            thread.cycle();
            clock.advance(Duration.ofMillis(400));
        }
        assertEquals(Set.of("B"), thread.actuatorsInUse(), "refreshed every 400 ms, the 500 ms watchdog never fires");
    }

    @Test
    void shouldRefreshContinuousContainerInPlaceWithoutInterruptingIt() throws Exception {
        List<Double> speeds = new ArrayList<>();
        Container first = Container.builder("drive").requires("B", "C").refreshes("continuous").watchdog(Duration.ofMillis(500))
                .action(now -> speeds.add(1.0)).logic(now -> false).onEnd(interrupted -> ended.add("drive:" + interrupted)).build();
        CompletableFuture<Void> f1 = thread.submit(first);
        thread.cycle();
        clock.advance(Duration.ofMillis(400));
        CompletableFuture<Void> f2 = thread.submit(Container.builder("drive").requires("B", "C").refreshes("continuous")
                .watchdog(Duration.ofMillis(500)).action(now -> speeds.add(2.0)).logic(now -> false).build());
        thread.cycle();

        assertEquals(List.of(1.0, 2.0), speeds, "the refresh's actions set the new speeds");
        f2.get(0, TimeUnit.SECONDS);
        assertFalse(f1.isDone(), "the running command goes on");
        assertEquals(List.of(), ended);

        clock.advance(Duration.ofMillis(400));
        thread.cycle();
        assertFalse(f1.isDone(), "the refresh restarted the watchdog: 400 ms after it, still running");
        clock.advance(Duration.ofMillis(200));
        thread.cycle();
        assertInstanceOf(RobotException.class, failure(f1));
        assertEquals(List.of("drive:true"), ended);
    }

    @Test
    void shouldInterruptContinuousContainerWhenRefreshNeedsOtherActuators() {
        CompletableFuture<Void> both = thread.submit(Container.builder("drive").requires("B", "C").refreshes("continuous").logic(now -> false).build());
        thread.cycle();
        thread.submit(Container.builder("drive").requires("B").refreshes("continuous").logic(now -> false).build());
        thread.cycle();
        assertInstanceOf(CommandPreemptedException.class, failure(both));
    }

    @Test
    void shouldEndEveryContainerWithLinkExceptionWhenLinkFails() {
        CompletableFuture<Void> a = thread.submit(normal("a", new AtomicBoolean(), "A"));
        CompletableFuture<Void> b = thread.submit(normal("b", new AtomicBoolean(), "B"));
        thread.cycle();
        thread.linkFailed("serial /dev/pts/9", new IOException("port closed"));
        thread.cycle();

        RobotLinkException e = assertInstanceOf(RobotLinkException.class, failure(a));
        assertTrue(e.getMessage().contains("serial /dev/pts/9") && e.getMessage().contains("stopped"), e.getMessage());
        assertInstanceOf(RobotLinkException.class, failure(b));
        assertEquals(List.of("a:interrupted", "b:interrupted"), ended, "end actions stop the motors");
    }

    @Test
    void shouldEndAContainerSubmittedBeforeTheLinkWasReportedLostButNotYetAdmitted() {
        // the platform admitted it while the link was up; the link agent found it down before the next cycle
        CompletableFuture<Void> late = thread.submit(normal("late", new AtomicBoolean(), "A"));
        thread.linkFailed("serial /dev/pts/9", new IOException("port closed"));
        // what follows the report (the link's safety stop) is admitted
        CompletableFuture<Void> after = thread.submit(normal("after", new AtomicBoolean(true), "B"));
        thread.cycle();

        assertInstanceOf(RobotLinkException.class, failure(late), "not left waiting on a link that is down");
        assertFalse(thread.actuatorsInUse().contains("A"), "it never took its actuators");
        assertTrue(after.isDone() && !after.isCompletedExceptionally(), "the command submitted after the report ran");
    }

    @Test
    void aSecondLinkFailureReportedBeforeTheFirstIsConsumedEndsWhatWasQueuedBeforeIt() {
        // the link failed, came back and failed again before the action thread's next cycle (a busy machine):
        // a command queued while it was back must end with the second failure, not run when the link returns
        CompletableFuture<Void> first = thread.submit(normal("first", new AtomicBoolean(), "A"));
        thread.linkFailed("urbi 127.0.0.1:54000", new IOException("connection reset"));
        CompletableFuture<Void> whileBack = thread.submit(normal("while-back", new AtomicBoolean(), "B"));
        thread.linkFailed("urbi 127.0.0.1:54000", new IOException("connection reset again"));
        CompletableFuture<Void> after = thread.submit(normal("after", new AtomicBoolean(true), "C"));
        thread.cycle();

        assertInstanceOf(RobotLinkException.class, failure(first));
        RobotLinkException e = assertInstanceOf(RobotLinkException.class, failure(whileBack), "not left waiting on a link that is down");
        assertTrue(e.getMessage().contains("again"), "it ends with the failure that came after it: " + e.getMessage());
        assertFalse(thread.actuatorsInUse().contains("B"), "it never took its actuators");
        assertTrue(after.isDone() && !after.isCompletedExceptionally(), "the command submitted after the second report ran");
    }

    @Test
    void shouldEndContainerWhoseLogicThrowsAndKeepCycling() {
        Container bad = Container.builder("bad").requires("A").logic(now -> {
            throw new IllegalStateException("sensor exploded");
        }).build();
        CompletableFuture<Void> f = thread.submit(bad);
        CompletableFuture<Void> good = thread.submit(normal("good", new AtomicBoolean(true), "B"));
        thread.cycle();
        assertInstanceOf(IllegalStateException.class, failure(f));
        assertTrue(good.isDone());
        assertEquals(1, thread.errors());
    }

    @Test
    void shouldLetEndActionSubmitWithoutSeeingItsOwnContainerAgain() {
        AtomicInteger endCalls = new AtomicInteger();
        Container c = Container.builder("self").requires("A").logic(now -> true).onEnd(interrupted -> {
            endCalls.incrementAndGet();
            thread.submit(normal("follow-up", new AtomicBoolean(), "A"));
        }).build();
        thread.submit(c);
        thread.cycle();
        thread.cycle();
        assertEquals(1, endCalls.get());
        assertEquals(Set.of("A"), thread.actuatorsInUse());
    }

    @Test
    void shouldFailQueuedAndRunningContainersOnClose() {
        CompletableFuture<Void> running = thread.submit(normal("running", new AtomicBoolean(), "A"));
        thread.cycle();
        CompletableFuture<Void> queued = thread.submit(normal("queued", new AtomicBoolean(), "B"));
        thread.close();
        assertTrue(failure(running).getMessage().contains("closed"));
        assertTrue(failure(queued).getMessage().contains("closed"));
        assertTrue(failure(thread.submit(normal("late", new AtomicBoolean(), "C"))).getMessage().contains("closed"));
    }

    @Test
    void shouldRunItsOwnThreadOnADecoratedWallClockAndRefuseASecondStart() throws Exception {
        io.robomw.api.Clock decorated = () -> System.nanoTime() + 1_000_000_000L; // a wall clock that is not Clock.system()
        try (ExecutionActionThread real = new ExecutionActionThread("decorated", decorated, PERIOD)) {
            CountDownLatch ran = new CountDownLatch(1);
            real.submit(Container.builder("probe").requires("A").logic(now -> {
                ran.countDown();
                return true;
            }).build());
            real.start();
            assertTrue(ran.await(10, java.util.concurrent.TimeUnit.SECONDS), "its thread cycles on any wall clock");
            assertThrows(IllegalStateException.class, real::start);
        }
    }

    @Test
    void shouldRunCyclesOnItsOwnNamedThreadWithWallClock() throws Exception {
        try (ExecutionActionThread real = new ExecutionActionThread("wall", io.robomw.api.Clock.system(), PERIOD)) {
            CountDownLatch ran = new CountDownLatch(1);
            String[] threadName = new String[1];
            real.submit(Container.builder("probe").requires("A").logic(now -> {
                threadName[0] = Thread.currentThread().getName();
                ran.countDown();
                return true;
            }).build());
            real.start();
            assertTrue(ran.await(5, TimeUnit.SECONDS), "the action thread should cycle by itself");
            assertEquals("wall-action", threadName[0]);
        }
    }

    @Test
    void shouldRejectContainerWithoutActuators() {
        assertThrows(IllegalArgumentException.class, () -> Container.builder("nothing").build());
    }
}
