package io.robomw.platform.motor;

import io.robomw.api.CommandPreemptedException;
import io.robomw.api.ManualClock;
import io.robomw.api.RobotException;
import io.robomw.api.RobotLinkException;
import io.robomw.api.spi.ConnectionSettings;
import io.robomw.api.spi.MotorCommand;
import io.robomw.api.spi.MotorTarget;
import io.robomw.api.spi.PlatformConfig;
import io.robomw.api.spi.PlatformServices;
import io.robomw.api.spi.SensorChannel;
import io.robomw.platform.BrickPlatform;
import io.robomw.platform.sensor.Sensor;
import io.robomw.platform.sensor.SensorPlatform;
import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.Test;

import java.io.IOException;
import java.time.Duration;
import java.util.ArrayList;
import java.util.HashMap;
import java.util.List;
import java.util.Map;
import java.util.Set;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.ExecutionException;
import java.util.concurrent.TimeUnit;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertInstanceOf;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * The motor platform and BrickPlatform on a manual clock, with a fake driver whose motors turn at
 * exactly the commanded speed between cycles; the link agent runs inline, after each cycle.
 */
class MotorPlatformTest {

    private static final Duration PERIOD = Duration.ofMillis(10);

    private final ManualClock clock = new ManualClock();
    private final FakeMotors motors = new FakeMotors();
    private BrickPlatform platform;
    private MotorPlatform motorPlatform;

    /**
     * Motors that integrate their speed over simulated time; records what the link side sent. Optionally
     * like an NXT: the brick ends a limited rotation itself at its limit, counted from where the
     * motor is when the command arrives, and says so; optionally on a busy link, whose commands
     * reach the motors {@code commandLag} cycles after the link side sent them (replies still report
     * what the brick did after every command sent before them); or with a blocked motor.
     */
    static final class FakeMotors implements MotorDriver, LinkTiming {
        final List<List<MotorState>> sent = new ArrayList<>();
        final Map<String, Double> speed = new HashMap<>(Map.of("B", 0.0, "C", 0.0));
        final Map<String, Double> position = new HashMap<>(Map.of("B", 0.0, "C", 0.0));
        private final Map<String, Double> stopAt = new HashMap<>();
        private final java.util.ArrayDeque<List<MotorState>> inFlight = new java.util.ArrayDeque<>();
        private final java.util.ArrayDeque<Integer> dueAt = new java.util.ArrayDeque<>();
        private int advances;
        IOException failNext;
        boolean brickStopsAtLimit;
        boolean blocked;
        /** The share of its speed a motor turns at (a loaded link's driver creeping, a weak battery). */
        double share = 1;
        int commandLag;

        @Override
        public LinkTiming timing() {
            return this;
        }

        @Override
        public boolean stopsAtLimit() {
            return brickStopsAtLimit;
        }

        @Override
        public void send(List<MotorState> motors, FeedbackSink feedback) throws IOException {
            if (failNext != null) {
                throw failNext;
            }
            sent.add(motors);
            inFlight.addLast(motors);
            dueAt.addLast(advances + commandLag);
            applyDue();
        }

        @Override
        public int poll(FeedbackSink feedback) {
            position.forEach(feedback::degrees);
            if (brickStopsAtLimit && inFlight.isEmpty()) {
                speed.forEach((port, dps) -> {
                    if (dps == 0) {
                        feedback.stoppedAtLimit(port);
                    }
                });
            }
            return 0;
        }

        private void applyDue() {
            while (!inFlight.isEmpty() && dueAt.peekFirst() <= advances) {
                dueAt.removeFirst();
                for (MotorState m : inFlight.removeFirst()) {
                    speed.put(m.port(), m.degreesPerSecond());
                    if (m.running() && !Double.isInfinite(m.limitDegrees())) {
                        stopAt.put(m.port(), position.get(m.port()) + Math.signum(m.degreesPerSecond()) * m.limitDegrees());
                    } else {
                        stopAt.remove(m.port());
                    }
                }
            }
        }

        void advance(Duration dt) {
            advances++;
            applyDue();
            if (blocked) {
                return;
            }
            speed.forEach((port, dps) -> {
                double next = position.get(port) + share * dps * dt.toNanos() / 1e9;
                Double limit = stopAt.get(port);
                if (brickStopsAtLimit && limit != null && (dps > 0 ? next >= limit : next <= limit)) {
                    next = limit;
                    speed.put(port, 0.0);
                    stopAt.remove(port);
                }
                position.put(port, next);
            });
        }
    }

