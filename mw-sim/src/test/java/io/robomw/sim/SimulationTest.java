package io.robomw.sim;

import io.robomw.api.Pose;
import io.robomw.api.Position;
import io.robomw.api.ReturnType;
import io.robomw.api.Robot;
import io.robomw.api.RobotException;
import io.robomw.api.SensorType;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicBoolean;
import java.util.concurrent.locks.LockSupport;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * Robots driven through all three layers (Instruction, Configuration, Platform) in a dyn4j world.
 * Every check is on the simulated robot's true pose, not on its own odometry.
 */
class SimulationTest {

    private static final Duration LIMIT = Duration.ofSeconds(120);

    /** The paper's NXT robot, as a file the world points to; its platform is nxt, and the simulation runs it on sim. */
    static final String ROBOT = """
            name: scout
            platform: nxt
            connection: { port: /dev/rfcomm0 }
            drive:
              wheel_diameter: 0.056
              track_width: 0.112
              max_speed: 0.30
              left:  { port: B }
              right: { port: C }
            body: { length: 0.20, width: 0.15, mass: 0.6, friction: 0.8 }
            sensors:
              - { name: sonar, type: sonar, position: front, port: S4, conversion: { scale: 0.01 }, options: { noise: %s } }
              - { name: bumper, type: touch, position: front, port: S1 }
              - { name: floor, type: light, position: bottom, port: S3, conversion: { scale: 0.000977517 } }
              - { name: compass, type: compass, position: center, port: S2 }
            """;

    @TempDir
    Path dir;

    private Simulation world(double x, double y, double heading, double noise, String extra) throws IOException {
        Files.writeString(dir.resolve("scout.yaml"), ROBOT.formatted(noise));
        Files.writeString(dir.resolve("world.yaml"), """
                name: test
                arena: { width: 4, height: 3 }
                seed: 7
                physics_hz: 100
                floor:
                  - { x: 3.0, y: 0.0, width: 1.0, height: 3.0, brightness: 0.1 }
                robots:
                  - { robot: scout.yaml, name: r1, x: %s, y: %s, heading: %s }
                %s
                """.formatted(x, y, heading, extra));
        return Simulation.load(dir.resolve("world.yaml"));
    }

    private static Pose truePose(Simulation sim) {
        return sim.world().robot("r1").pose();
    }

    @Test
    void shouldEndOneMetreMoveWithinOneCentimetre() throws Exception {
        try (Simulation sim = world(1, 1.5, 0, 0, "")) {
            Robot r = sim.robot("r1");
            sim.run(LIMIT, () -> r.move(1.0, 0.2));
            Pose p = truePose(sim);
            assertEquals(2.0, p.x(), 0.01, "x after move(1.0, 0.2)");
            assertEquals(1.5, p.y(), 0.002);
            assertEquals(1.0, r.pose().x(), 0.01, "odometry agrees");
        }
    }

    @Test
    void shouldTurnQuarterWithinOneDegree() throws Exception {
        try (Simulation sim = world(2, 1.5, 0, 0, "")) {
            Robot r = sim.robot("r1");
            sim.run(LIMIT, () -> r.turn(Math.PI / 2, 1.0));
            assertEquals(90.0, Math.toDegrees(truePose(sim).heading()), 1.0);
            assertEquals(2.0, truePose(sim).x(), 0.005, "a turn on the spot does not travel");
        }
    }

    @Test
    void shouldReturnWithinThreeCentimetresAfterOneMetreSquare() throws Exception {
        try (Simulation sim = world(1, 1, 0, 0, "")) {
            Robot r = sim.robot("r1");
            Pose start = truePose(sim);
            sim.run(LIMIT, () -> {
                for (int i = 0; i < 4; i++) {
                    r.move(1.0, 0.2);
                    r.turn(Math.PI / 2, 1.0);
                }
            });
            assertTrue(truePose(sim).distanceTo(start) < 0.03, "back within 3 cm, got " + truePose(sim).distanceTo(start));
        }
    }

    @Test
    void shouldReadSixtyCentimetresFacingWallSixtyCentimetresAway() throws Exception {
        // Arena wall at x = 4; the sonar sits on the front edge, 0.10 m ahead of the centre.
        try (Simulation sim = world(4 - 0.60 - 0.10, 1.5, 0, 0, "")) {
            Robot r = sim.robot("r1");
            double[] cm = new double[1];
            sim.run(LIMIT, () -> cm[0] = r.getValue(Position.FRONT, SensorType.SONAR, ReturnType.CENTIMETERS));
            assertEquals(60.0, cm[0], 1.0);
        }
    }

