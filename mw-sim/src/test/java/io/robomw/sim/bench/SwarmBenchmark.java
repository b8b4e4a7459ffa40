package io.robomw.sim.bench;

import io.robomw.api.Pose;
import io.robomw.sim.SimWorld;
import io.robomw.sim.Simulation;
import io.robomw.sim.programs.WanderController;
import io.robomw.sim.world.WorldDescription;

import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.Locale;

/**
 * The swarm benchmark of the simulation issue: N differential-drive robots with 8 infra-red range
 * sensors each, wandering in a walled arena (one robot per square metre), driven through all three
 * layers by the {@link WanderController} at 10 Hz. Prints the real-time factor (simulated seconds
 * per wall-clock second) for each N and configuration, with, in the same run, the naive baseline:
 * a dyn4j world ray cast for every sensor ray (sensing on the same worker threads).
 *
 * <p>Run on demand: {@code bench/sim-swarm [N...]} (see {@code docs/benchmarks.md}). Not a test.
 */
public final class SwarmBenchmark {

    /** One configuration. */
    record Config(String label, double physicsHz, double sensorHz, SimWorld.RangeMethod method) {
    }

    private SwarmBenchmark() {
    }

    /**
     * @param args robot counts (default 100 1000 10000); {@code --quick} measures shorter
     * @throws IOException if the temporary robot file cannot be written
     */
    public static void main(String[] args) throws IOException {
        List<Integer> counts = new ArrayList<>();
        boolean quick = false;
        for (String a : args) {
            if (a.equals("--quick")) {
                quick = true;
            } else {
                counts.add(Integer.parseInt(a));
            }
        }
        if (counts.isEmpty()) {
            counts = List.of(100, 1000, 10_000);
        }
        List<Config> configs = List.of(
                new Config("grid, physics 50 Hz, sensors 10 Hz", 50, 10, SimWorld.RangeMethod.GRID),
                new Config("grid, physics 20 Hz, sensors 10 Hz", 20, 10, SimWorld.RangeMethod.GRID),
                new Config("naive dyn4j ray casts, physics 50 Hz, sensors 10 Hz", 50, 10, SimWorld.RangeMethod.DYN4J_RAYCAST),
                new Config("naive dyn4j ray casts, physics 50 Hz, sensors 50 Hz", 50, 50, SimWorld.RangeMethod.DYN4J_RAYCAST),
                new Config("naive dyn4j ray casts, everything at 10 Hz", 10, 10, SimWorld.RangeMethod.DYN4J_RAYCAST));
        System.out.printf(Locale.ROOT, "machine: %d processors, %s %s, max heap %d MiB%n", Runtime.getRuntime().availableProcessors(),
                System.getProperty("java.vm.name"), System.getProperty("java.version"), Runtime.getRuntime().maxMemory() >> 20);
        System.out.println("| N | configuration | real-time factor | ratio to naive (same rates) |");
        System.out.println("|---|---|---|---|");
        for (int n : counts) {
            double naiveSameRates = Double.NaN;
            double[] results = new double[configs.size()];
            for (int c = configs.size() - 1; c >= 0; c--) {
                Config config = configs.get(c);
                double simSeconds = quick ? 5 : Math.max(5, Math.min(60, 20_000.0 / n));
                results[c] = run(n, config, simSeconds);
                if (c == 2) {
                    naiveSameRates = results[c];
                }
            }
            for (int c = 0; c < configs.size(); c++) {
                String ratio = c < 2 && configs.get(c).physicsHz() == 50 ? String.format(Locale.ROOT, "%.1f×", results[c] / naiveSameRates) : "";
                System.out.printf(Locale.ROOT, "| %d | %s | %.2f× | %s |%n", n, configs.get(c).label(), results[c], ratio);
            }
        }
    }

    /** @return the real-time factor of one run */
    static double run(int n, Config config, double simSeconds) throws IOException {
        Path dir = Files.createTempDirectory("robomw-swarm");
        Path robot = dir.resolve("swarm-bot.yaml");
        StringBuilder sensors = new StringBuilder();
        for (int i = 0; i < 8; i++) {
            sensors.append(String.format(Locale.ROOT,
                    "  - { name: ir%d, type: infrared, position: center, port: S%d, options: { angle: %.6f, x: %.4f, y: %.4f, max_range: 0.5, rate_hz: %s } }%n",
                    i, i, i * Math.PI / 4, 0.06 * Math.cos(i * Math.PI / 4), 0.06 * Math.sin(i * Math.PI / 4), config.sensorHz()));
        }
        Files.writeString(robot, """
                name: swarm-bot
                platform: sim
                cycle_hz: 10
                drive: { wheel_diameter: 0.056, track_width: 0.112, max_speed: 0.3, left: { port: B }, right: { port: C } }
                body: { length: 0.12, width: 0.12, mass: 0.3 }
                sensors:
                """ + sensors);
        int cols = (int) Math.ceil(Math.sqrt(n));
        double side = cols * 1.0;
        List<WorldDescription.RobotPlacement> placements = new ArrayList<>();
        for (int i = 0; i < n; i++) {
            placements.add(new WorldDescription.RobotPlacement(robot, "r" + i,
                    new Pose(0.5 + (i % cols), 0.5 + (double) (i / cols), (i * 2.399963) % (2 * Math.PI))));
        }
        WorldDescription world = new WorldDescription("swarm-" + n, side, side, true, 0.1, 0.8, List.of(), List.of(), placements, 1,
                config.physicsHz(), "benchmark");
        try (Simulation sim = Simulation.create(world, Runtime.getRuntime().availableProcessors(), config.method())) {
            WanderController.install(sim, 10, 1);
            sim.runFor(Duration.ofSeconds(2));
            long start = System.nanoTime();
            sim.runFor(Duration.ofMillis(Math.round(simSeconds * 1000)));
            return simSeconds / ((System.nanoTime() - start) / 1e9);
        } finally {
            Files.deleteIfExists(robot);
            Files.deleteIfExists(dir);
        }
    }
}