    private BrickPlatform open() throws IOException {
        PlatformConfig config = new PlatformConfig("fake", "fake", new ConnectionSettings(Map.of(), "test"),
                List.of(io.robomw.api.spi.MotorChannel.actuator("B"), io.robomw.api.spi.MotorChannel.actuator("C")),
                List.of(new SensorChannel("left-tacho", io.robomw.api.SensorType.TACHO, "B", Map.of()),
                        new SensorChannel("sonar", io.robomw.api.SensorType.SONAR, "S4", Map.of())),
                PERIOD, Duration.ofMillis(500), clock, PlatformServices.none(), io.robomw.api.spi.Cycling.BY_OWNER, io.robomw.api.spi.FailurePolicy.logging());
        motorPlatform = new MotorPlatform(config, motors);
        SensorPlatform sensors = new SensorPlatform(motorPlatform) {
            @Override
            public Sensor createSensor(SensorChannel sensorObject) {
                return () -> CompletableFuture.completedFuture(42.0);
            }
        };
        platform = new BrickPlatform(config, motorPlatform, sensors, null, null).start();
        return platform;
    }

    @AfterEach
    void close() {
        if (platform != null) {
            platform.close();
        }
    }

    /** One simulated cycle: motors move for a period, then the action thread cycles. */
    private void step() {
        motors.advance(PERIOD);
        clock.advance(PERIOD);
        platform.actionThread().cycle();
    }

    private void stepUntilDone(CompletableFuture<?> f, int maxCycles) {
        for (int i = 0; i < maxCycles && !f.isDone(); i++) {
            step();
        }
        assertTrue(f.isDone(), "not done after " + maxCycles + " cycles");
    }

    /**
     * Turns B 720° at 360°/s and C −360° at 180°/s to the end, one cycle more, and checks that each
     * stopped within half a cycle of travel of where it started plus its target.
     */
    private void turnBothAndCheckTheyStopFrom(double b, double c) throws Exception {
        CompletableFuture<Void> move = platform.run(MotorCommand.of("move", List.of(
                MotorTarget.rotate("B", 720, 360), MotorTarget.rotate("C", -360, 180))));
        stepUntilDone(move, 1000);
        move.get(0, TimeUnit.SECONDS);
        step();
        assertEquals(b + 720, motors.position.get("B"), 360 * PERIOD.toMillis() / 2000.0, "B within half a cycle of travel");
        assertEquals(c - 360, motors.position.get("C"), 180 * PERIOD.toMillis() / 2000.0);
    }

    @Test
    void shouldStopEachMotorWithinHalfCycleOfItsTarget() throws Exception {
        open();
        turnBothAndCheckTheyStopFrom(0, 0);
        assertEquals(0.0, motors.speed.get("B"));
        assertEquals(0.0, motors.speed.get("C"));
    }

    /**
     * A rotation commanded before the link side's first poll (right after opening) counts from
     * where the brick's counter stands, not from 0: an NXT's tacho count kept from before, or the
     * Intelligent Interface's impulse wheel, which starts mid-tooth at half a tick. Counted from 0,
     * the first reading looked like 500° of turning and B stopped at once (and a motor turning
     * the other way would look short of its target by as much: the driver's own limit stops it,
     * and the command waits until it fails as blocked).
     */
    @Test
    void aRotationCommandedBeforeTheFirstReadingCountsFromWhereTheCounterStands() throws Exception {
        motors.position.put("B", 500.0);
        motors.position.put("C", -40.0);
        open();
        turnBothAndCheckTheyStopFrom(500, -40);
    }

    /**
     * The same right after the link agent reopened the link: the brick may have been switched off
     * and on meanwhile (its counters back at 0), and a command admitted as soon as the link is up
     * again counts from the brick's reading, not from the last one before the loss.
     */
    @Test
    void aRotationCommandedRightAfterTheLinkIsReopenedCountsFromTheBricksNewReading() throws Exception {
        open();
        CompletableFuture<Void> first = platform.run(MotorCommand.of("first", List.of(MotorTarget.rotate("B", 90, 360))));
        stepUntilDone(first, 100);
        step();
        motors.position.put("B", 0.0); // switched off and on while the link was away
        motorPlatform.linkSide().linkReopened();
        CompletableFuture<Void> move = platform.run(MotorCommand.of("move", List.of(MotorTarget.rotate("B", 360, 360))));
        stepUntilDone(move, 1000);
        move.get(0, TimeUnit.SECONDS);
        step();
        assertEquals(360, motors.position.get("B"), 360 * PERIOD.toMillis() / 2000.0, "B within half a cycle of travel from where the brick stood");
    }
    @Test
    void shouldSendOnlyChangedMotorsToTheDriver() throws Exception {
        open();
        platform.run(MotorCommand.of("b only", List.of(MotorTarget.run("B", 100))));
        step();
        assertEquals(List.of(new MotorState("B", 100, Double.POSITIVE_INFINITY, MotorState.StopMode.BRAKE)), motors.sent.get(0));
        int before = motors.sent.size();
        step();
        step();
        assertEquals(before, motors.sent.size(), "nothing changed, nothing sent");
    }

