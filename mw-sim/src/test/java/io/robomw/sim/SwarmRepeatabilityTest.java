package io.robomw.sim;

import io.robomw.api.Pose;
import io.robomw.sim.programs.WanderController;
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
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * A crowded swarm, large enough that every per-robot pass of a step is split between threads,
 * gives the same trajectories bit for bit whatever the number of threads stepping it: robots
 * that see each other with noisy range sensors (every sensor its own seeded stream), bump into
 * each other and the walls, and are driven through all three layers by the wander controller.
 */
class SwarmRepeatabilityTest {

    private static final int ROBOTS = 160;

    @TempDir
    Path dir;

    @Test
    void shouldGiveTheSameTrajectoriesBitForBitWhateverTheNumberOfThreads() throws IOException {
        WorldDescription world = crowdedWorld();
        List<Pose> oneThread = sameOnOneTwoAndThreeThreads(world);
        long moved = 0;
        for (int i = 0; i < ROBOTS; i++) {
            Pose start = world.robots().get(i).start();
            if (oneThread.get(i).distanceTo(start) > 0.2) {
                moved++;
            }
        }
        assertTrue(moved > ROBOTS / 4, "many robots wandered off (else the test proves little): " + moved + " of " + ROBOTS);
    }

    @Test
    void shouldGiveTheSameTrajectoriesBitForBitWhateverTheNumberOfThreadsOnTheSwarmEngine() throws IOException {
        // 160 robots in 5 batches of the engine's contact detection (split between threads from 2 on),
        // 0.13 m apart: they start touching and push and turn against each other
        WorldDescription world = crowdedWorld(0.13).withEngine(WorldDescription.PhysicsEngine.SWARM);
        List<Pose> oneThread = sameOnOneTwoAndThreeThreads(world);
        long moved = 0;
        for (int i = 0; i < ROBOTS; i++) {
            Pose start = world.robots().get(i).start();
            Pose end = oneThread.get(i);
            if (end.distanceTo(start) > 0.05 || Math.abs(Pose.normalize(end.heading() - start.heading())) > 0.3) {
                moved++;
            }
        }
        assertTrue(moved > ROBOTS / 2, "most robots moved or turned (else the test proves little): " + moved + " of " + ROBOTS);
        assertTrue(contactsSeen > 1000, "robots touched each other or the walls (else the solve's order proves nothing): " + contactsSeen);
    }

    /** Contacts counted after each step of the last swarm-engine run. */
    private long contactsSeen;

    @Test
    void shouldWanderExactlyAsAStepListenerWhenTheControllerRunsInTheWorldsPass() throws IOException {
        WorldDescription world = crowdedWorld();
        List<Pose> inPass = run(world, 2);
        List<Pose> asListener = run(world, 2, false);
        assertEquals(asListener, inPass, "the controller's ticks inside the world's pass against the same controller as a step listener");
    }

    /** The poses of every robot after 4 simulated seconds. */
    /** @return the poses after a run on the stepping thread alone, checked equal bit for bit to runs on 2 and 3 threads */
    private List<Pose> sameOnOneTwoAndThreeThreads(WorldDescription world) {
        List<Pose> oneThread = run(world, 1);
        assertEquals(oneThread, run(world, 2), "2 threads against the stepping thread alone");
        assertEquals(oneThread, run(world, 3), "3 threads against the stepping thread alone");
        return oneThread;
    }

    private List<Pose> run(WorldDescription world, int threads) {
        return run(world, threads, true);
    }

    /** The poses of every robot after 4 simulated seconds, the controller in the world's pass or as a step listener. */
    private List<Pose> run(WorldDescription world, int threads, boolean inPass) {
        try (Simulation sim = Simulation.create(world, threads)) {
            if (inPass) {
                WanderController.install(sim, 10, 3);
            } else {
                sim.addStepListener(new WanderController(sim, 10, 3));
            }
            if (sim.world().physics() instanceof io.robomw.sim.physics.SwarmPhysics swarm) {
                contactsSeen = 0;
                sim.addStepListener(() -> contactsSeen += swarm.contactCount());
            }
            sim.runFor(Duration.ofSeconds(4));
            List<Pose> poses = new ArrayList<>();
            for (SimRobot r : sim.world().robots()) {
                poses.add(r.pose());
            }
            return poses;
        }
    }

    /** 160 robots 0.35 m apart (their 0.5 m sensors see their neighbours), noisy sensors, 50 Hz physics. */
    private WorldDescription crowdedWorld() throws IOException {
        return crowdedWorld(0.35);
    }

    /** 160 robots the given distance apart, noisy sensors, 50 Hz physics. */
    private WorldDescription crowdedWorld(double spacing) throws IOException {
        Path robot = dir.resolve("bot.yaml");
        SwarmRobotFile.write(robot, i -> i % 2 == 0 ? "10" : "25");
        int cols = 16;
        List<WorldDescription.RobotPlacement> placements = new ArrayList<>();
        for (int i = 0; i < ROBOTS; i++) {
            placements.add(new WorldDescription.RobotPlacement(robot, "r" + i,
                    new Pose(0.3 + spacing * (i % cols), 0.3 + spacing * (i / cols), (i * 2.399963) % (2 * Math.PI))));
        }
        return new WorldDescription("crowd", 0.3 + spacing * cols, 0.3 + spacing * (ROBOTS / cols), true, 0.1, 0.8, List.of(), List.of(),
                placements, 11, 50, "test");
    }
}
