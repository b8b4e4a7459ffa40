package io.robomw.platform.exec;

import io.robomw.api.CommandPreemptedException;
import io.robomw.api.ManualClock;
import io.robomw.api.RobotException;
import io.robomw.api.spi.CommandPriority;
import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.Test;

import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.Set;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.ExecutionException;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicBoolean;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertInstanceOf;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * A continuous command refreshed through a {@link RefreshSlot} is admitted exactly as a container
 * per refresh would be: in its place among the other commands, by the same clash, refresh and
 * watchdog rules, its failures logged, counted and ending the container it refreshed.
 */
class RefreshSlotTest {

    private static final Duration PERIOD = Duration.ofMillis(10);
    private static final Set<String> WHEELS = Set.of("B", "C");

    private final ManualClock clock = new ManualClock();
    private final ExecutionActionThread thread = new ExecutionActionThread("test-robot", clock, PERIOD);
    /** What happened, in order: "start 1.0,2.0" (a container from the slot started), "refresh 3.0,4.0", "end drive#1:interrupted", ... */
    private final List<String> events = new ArrayList<>();
    /** The containers the slot made, in order. */
    private final List<Container> made = new ArrayList<>();
    /** A refresh with this first value throws. */
    private double failOn = Double.NaN;

    private final RefreshSlot slot = new RefreshSlot("drive", WHEELS, CommandPriority.NORMAL, "continuous", 2, new RefreshSlot.Handler() {
        @Override
        public void refresh(double[] values, long nowNanos) {
            if (values[0] == failOn) {
                throw new IllegalStateException("motor driver rejected " + values[0]);
            }
            events.add("refresh " + values[0] + "," + values[1]);
        }

        @Override
        public Container container(double[] values) {
            double[] mine = values.clone();
            String name = "drive#" + (made.size() + 1);
            Container c = Container.builder(name).requires(WHEELS).refreshes("continuous").watchdog(Duration.ofMillis(500))
                    .action(now -> events.add("start " + mine[0] + "," + mine[1]))
                    .logic(now -> false)
                    .onEnd(interrupted -> events.add("end " + name + (interrupted ? ":interrupted" : ":finished")))
                    .build();
            made.add(c);
            return c;
        }
    });

    @AfterEach
    void close() {
        thread.close();
    }

    private void drive(double left, double right) {
        thread.refresh(slot, new double[] {left, right});
    }

    /** A move on the given wheel: runs until {@code done}, records its start and end. */
    private Container move(String name, AtomicBoolean done, CommandPriority priority, String... wheels) {
        return Container.builder(name).requires(wheels).priority(priority)
                .action(now -> events.add("start " + name))
                .logic(now -> done.get())
                .onEnd(interrupted -> events.add("end " + name + (interrupted ? ":interrupted" : ":finished")))
                .build();
    }

    private static Throwable failure(CompletableFuture<Void> f) {
        ExecutionException e = assertThrows(ExecutionException.class, () -> f.get(0, TimeUnit.SECONDS));
        return e.getCause();
    }

    @Test
    void shouldStartOneContainerAndThenRefreshItInPlaceAtEveryCycle() {
        drive(1, 2);
        assertEquals(List.of(), events, "nothing happens before the cycle");
        thread.cycle();
        for (int i = 0; i < 5; i++) {
            clock.advance(PERIOD);
            drive(3 + i, 4 + i);
            thread.cycle();
        }

        assertEquals(List.of("start 1.0,2.0", "refresh 3.0,4.0", "refresh 4.0,5.0", "refresh 5.0,6.0", "refresh 6.0,7.0", "refresh 7.0,8.0"), events);
        assertEquals(1, made.size(), "one container for the whole drive");
        assertFalse(made.get(0).completion().isDone());
        assertEquals(WHEELS, thread.actuatorsInUse());
    }

    @Test
    void shouldRestartTheWatchdogAtEachRefreshAndStopTheDriveWhenRefreshesStop() {
        drive(1, 1);
        thread.cycle();
        for (int i = 0; i < 10; i++) {
            clock.advance(Duration.ofMillis(400));
            drive(1, 1);
            thread.cycle();
        }
        assertFalse(made.get(0).completion().isDone(), "refreshed every 400 ms, the 500 ms watchdog never fired");

        clock.advance(Duration.ofMillis(400));
        thread.cycle();
        assertFalse(made.get(0).completion().isDone());
        clock.advance(Duration.ofMillis(200));
        thread.cycle();
        RobotException e = assertInstanceOf(RobotException.class, failure(made.get(0).completion()));
        assertTrue(e.getMessage().contains("watchdog"), e.getMessage());
        assertEquals("end drive#1:interrupted", events.get(events.size() - 1));
        assertEquals(Set.of(), thread.actuatorsInUse());
    }

    @Test
    void shouldReplaceQueuedValuesWhenNothingWasSubmittedAfterThem() {
        drive(1, 1);
        thread.cycle();
        drive(2, 2);
        drive(3, 3);
        thread.cycle();

        assertEquals(List.of("start 1.0,1.0", "refresh 3.0,3.0"), events, "the newest refresh is the one admitted");
    }

    @Test
    void shouldLetAMoveSubmittedAfterADriveInTheSameCycleInterruptIt() {
        drive(1, 1);
        thread.cycle();
        drive(2, 2);
        CompletableFuture<Void> move = thread.submit(move("move", new AtomicBoolean(), CommandPriority.NORMAL, "B"));
        thread.cycle();

        assertEquals(List.of("start 1.0,1.0", "refresh 2.0,2.0", "end drive#1:interrupted", "start move"), events);
        assertInstanceOf(CommandPreemptedException.class, failure(made.get(0).completion()));
        assertFalse(move.isDone());
        assertEquals(Set.of("B"), thread.actuatorsInUse());
    }