    @Test
    void shouldStopAllMotorsAndRefuseNormalCommandsInTheSameCycle() throws Exception {
        open();
        CompletableFuture<Void> run = platform.run(MotorCommand.of("run", List.of(MotorTarget.run("B", 100), MotorTarget.run("C", 100))));
        step();
        platform.stopAll();
        CompletableFuture<Void> sneaky = platform.run(MotorCommand.of("sneaky", List.of(MotorTarget.run("B", 50))));
        step();
        assertInstanceOf(CommandPreemptedException.class, assertThrows(ExecutionException.class, () -> run.get(0, TimeUnit.SECONDS)).getCause());
        assertInstanceOf(CommandPreemptedException.class, assertThrows(ExecutionException.class, () -> sneaky.get(0, TimeUnit.SECONDS)).getCause());
        assertEquals(0.0, motors.speed.get("B"));
        assertEquals(0.0, motors.speed.get("C"));
    }

    @Test
    void shouldFailCommandsAndReportLinkDownWhenRunImplThrows() throws Exception {
        open();
        motors.failNext = new IOException("brick unplugged");
        CompletableFuture<Void> move = platform.run(MotorCommand.of("move", List.of(MotorTarget.rotate("B", 720, 360))));
        step();
        step();
        RobotLinkException e = assertInstanceOf(RobotLinkException.class, assertThrows(ExecutionException.class, () -> move.get(0, TimeUnit.SECONDS)).getCause());
        assertTrue(e.getMessage().contains("brick unplugged"), e.getMessage());
        assertTrue(platform.run(MotorCommand.of("again", List.of(MotorTarget.run("B", 1)))).isCompletedExceptionally(), "refused while the link is down");

        motors.failNext = null;
        step();
        CompletableFuture<Void> after = platform.run(MotorCommand.of("after", List.of(MotorTarget.rotate("B", 10, 360))));
        stepUntilDone(after, 100);
        after.get(0, TimeUnit.SECONDS);
    }

    @Test
    void shouldReadTachoThroughMotorSensorAndOtherSensorsThroughDriver() throws Exception {
        open();
        platform.run(MotorCommand.of("move", List.of(MotorTarget.rotate("B", 90, 90))));
        for (int i = 0; i < 50; i++) {
            step();
        }
        assertEquals(motors.position.get("B"), platform.readRaw("left-tacho").get(0, TimeUnit.SECONDS), 1e-9);
        assertEquals(42.0, platform.readRaw("sonar").get(0, TimeUnit.SECONDS));
        assertTrue(platform.readRaw("nothing").isCompletedExceptionally());
    }

    @Test
    void shouldRejectCommandForUnknownPort() throws Exception {
        open();
        IllegalArgumentException e = assertThrows(IllegalArgumentException.class,
                () -> platform.run(MotorCommand.of("bad", List.of(MotorTarget.run("Z", 1)))));
        assertTrue(e.getMessage().contains("port Z"), e.getMessage());
        assertFalse(platform.hasEncoder("Z"));
    }

    @Test
    void shouldStopMotorsWhenContinuousCommandIsNotRefreshed() throws Exception {
        open();
        platform.run(new MotorCommand("drive", List.of(MotorTarget.run("B", 100)), io.robomw.api.spi.CommandPriority.NORMAL, Duration.ofMillis(500)));
        step();
        assertEquals(100.0, motors.speed.get("B"));
        for (int i = 0; i < 52; i++) {
            step();
        }
        assertEquals(0.0, motors.speed.get("B"), "the watchdog stopped the motor");
    }