    @Test
    void shouldPressBumperAndStopAtWallWhenDrivingIntoIt() throws Exception {
        try (Simulation sim = world(3.5, 1.5, 0, 0, "")) {
            Robot r = sim.robot("r1");
            double[] pressedBefore = new double[1];
            double[] pressedAfter = new double[1];
            sim.run(LIMIT, () -> {
                pressedBefore[0] = r.getValue(Position.FRONT, SensorType.TOUCH, ReturnType.BOOLEAN);
                CompletableFuture<Void> drive = r.moveAsync(1.0, 0.2);
                while (r.getValue(Position.FRONT, SensorType.TOUCH, ReturnType.BOOLEAN) == 0.0) {
                    assertFalse(drive.isDone(), "the 1 m move cannot finish: the wall is 0.4 m away");
                }
                pressedAfter[0] = 1.0;
                r.stop();
            });
            assertEquals(0.0, pressedBefore[0]);
            assertEquals(1.0, pressedAfter[0]);
            double front = truePose(sim).x() + 0.10;
            assertTrue(front <= 4.0 + 0.005, "the robot's front is at the wall, not through it: " + front);
            assertTrue(front >= 3.98, "the robot reached the wall: " + front);
            sim.runFor(Duration.ofSeconds(1));
            assertEquals(front, truePose(sim).x() + 0.10, 0.002, "stopped");
        }
    }

    @Test
    void shouldReadDarkFloorPatchWithLightSensor() throws Exception {
        try (Simulation sim = world(3.5, 1.5, 0, 0, "")) {
            Robot r = sim.robot("r1");
            double[] percent = new double[1];
            sim.run(LIMIT, () -> percent[0] = r.getValue(Position.BOTTOM, SensorType.LIGHT, ReturnType.PERCENT));
            assertEquals(10.0, percent[0], 0.1);
        }
    }

    @Test
    void shouldTimeEveryPhaseOfEveryStepOnTheProfileClockAndStopWhenAskedTo() throws Exception {
        try (Simulation sim = world(1, 1, 0, 0, "")) {
            long[] now = {0};
            // a clock that moves 1 ns each time it is read: each phase of each step gets 1 ns
            sim.world().profile(() -> ++now[0]);
            sim.runFor(Duration.ofMillis(100));
            long[] phases = sim.world().phaseNanos();
            assertEquals(SimWorld.Phase.values().length, phases.length);
            for (SimWorld.Phase p : SimWorld.Phase.values()) {
                assertEquals(10, phases[p.ordinal()], p + ": ten steps at 100 Hz, one reading each");
            }
            sim.world().profile(null);
            long read = now[0];
            sim.runFor(Duration.ofMillis(100));
            assertEquals(read, now[0], "not profiling: the clock is not read");
        }
    }

    @Test
    void shouldGiveIdenticalTrajectoriesForSameSeed() throws Exception {
        List<Pose> first = wanderTrace();
        List<Pose> second = wanderTrace();
        assertEquals(first, second, "bit for bit");
    }

    /** A program that reacts to a noisy sonar, so any nondeterminism shows in the trajectory. */
    private List<Pose> wanderTrace() throws IOException {
        try (Simulation sim = world(1, 1, 0.3, 0.02, "")) {
            Robot r = sim.robot("r1");
            List<Pose> trace = new ArrayList<>();
            sim.run(LIMIT, () -> {
                for (int i = 0; i < 40; i++) {
                    double d = r.getValue(Position.FRONT, SensorType.SONAR, ReturnType.METERS);
                    if (d < 0.5) {
                        r.turn(1.0 + d, 1.5);
                    } else {
                        r.move(Math.min(0.3, d - 0.3), 0.25);
                    }
                    trace.add(truePose(sim));
                }
            });
            return trace;
        }
    }

    @Test
    void shouldRunTwoRobotProgramsInParallelInLockstep() throws Exception {
        try (Simulation sim = world(1, 1, 0, 0, "  - { robot: scout.yaml, name: r2, x: 1, y: 2, heading: 0 }")) {
            Robot r1 = sim.robot("r1");
            Robot r2 = sim.robot("r2");
            sim.run(LIMIT, () -> r1.move(1.0, 0.2), () -> r2.move(0.5, 0.1));
            assertEquals(2.0, sim.world().robot("r1").pose().x(), 0.01);
            assertEquals(1.5, sim.world().robot("r2").pose().x(), 0.01);
            assertEquals(5.0, sim.world().time(), 0.1, "both took 5 s of simulated time, in parallel");
        }
    }