    @Test
    void shouldLetADriveAfterAMoveInterruptTheMove() {
        CompletableFuture<Void> move = thread.submit(move("move", new AtomicBoolean(), CommandPriority.NORMAL, "B"));
        thread.cycle();
        drive(5, 6);
        thread.cycle();

        assertEquals(List.of("start move", "end move:interrupted", "start 5.0,6.0"), events);
        assertInstanceOf(CommandPreemptedException.class, failure(move));
        assertEquals(WHEELS, thread.actuatorsInUse());
    }

    @Test
    void shouldAdmitDriveMoveDriveQueuedInOneCycleInThatOrder() {
        drive(1, 1);
        thread.cycle();
        drive(2, 2);
        CompletableFuture<Void> move = thread.submit(move("move", new AtomicBoolean(), CommandPriority.NORMAL, "C"));
        drive(3, 3); // after the move: it must not replace the values queued before it
        thread.cycle();

        assertEquals(List.of("start 1.0,1.0", "refresh 2.0,2.0", "end drive#1:interrupted", "start move", "end move:interrupted", "start 3.0,3.0"),
                events);
        assertInstanceOf(CommandPreemptedException.class, failure(move));
        assertEquals(2, made.size());
        assertFalse(made.get(1).completion().isDone(), "the last drive runs");

        clock.advance(PERIOD);
        drive(4, 4);
        thread.cycle();
        assertEquals("refresh 4.0,4.0", events.get(events.size() - 1), "and the slot refreshes it from then on");
    }

    @Test
    void shouldBeRefusedWhileASafetyStopSubmittedBeforeItHoldsTheMotors() {
        drive(1, 1);
        thread.cycle();
        thread.submit(Container.builder("stop").requires(WHEELS).priority(CommandPriority.SAFETY).action(now -> events.add("stop"))
                .logic(now -> true).build());
        drive(2, 2);
        thread.cycle();

        assertEquals(List.of("start 1.0,1.0", "end drive#1:interrupted", "stop"), events, "the drive after the stop did not restart the motors");
        assertInstanceOf(CommandPreemptedException.class, failure(made.get(1).completion()), "refused");
        assertEquals(Set.of(), thread.actuatorsInUse());

        drive(3, 3);
        thread.cycle();
        assertEquals("start 3.0,3.0", events.get(events.size() - 1), "a drive after the stop's cycle starts again");
    }

    @Test
    void shouldBeInterruptedByASafetyStopSubmittedAfterIt() {
        drive(1, 1);
        thread.submit(Container.builder("stop").requires(WHEELS).priority(CommandPriority.SAFETY).action(now -> events.add("stop"))
                .logic(now -> true).build());
        thread.cycle();

        assertEquals(List.of("start 1.0,1.0", "end drive#1:interrupted", "stop"), events);
        assertInstanceOf(CommandPreemptedException.class, failure(made.get(0).completion()));
    }

    @Test
    void shouldEndTheDriveWithTheFailureOfARefreshCountItAndKeepCycling() {
        drive(1, 1);
        thread.cycle();
        failOn = 7;
        drive(7, 7);
        thread.cycle();

        IllegalStateException e = assertInstanceOf(IllegalStateException.class, failure(made.get(0).completion()));
        assertTrue(e.getMessage().contains("rejected 7.0"), e.getMessage());
        assertEquals(1, thread.errors());
        assertEquals("end drive#1:interrupted", events.get(events.size() - 1), "its end action stopped the motors");

        drive(2, 2);
        thread.cycle();
        assertEquals("start 2.0,2.0", events.get(events.size() - 1));
    }

    @Test
    void shouldDropRefreshesOnceClosedAndQueuedValuesOnClose() {
        drive(1, 1);
        thread.close();
        assertEquals(List.of(), events, "queued values were not run");
        drive(2, 2);
        thread.cycle();
        assertEquals(List.of(), events);
    }

    @Test
    void shouldDropRefreshesOnceTheThreadHasDied() {
        drive(1, 1);
        thread.cycle();
        thread.died(new OutOfMemoryError("test"));
        assertEquals("end drive#1:interrupted", events.get(events.size() - 1));
        assertTrue(thread.failure().isPresent());
        int before = events.size();
        drive(2, 2);
        assertEquals(before, events.size());
    }

    @Test
    void shouldRefuseASlotOfAnotherThreadAndValuesThatDoNotFit() {
        drive(1, 1);
        try (ExecutionActionThread other = new ExecutionActionThread("other", clock, PERIOD)) {
            IllegalArgumentException e = assertThrows(IllegalArgumentException.class, () -> other.refresh(slot, new double[] {1, 1}));
            assertTrue(e.getMessage().contains("another robot"), e.getMessage());
        }
        IllegalArgumentException e = assertThrows(IllegalArgumentException.class, () -> thread.refresh(slot, new double[] {1, 2, 3}));
        assertTrue(e.getMessage().contains("takes 2 values"), e.getMessage());
    }

    @Test
    void shouldRefreshAContainerSubmittedWithTheSameKeyActuatorsAndPriority() {
        Container submitted = Container.builder("drive").requires(WHEELS).refreshes("continuous").logic(now -> false)
                .action(now -> events.add("start submitted")).build();
        thread.submit(submitted);
        thread.cycle();
        drive(1, 2);
        thread.cycle();

        assertEquals(List.of("start submitted", "refresh 1.0,2.0"), events);
        assertFalse(submitted.completion().isDone());
        assertEquals(0, made.size());
    }
}
