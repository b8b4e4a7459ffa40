package io.robomw.sim.bench;

import io.robomw.api.Pose;
import io.robomw.sim.SimRobot;
import io.robomw.sim.SimWorld;
import io.robomw.sim.Simulation;
import io.robomw.sim.programs.WanderController;
import io.robomw.sim.physics.SwarmPhysics;
import io.robomw.sim.world.WorldDescription;

import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.Locale;

/**
 * A fingerprint of a swarm run, to check that a change to the engine keeps the trajectories bit for
 * bit: the swarm benchmark's world ({@code swarm50}: 50 Hz physics, 8 range sensors at 10 Hz, the
 * wander controller through the batches) run for a while, then one hash of every robot's pose, range
 * samples and trajectory (its length and its kept points), printed with the contacts seen. Run the
 * same arguments on two builds and compare the lines. Not a test (a long run); run on demand:
 * {@code PoseHash N SECONDS THREADS [SPACING]}, SPACING (default 1 m) below 1 crowds the robots so
 * that they touch (0.2 m: most robots push against others).
 */
public final class PoseHash {

    private PoseHash() {
    }

    /**
     * @param args N, simulated seconds, threads, and optionally the spacing between robots (metres)
     * @throws IOException if the temporary robot file cannot be written
     */
    public static void main(String[] args) throws IOException {
        int n = Integer.parseInt(args[0]);
        double seconds = Double.parseDouble(args[1]);
        int threads = Integer.parseInt(args[2]);
        double spacing = args.length > 3 ? Double.parseDouble(args[3]) : 1.0;
        SwarmBenchmark.Config config = new SwarmBenchmark.Config("swarm", 50, 10, SimWorld.RangeMethod.GRID, WorldDescription.PhysicsEngine.SWARM);
        Path dir = Files.createTempDirectory("posehash");
        try {
            WorldDescription d = SwarmBenchmark.world(n, config, dir);
            if (spacing != 1.0) {
                List<WorldDescription.RobotPlacement> moved = new ArrayList<>();
                for (WorldDescription.RobotPlacement r : d.robots()) {
                    Pose p = r.start();
                    moved.add(new WorldDescription.RobotPlacement(r.description(), r.name(), new Pose(p.x() * spacing, p.y() * spacing, p.heading())));
                }
                d = new WorldDescription(d.name(), d.width() * spacing, d.height() * spacing, d.walls(), d.wallThickness(), d.floorBrightness(),
                        d.obstacles(), d.patches(), moved, d.seed(), d.physicsHz(), d.trajectories(), d.engine(), d.source());
            }
            long contacts = 0;
            try (Simulation sim = Simulation.create(d, threads, config.method())) {
                WanderController.install(sim, 10, 1);
                SimWorld w = sim.world();
                for (int t = 0; t < Math.round(seconds * 10); t++) {
                    sim.runFor(Duration.ofMillis(100));
                    contacts += ((SwarmPhysics) w.physics()).contactCount();
                }
                long h = 1125899906842597L;
                for (SimRobot r : w.robots()) {
                    Pose p = r.pose();
                    h = 31 * h + Double.doubleToLongBits(p.x());
                    h = 31 * h + Double.doubleToLongBits(p.y());
                    h = 31 * h + Double.doubleToLongBits(p.heading());
                    for (int k = 0; k < r.rangeSensors().size(); k++) {
                        h = 31 * h + Double.doubleToLongBits(w.rangeReading(r.index(), k));
                    }
                    h = 31 * h + Double.doubleToLongBits(r.trajectory().length());
                    h = 31 * h + r.trajectory().samples();
                    for (double v : r.trajectory().snapshot()) {
                        h = 31 * h + Double.doubleToLongBits(v);
                    }
                }
                System.out.printf(Locale.ROOT, "N=%d t=%.1f threads=%d spacing=%s steps=%d hash=%016x contacts(sampled)=%d%n",
                        n, seconds, threads, spacing, w.steps(), h, contacts);
            }
        } finally {
            try (var files = Files.list(dir)) {
                for (Path f : files.toList()) {
                    Files.deleteIfExists(f);
                }
            }
            Files.deleteIfExists(dir);
        }
    }
}