    @Test
    void aBrickThatStopsAtItsLimitEndsTheRotationWhenItSaysSoEvenOnABusyLink() throws Exception {
        motors.brickStopsAtLimit = true;
        motors.commandLag = 5;
        open();
        for (int[] leg : new int[][] {{-90, 90}, {360, 90}, {-45, 180}, {200, 90}}) {
            CompletableFuture<Void> rotate = platform.run(MotorCommand.of("rotate", List.of(MotorTarget.rotate("B", leg[0], leg[1]))));
            stepUntilDone(rotate, 1000);
            rotate.get(0, TimeUnit.SECONDS);
        }
        assertEquals(-90 + 360 - 45 + 200, motors.position.get("B"), 1e-9, "every rotation ran to the brick's limit, none was cut short");
    }

    @Test
    void aBlockedMotorFailsItsRotationWithAClearErrorInsteadOfWaitingForever() throws Exception {
        motors.blocked = true;
        open();
        CompletableFuture<Void> rotate = platform.run(MotorCommand.of("rotate", List.of(MotorTarget.rotate("B", 360, 360))));
        stepUntilDone(rotate, 600);
        RobotException e = assertInstanceOf(RobotException.class, assertThrows(ExecutionException.class, () -> rotate.get(0, TimeUnit.SECONDS)).getCause());
        assertTrue(e.getMessage().contains("motor B did not finish turning 360°") && e.getMessage().contains("5.0 s"), e.getMessage());
        assertEquals(0.0, motors.speed.get("B"), "stopped");
    }

    @Test
    void aRotationSlowerThanAskedGoesOnWhileItsEncoderShowsProgress() throws Exception {
        motors.share = 0.15; // 6.7 s for what takes 1 s at speed: beyond the 5 s a rotation may show no progress
        open();
        CompletableFuture<Void> rotate = platform.run(MotorCommand.of("rotate", List.of(MotorTarget.rotate("B", 360, 360))));
        stepUntilDone(rotate, 2000);
        rotate.get(0, TimeUnit.SECONDS);
        assertEquals(360, motors.position.get("B"), 30, "it turned its rotation");
        assertEquals(0.0, motors.speed.get("B"), "stopped at its target");
    }

    private static MotorCommand drive(double left, double right) {
        return new MotorCommand("drive", List.of(MotorTarget.run("B", left), MotorTarget.run("C", right)),
                io.robomw.api.spi.CommandPriority.NORMAL, Duration.ofMillis(500));
    }

    @Test
    void aDetachedDriveKeepsTheMotorsTurningWhileRefreshedAndStopsWhenItIsNot() throws Exception {
        open();
        for (int i = 0; i < 40; i++) {
            platform.runDetached(drive(100 + i, -100 - i));
            step();
            assertEquals(100.0 + i, motors.speed.get("B"));
            assertEquals(-100.0 - i, motors.speed.get("C"));
        }
        for (int i = 0; i < 52; i++) {
            step();
        }
        assertEquals(0.0, motors.speed.get("B"), "the watchdog stopped the motors");
        assertEquals(0.0, motors.speed.get("C"));
    }

    @Test
    void aMoveSubmittedAfterADetachedDriveInTheSameCycleTakesItsMotor() throws Exception {
        open();
        platform.runDetached(drive(100, 100));
        step();
        platform.runDetached(drive(50, 60));
        CompletableFuture<Void> move = platform.run(MotorCommand.of("move", List.of(MotorTarget.rotate("B", 90, 90))));
        step();
        assertEquals(90.0, motors.speed.get("B"), "the move runs B");
        assertEquals(0.0, motors.speed.get("C"), "the interrupted drive stopped C");
        stepUntilDone(move, 1000);
        move.get(0, TimeUnit.SECONDS);
    }

    @Test
    void aDetachedDriveAfterAMoveInterruptsItAndStopsAfterIt() throws Exception {
        open();
        CompletableFuture<Void> move = platform.run(MotorCommand.of("move", List.of(MotorTarget.rotate("B", 720, 90))));
        step();
        platform.runDetached(drive(30, 40));
        step();
        assertInstanceOf(CommandPreemptedException.class, assertThrows(ExecutionException.class, () -> move.get(0, TimeUnit.SECONDS)).getCause());
        assertEquals(30.0, motors.speed.get("B"));
        assertEquals(40.0, motors.speed.get("C"));

        platform.runDetached(drive(30, 40));
        platform.stopAll();
        platform.runDetached(drive(70, 70)); // after the stop, in its cycle: refused
        step();
        assertEquals(0.0, motors.speed.get("B"));
        assertEquals(0.0, motors.speed.get("C"));
    }

