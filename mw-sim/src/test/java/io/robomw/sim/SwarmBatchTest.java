package io.robomw.sim;

import io.robomw.api.Pose;
import io.robomw.api.Robot;
import io.robomw.api.spi.FailurePolicy;
import io.robomw.api.spi.PlatformServices;
import io.robomw.sim.programs.WanderController;
import io.robomw.testkit.RecordingFailures;
import io.robomw.sim.world.WorldDescription;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * The robots of one robot file are driven together, in a batch over arrays, through the same three
 * layers as one robot's own stack: the wander controller gives the same trajectories, bit for bit,
 * whether it drives them in their batch or each through its own {@code Robot}; a robot a program
 * addresses one by one leaves the batch, moves as commanded through its own execution action
 * thread, and keeps its odometry; a failure of one batched robot's part of a step brakes that
 * robot only.
 */
class SwarmBatchTest {

    @TempDir
    Path dir;

    @Test
    void wandersInBatchesExactlyAsEveryRobotThroughItsOwnStack() throws IOException {
        for (WorldDescription.PhysicsEngine engine : WorldDescription.PhysicsEngine.values()) {
            WorldDescription world = crowd(120, 0.3).withEngine(engine);
            List<Pose> batched = wander(world, false);
            List<Pose> oneByOne = wander(world, true);
            assertEquals(oneByOne, batched, engine + ": the batch against every robot through its own Robot, ConfiguredRobot and action thread");
            long moved = 0;
            for (int i = 0; i < batched.size(); i++) {
                moved += batched.get(i).distanceTo(world.robots().get(i).start()) > 0.2 ? 1 : 0;
            }
            assertTrue(moved > batched.size() / 4, engine + ": many robots wandered (else the test proves little): " + moved);
        }
    }

    /** Every robot's true pose after 6 simulated seconds of wandering; {@code promoteAll}: each addressed one by one first. */
    private List<Pose> wander(WorldDescription world, boolean promoteAll) {
        try (Simulation sim = Simulation.create(world, 2)) {
            int batched = 0;
            for (SimRobot r : sim.world().robots()) {
                batched += sim.world().batched(r.index()) ? 1 : 0;
            }
            assertEquals(world.robots().size(), batched, "every robot of the file starts in its batch");
            if (promoteAll) {
                for (Robot r : sim.robots()) {
                    assertEquals(new Pose(0, 0, 0), r.pose(), "a pose read promotes the robot; its odometry starts where it stands");
                }
                for (SimRobot r : sim.world().robots()) {
                    assertFalse(sim.world().batched(r.index()), r.name() + " was promoted");
                }
            }
            WanderController.install(sim, 10, 5);
            sim.runFor(Duration.ofSeconds(6));
            List<Pose> poses = new ArrayList<>();
            for (SimRobot r : sim.world().robots()) {
                poses.add(r.pose());
            }
            return poses;
        }
    }

    @Test
    void aRobotAddressedOneByOneLeavesItsBatchAndMovesAsCommanded() throws IOException {
        WorldDescription world = crowd(12, 1.0);
        try (Simulation sim = Simulation.create(world, 2)) {
            SimWorld w = sim.world();
            // every robot still in its batch drives straight on at 0.05 m/s, through the batch
            w.addRobotController(5, i -> {
                if (w.batched(i)) {
                    w.driveBatched(i, 0.05, 0);
                }
            });
            sim.runFor(Duration.ofSeconds(2));
            Pose start = world.robots().get(3).start();
            SimRobot body = w.robot("r3");
            double before = body.pose().distanceTo(start);
            assertEquals(0.1, before, 0.01, "driven by its batch for 2 s at 0.05 m/s");
            Robot r3 = sim.robot("r3");
            sim.run(Duration.ofSeconds(30), () -> {
                r3.move(0.2, 0.1);
                r3.turn(Math.PI / 2, 0.8);
            });
            assertFalse(w.batched(body.index()), "r3 left its batch");
            assertTrue(w.batched(w.robot("r4").index()), "the others stay in theirs");
            Pose end = body.pose();
            assertEquals(0.3, end.distanceTo(start), 0.01, "0.1 m by its batch, then 0.2 m as commanded");
            assertEquals(Pose.normalize(start.heading() + Math.PI / 2), end.heading(), 0.03, "then a quarter turn left");
            Pose odometry = r3.pose();
            assertEquals(0.3, Math.hypot(odometry.x(), odometry.y()), 0.01, "its odometry went on from its batch's");
            assertEquals(Math.PI / 2, odometry.heading(), 0.03);
            double othersBefore = w.robot("r4").pose().distanceTo(world.robots().get(4).start());
            sim.runFor(Duration.ofSeconds(1));
            assertEquals(othersBefore + 0.05, w.robot("r4").pose().distanceTo(world.robots().get(4).start()), 0.005, "the batch drives on");
            assertEquals(end.distanceTo(start), body.pose().distanceTo(start), 1e-3, "r3 stands where its program left it");
        }
    }

