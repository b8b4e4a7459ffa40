package io.robomw.sim.bench;

import io.robomw.sim.Parallel;
import io.robomw.sim.physics.Dyn4jPhysics;
import io.robomw.sim.physics.Physics;
import io.robomw.sim.physics.SwarmPhysics;

import java.lang.management.ManagementFactory;
import java.util.Locale;
import java.util.SplittableRandom;

/**
 * The physics step alone, both engines interleaved in one JVM: N robots (0.12 m boxes, one per
 * square metre, as in {@link SwarmBenchmark}) in a walled arena, each driving at 0.2 m/s and turning
 * at a speed drawn anew every second from a seeded stream (no sensing, no controller: they do bump
 * into each other and the walls, more often than wandering robots that see each other). Prints per
 * engine and round the wall time and the process's CPU time per step, the contacts per step (swarm
 * engine), and the real-time factor of the step alone; then the medians.
 *
 * <p>Run on demand ({@code docs/benchmarks.md}): {@code java -cp ... io.robomw.sim.bench.PhysicsStepBenchmark
 * N [rounds] [seconds per round] [threads]}. Not a test.
 */
public final class PhysicsStepBenchmark {

    private static final double DT = 1.0 / 50;

    private PhysicsStepBenchmark() {
    }

    /**
     * @param args N, rounds (default 5), wall seconds per measured window (default 5), worker threads (default the processors)
     */
    public static void main(String[] args) {
        int n = Integer.parseInt(args[0]);
        int rounds = args.length > 1 ? Integer.parseInt(args[1]) : 5;
        double seconds = args.length > 2 ? Double.parseDouble(args[2]) : 5;
        int threads = args.length > 3 ? Integer.parseInt(args[3]) : Runtime.getRuntime().availableProcessors();
        System.out.printf(Locale.ROOT, "physics step alone: N = %d, %d rounds of %.1f s each engine, %d threads, %s %s%n", n, rounds, seconds,
                threads, System.getProperty("java.vm.name"), System.getProperty("java.version"));
        double[][] cpu = new double[2][rounds];
        double[][] wall = new double[2][rounds];
        try (Parallel parallel = new Parallel(threads)) {
            for (int r = 0; r < rounds; r++) {
                for (int e = 0; e < 2; e++) {
                    int engine = (r % 2 == 0) ? e : 1 - e;
                    double[] m = measure(n, engine == 1, parallel, seconds);
                    wall[engine][r] = m[0];
                    cpu[engine][r] = m[1];
                    System.out.printf(Locale.ROOT, "round %d %-6s: %.1f µs wall, %.1f µs CPU per step (%.2f processors), %.1f contacts per step, %.1f× real time%n",
                            r + 1, engine == 1 ? "swarm" : "dyn4j", m[0], m[1], m[1] / m[0], m[2], DT * 1e6 / m[0]);
                }
            }
        }
        for (int e = 0; e < 2; e++) {
            java.util.Arrays.sort(wall[e]);
            java.util.Arrays.sort(cpu[e]);
            System.out.printf(Locale.ROOT, "%s: median %.1f µs wall (%.1f-%.1f), %.1f µs CPU (%.1f-%.1f) per step; %.1f× real time%n",
                    e == 1 ? "swarm" : "dyn4j", wall[e][rounds / 2], wall[e][0], wall[e][rounds - 1], cpu[e][rounds / 2], cpu[e][0],
                    cpu[e][rounds - 1], DT * 1e6 / wall[e][rounds / 2]);
        }
    }

    /** @return {wall µs per step, process CPU µs per step, contacts per step} after a warm-up of as long as the window */
    private static double[] measure(int n, boolean swarm, Parallel parallel, double seconds) {
        int cols = (int) Math.ceil(Math.sqrt(n));
        double side = cols;
        Physics p = swarm ? new SwarmPhysics(parallel, -1.1, -1.1, side + 1.1, side + 1.1) : new Dyn4jPhysics(DT);
        p.addStaticBox(side / 2, -0.05, side + 0.2, 0.1, 0);
        p.addStaticBox(side / 2, side + 0.05, side + 0.2, 0.1, 0);
        p.addStaticBox(-0.05, side / 2, 0.1, side, 0);
        p.addStaticBox(side + 0.05, side / 2, 0.1, side, 0);
        for (int i = 0; i < n; i++) {
            p.addBody(0.12, 0.12, 0.3, 0.5, 0.5 + (i % cols), 0.5 + (double) (i / cols), (i * 2.399963) % (2 * Math.PI));
        }
        SplittableRandom random = new SplittableRandom(42);
        double[] turn = new double[n];
        long[] steps = {0};
        long contacts = 0;
        Runnable step = () -> {
            if (steps[0] % 50 == 0) {
                for (int i = 0; i < n; i++) {
                    turn[i] = random.nextDouble(-2, 2);
                }
            }
            for (int i = 0; i < n; i++) {
                p.drive(i, 0.2, turn[i]);
            }
            p.step(DT);
            steps[0]++;
        };
        long end = System.nanoTime() + Math.round(seconds * 1e9);
        while (System.nanoTime() < end) {
            step.run();
        }
        long s0 = steps[0];
        long cpu0 = processCpuNanos();
        long t0 = System.nanoTime();
        end = t0 + Math.round(seconds * 1e9);
        long now;
        do {
            step.run();
            if (p instanceof SwarmPhysics sp) {
                contacts += sp.contactCount();
            }
            now = System.nanoTime();
        } while (now < end);
        long taken = steps[0] - s0;
        return new double[] {(now - t0) / 1e3 / taken, (processCpuNanos() - cpu0) / 1e3 / taken, (double) contacts / taken};
    }

    private static long processCpuNanos() {
        return ManagementFactory.getOperatingSystemMXBean() instanceof com.sun.management.OperatingSystemMXBean os ? os.getProcessCpuTime() : -1;
    }
}