    @Test
    void shouldExplainHowToCallRobotsWhenNothingAdvancesTime() throws Exception {
        try (Simulation sim = world(1, 1, 0, 0, "")) {
            RobotException e = assertThrows(RobotException.class, () -> sim.robot("r1").move(0.1, 0.1));
            assertTrue(e.getMessage().contains("Simulation.run"), e.getMessage());
        }
    }

    @Test
    void shouldDriveInRealTimeFromAnyThread() throws Exception {
        try (Simulation sim = world(1, 1.5, 0, 0, "")) {
            sim.startRealTime(20);
            sim.robot("r1").move(0.2, 0.2);
            sim.stopRealTime();
            assertEquals(1.2, truePose(sim).x(), 0.01);
        }
    }

    @Test
    void shouldGiveAReaderOnAnotherThreadWholePosesOfOneStepNeverPartsOfTwo() throws Exception {
        // The true pose is kept in three fields written at every step (no object per step); a viewer
        // on its own thread must still read x, y and heading of one and the same step.
        try (Simulation sim = world(2, 1.5, 0, 0, "")) {
            SimRobot body = sim.world().robot("r1");
            Robot r = sim.robot("r1");
            java.util.Set<Pose> stepped = java.util.concurrent.ConcurrentHashMap.newKeySet();
            stepped.add(body.pose());
            sim.addStepListener(() -> {
                stepped.add(body.pose());
                r.drive(0.2, 1.0); // a circle: x, y and heading all change at every step
            });
            java.util.Set<Pose> distinct = java.util.concurrent.ConcurrentHashMap.newKeySet();
            java.util.concurrent.atomic.AtomicBoolean stop = new java.util.concurrent.atomic.AtomicBoolean();
            java.util.concurrent.CountDownLatch reading = new java.util.concurrent.CountDownLatch(1);
            Thread viewer = new Thread(() -> {
                while (!stop.get()) {
                    distinct.add(body.pose());
                    reading.countDown();
                }
            }, "pose-viewer");
            viewer.start();
            try {
                assertTrue(reading.await(60, java.util.concurrent.TimeUnit.SECONDS), "the viewer thread runs");
                // Steps until the viewer, on a loaded machine given the processor now and then, has read 50 of them
                for (int i = 0; i < 3600 && distinct.size() < 50; i++) {
                    sim.runFor(Duration.ofSeconds(1));
                }
            } finally {
                stop.set(true);
                viewer.join();
            }
            assertTrue(distinct.size() >= 50, "the viewer saw the robot move: " + distinct.size() + " distinct poses");
            for (Pose p : distinct) {
                assertTrue(stepped.contains(p), "read " + p + ", which no step left the robot in");
            }
        }
    }

    @Test
    void shouldCatchUpWithoutLosingSimulatedTimeAfterItsThreadWasHeldUp() throws Exception {
        assertEquals(0.0, simulatedTimeLostAfterAStallOf(Duration.ofMillis(500)), 1e-6,
                "every step after half a second held up stood for its own period: the run caught up");
    }

    @Test
    void shouldGoOnFromNowRatherThanRaceAfterALongStall() throws Exception {
        assertTrue(simulatedTimeLostAfterAStallOf(Duration.ofMillis(1500)) >= 1.5 - 0.011,
                "a run held up for longer than a second does not race through the missed time");
    }

    /**
     * Holds the real-time thread up once, in a step listener (as a long collection would), then
     * returns how much wall-clock time the steps' schedule skipped over the next simulated second:
     * the wall-clock time the step one simulated second later stands for, minus one second.
     */
    private double simulatedTimeLostAfterAStallOf(Duration stall) throws Exception {
        try (Simulation sim = world(1, 1.5, 0, 0, "")) {
            sim.startRealTime(1);
            AtomicBoolean held = new AtomicBoolean();
            long[] wall0 = new long[1];
            double[] time0 = new double[1];
            double[] lost = new double[1];
            CountDownLatch secondLater = new CountDownLatch(1);
            sim.addStepListener(() -> {
                if (!held.getAndSet(true)) {
                    wall0[0] = sim.stepWallNanos();
                    time0[0] = sim.world().time();
                    long end = System.nanoTime() + stall.toNanos();
                    for (long left = stall.toNanos(); left > 0; left = end - System.nanoTime()) {
                        LockSupport.parkNanos(left);
                    }
                } else if (secondLater.getCount() > 0 && sim.world().time() >= time0[0] + 1.0 - 1e-9) {
                    lost[0] = (sim.stepWallNanos() - wall0[0]) / 1e9 - (sim.world().time() - time0[0]);
                    secondLater.countDown();
                }
            });
            assertTrue(secondLater.await(30, TimeUnit.SECONDS), "a simulated second passed after the stall");
            sim.stopRealTime();
            return lost[0];
        }
    }
}