    @Test
    void aDetachedDriveIsDroppedWhileTheLinkIsDown() throws Exception {
        open();
        motors.failNext = new IOException("brick unplugged");
        platform.runDetached(drive(100, 100));
        step();
        step();
        int sent = motors.sent.size();
        platform.runDetached(drive(80, 80));
        step();
        assertEquals(sent, motors.sent.size(), "nothing was handed to the link");

        motors.failNext = null;
        step();
        platform.runDetached(drive(80, 80));
        step();
        assertEquals(80.0, motors.speed.get("B"), "once the link is back, drives run again");
    }

    private static final MotorState BRAKED_B = MotorState.stopped("B", MotorState.StopMode.BRAKE);
    private static final MotorState BRAKED_C = MotorState.stopped("C", MotorState.StopMode.BRAKE);

    @Test
    void aStopCompletesOnceTheLinkSideHasWrittenTheBrakesAndAMoveAfterItIsAdmitted() throws Exception {
        open();
        platform.run(drive(100, 100));
        step();
        CompletableFuture<Void> stop = platform.stopAll();
        assertFalse(stop.isDone(), "not before the cycle that applies it has handed it to the link");
        step();
        stop.get(0, TimeUnit.SECONDS);
        assertEquals(List.of(BRAKED_B, BRAKED_C), motors.sent.get(motors.sent.size() - 1), "the brakes were written when the stop completed");

        CompletableFuture<Void> move = platform.run(MotorCommand.of("move", List.of(MotorTarget.rotate("B", 90, 90))));
        step();
        assertFalse(move.isCompletedExceptionally(), "the move after the stop is admitted, not held by 'stop'");
        assertEquals(90.0, motors.speed.get("B"));
        stepUntilDone(move, 1000);
        move.get(0, TimeUnit.SECONDS);
    }

    @Test
    void aStopOfMotorsAtRestCompletesAtTheNextCycleWithoutWritingAgain() throws Exception {
        open();
        CompletableFuture<Void> stop = platform.stopAll();
        step();
        stop.get(0, TimeUnit.SECONDS);
        assertEquals(List.of(), motors.sent, "the motors were braked already: nothing to write");
    }

    @Test
    void aStopOnADeadLinkFailsNamingTheRobotAndItsBrakesGoOutWhenTheLinkReturns() throws Exception {
        open();
        motors.failNext = new IOException("brick unplugged");
        platform.run(drive(100, 100));
        step();
        step();
        CompletableFuture<Void> stop = platform.stopAll();
        RobotLinkException e = assertInstanceOf(RobotLinkException.class, assertThrows(ExecutionException.class, () -> stop.get(0, TimeUnit.SECONDS)).getCause());
        assertTrue(e.getMessage().contains("robot 'fake'") && e.getMessage().contains("link"), e.getMessage());

        motors.failNext = null;
        step();
        step();
        assertEquals(0.0, motors.speed.get("B"));
        assertEquals(0.0, motors.speed.get("C"));
    }

    @Test
    void aStopWhoseBatchTheLinkFailsToWriteFailsNamingTheRobot() throws Exception {
        open();
        platform.run(drive(100, 100));
        step();
        CompletableFuture<Void> stop = platform.stopAll();
        motors.failNext = new IOException("brick unplugged");
        step();
        RobotLinkException e = assertInstanceOf(RobotLinkException.class, assertThrows(ExecutionException.class, () -> stop.get(0, TimeUnit.SECONDS)).getCause());
        assertTrue(e.getMessage().contains("robot 'fake'") && e.getMessage().contains("brick unplugged"), e.getMessage());
    }

    @Test
    void aCancelledRunBrakesItsMotorsAtTheNextCycle() throws Exception {
        open();
        CompletableFuture<Void> move = platform.run(MotorCommand.of("move", List.of(MotorTarget.rotate("B", 720, 90), MotorTarget.rotate("C", 720, 90))));
        step();
        assertEquals(90.0, motors.speed.get("B"));
        move.cancel(true);
        step();
        assertEquals(List.of(BRAKED_B, BRAKED_C), motors.sent.get(motors.sent.size() - 1), "the cancelled move's end action braked its motors");
        assertEquals(0.0, motors.speed.get("B"));
        assertEquals(Set.of(), platform.actionThread().actuatorsInUse());
    }

    @Test
    void aRunCancelledBeforeItsCycleNeverStarts() throws Exception {
        open();
        CompletableFuture<Void> move = platform.run(MotorCommand.of("move", List.of(MotorTarget.rotate("B", 720, 90))));
        move.cancel(true);
        step();
        assertEquals(List.of(), motors.sent, "nothing was started");
    }
}