    @Test
    void aRobotIsPromotedWhileTheWorldRunsInRealTimeOnItsOwnThread() throws Exception {
        WorldDescription world = crowd(6, 1.0);
        try (Simulation sim = Simulation.create(world, 2)) {
            SimWorld w = sim.world();
            w.addRobotController(5, i -> {
                if (w.batched(i) && i != 2) {
                    w.driveBatched(i, 0.05, 0);
                }
            });
            sim.startRealTime(4);
            try {
                Robot r2 = sim.robot("r2");
                r2.move(0.15, 0.1); // promoted between two steps of the real-time thread, then moved by its own stack
                assertFalse(w.batched(w.robot("r2").index()));
                assertEquals(0.15, w.robot("r2").pose().distanceTo(world.robots().get(2).start()), 0.01, "it moved as commanded");
                assertEquals(0.15, r2.pose().x(), 0.01, "and its odometry says so");
                double r3 = w.robot("r3").pose().distanceTo(world.robots().get(3).start());
                io.robomw.testkit.Await.until("the batch drives r3 on", Duration.ofSeconds(30),
                        () -> w.robot("r3").pose().distanceTo(world.robots().get(3).start()) > r3 + 0.02);
            } finally {
                sim.stopRealTime();
            }
        }
    }

    @Test
    void aFailureOfOneBatchedRobotBrakesThatRobotOnlyAndIsReported() throws IOException {
        RecordingFailures policy = new RecordingFailures();
        Files.writeString(dir.resolve("scout.yaml"), """
                name: scout
                platform: sim
                drive: { wheel_diameter: 0.056, track_width: 0.112, max_speed: 0.30, left: { port: B }, right: { port: C } }
                body: { length: 0.20, width: 0.15, mass: 0.6, friction: 0.8 }
                """);
        Files.writeString(dir.resolve("world.yaml"), """
                name: failing
                arena: { width: 4, height: 3 }
                robots:
                  - { robot: scout.yaml, name: r1, x: 1, y: 1, heading: 0 }
                  - { robot: scout.yaml, name: r2, x: 1, y: 2, heading: 0 }
                """);
        try (Simulation sim = Simulation.load(dir.resolve("world.yaml"), java.util.Set.of(), PlatformServices.none().with(FailurePolicy.class, policy))) {
            SimWorld w = sim.world();
            int r1 = w.robot("r1").index();
            assertTrue(w.batched(r1) && w.batched(w.robot("r2").index()), "both robots of scout.yaml are batched");
            boolean[] broken = {false};
            boolean[] thrown = {false};
            w.addRobotController(5, i -> {
                if (broken[0] && i == r1 && !thrown[0]) {
                    thrown[0] = true;
                    throw new IllegalStateException("controller bug on this robot");
                }
                w.driveBatched(i, 0.1, 0);
            });
            sim.runFor(Duration.ofSeconds(1));
            broken[0] = true;
            assertTrue(sim.runUntil(() -> thrown[0], Duration.ofSeconds(1)), "the controller failed on r1");
            assertEquals(1, policy.reports().size(), "reported once: " + policy.reports());
            RecordingFailures.Report report = policy.reports().get(0);
            assertFalse(report.died());
            assertTrue(report.owner().contains("r1") && report.failure().getMessage().contains("controller bug"), report.toString());
            Pose r1Then = w.robot("r1").pose();
            Pose r2Then = w.robot("r2").pose();
            sim.runFor(Duration.ofMillis(80)); // before the next tick: r1 braked, r2 drives on
            assertTrue(w.robot("r2").pose().distanceTo(r2Then) > 0.006, "r2 drives on: " + w.robot("r2").pose());
            // its body's velocities were not set in the step that failed: it goes on for that one step (0.002 m), then stands
            assertTrue(w.robot("r1").pose().distanceTo(r1Then) < 0.003, "r1's motors braked when its part of the step failed: " + w.robot("r1").pose());
            assertTrue(w.batched(r1), "a failed robot stays in its batch: its next drive starts it again");
        }
    }

    /** {@code n} robots of one file in a row of rows {@code spacing} apart, 8 range sensors each, 50 Hz physics. */
    private WorldDescription crowd(int n, double spacing) throws IOException {
        Path robot = dir.resolve("bot.yaml");
        SwarmRobotFile.write(robot, i -> "10");
        int cols = (int) Math.ceil(Math.sqrt(n));
        List<WorldDescription.RobotPlacement> placements = new ArrayList<>();
        for (int i = 0; i < n; i++) {
            placements.add(new WorldDescription.RobotPlacement(robot, "r" + i,
                    new Pose(0.5 + spacing * (i % cols), 0.5 + spacing * (i / cols), (i * 2.399963) % (2 * Math.PI))));
        }
        double side = 1 + spacing * cols;
        return new WorldDescription("batch", side, side, true, 0.1, 0.8, List.of(), List.of(), placements, 11, 50, "test");
    }
}
