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
    record Config(String label, double physicsHz, double sensorHz, SimWorld.RangeMethod method, WorldDescription.PhysicsEngine engine) {
        Config(String label, double physicsHz, double sensorHz, SimWorld.RangeMethod method) {
            this(label, physicsHz, sensorHz, method, WorldDescription.PhysicsEngine.DYN4J);
        }
    }

    /**
     * The most points a robot's trajectory keeps in the benchmark's world: 128 (1 KiB a robot, the whole path ever
     * coarser), the window a swarm's world file sets; the default (1000 points, 8 KB a robot) alone would exceed the
     * 6 KiB a robot of issue 36's target at N = 100,000.
     */
    static final int TRAJECTORY_POINTS = 128;
    private static final WorldDescription.TrajectorySettings TRAJECTORY =
            new WorldDescription.TrajectorySettings(0.1, TRAJECTORY_POINTS, WorldDescription.Keep.WHOLE);

    private SwarmBenchmark() {
    }

    /**
     * @param args robot counts (default 100 1000 10000); {@code --quick} measures shorter
     * @throws IOException if the temporary robot file cannot be written
     */
    public static void main(String[] args) throws IOException {
        if (args.length > 0 && args[0].equals("--sample")) {
            sample(args);
            return;
        }
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

    /** The configurations by the key a sample names. */
    private static final java.util.Map<String, Config> BY_KEY = java.util.Map.of(
            "grid50", new Config("grid, physics 50 Hz, sensors 10 Hz", 50, 10, SimWorld.RangeMethod.GRID),
            "grid20", new Config("grid, physics 20 Hz, sensors 10 Hz", 20, 10, SimWorld.RangeMethod.GRID),
            "naive50", new Config("naive dyn4j ray casts, physics 50 Hz, sensors 10 Hz", 50, 10, SimWorld.RangeMethod.DYN4J_RAYCAST),
            "naive50s50", new Config("naive dyn4j ray casts, physics 50 Hz, sensors 50 Hz", 50, 50, SimWorld.RangeMethod.DYN4J_RAYCAST),
            "naive10", new Config("naive dyn4j ray casts, everything at 10 Hz", 10, 10, SimWorld.RangeMethod.DYN4J_RAYCAST),
            "swarm50", new Config("grid, swarm physics engine, physics 50 Hz, sensors 10 Hz", 50, 10, SimWorld.RangeMethod.GRID,
                    WorldDescription.PhysicsEngine.SWARM));

    /**
     * One sample for {@code bench/all}, in a JVM of its own: {@code --sample N CONFIG [--warmup S]
     * [--measure S] [--placement] [--threads T]} (CONFIG: grid50, grid20, naive50, naive50s50, naive10, swarm50 (grid50 on the
     * swarm physics engine); S: wall-clock seconds,
     * default 4 and 8; T: threads stepping the world, default the processors). The world runs for the warm-up (JIT, heap sizing; longer while the JIT
     * still compiles more than 50 ms a second, up to twice plus 10 s), then for the measured
     * window in whole steps; prints the real-time factor of the window and of each of its seconds,
     * where the step's time went (phases, on the world's profile clock), the CPU time a step took
     * (the process's, which does not count time the threads waited for a processor, and the
     * stepping thread's), GC and JIT time in the
     * window, with {@code --placement} each thread's CPU, processor and migrations
     * ({@link ThreadPlacement}, which costs some CPU itself), then
     * {@code BENCH} lines: the real-time factor; for grid50 and swarm50 also the physics step
     * alone as a ceiling (simulated seconds per wall second spent in it), its cost per robot, and
     * the live heap per robot (live heap after a full GC, less the heap before the world was made,
     * over N): at load ({@code heap-per-robot}) and after the window with what the trajectories
     * still have room to grow added ({@code heap-per-robot-full}: issue 36's figure); every sample
     * prints the load average before and after its window.
     */
    static void sample(String[] args) throws IOException {
        int n = Integer.parseInt(args[1]);
        String key = args[2];
        Config config = BY_KEY.get(key);
        if (config == null) {
            throw new IllegalArgumentException("unknown configuration " + key + "; known: " + BY_KEY.keySet());
        }
        double warmup = 4;
        double measure = 8;
        boolean watchThreads = false;
        int threads = Runtime.getRuntime().availableProcessors();
        for (int i = 3; i < args.length; i++) {
            switch (args[i]) {
                case "--threads" -> threads = Integer.parseInt(args[++i]);
                case "--warmup" -> warmup = Double.parseDouble(args[++i]);
                case "--measure" -> measure = Double.parseDouble(args[++i]);
                case "--placement" -> watchThreads = true;
                default -> throw new IllegalArgumentException("unknown option " + args[i]);
            }
        }
        long heapBefore = liveHeap();
        Path dir = Files.createTempDirectory("robomw-swarm");
        long building = System.nanoTime();
        try (Simulation sim = Simulation.create(world(n, config, dir), threads, config.method())) {
            WanderController.install(sim, 10, 1);
            double builtIn = (System.nanoTime() - building) / 1e9;
            long heapPerRobot = (liveHeap() - heapBefore) / n;
            SimWorld w = sim.world();
            Duration second = Duration.ofSeconds(1);
            // Warm up for the given wall time, and on while the JIT still compiled more than 50 ms in the last
            // second of it (a loaded machine starves the compiler threads), at most twice as long plus 10 s.
            long warmStart = System.nanoTime();
            long end = warmStart + Math.round(warmup * 1e9);
            long limit = warmStart + Math.round((2 * warmup + 10) * 1e9);
            long jitSlice = jitMillis();
            long slice = System.nanoTime();
            long jitLast = Long.MAX_VALUE;
            while (System.nanoTime() < limit && (System.nanoTime() < end || jitLast > 50)) {
                sim.runFor(second);
                if (System.nanoTime() - slice >= 1_000_000_000L) {
                    long j = jitMillis();
                    jitLast = j - jitSlice;
                    jitSlice = j;
                    slice = System.nanoTime();
                }
            }
            double warmedFor = (System.nanoTime() - warmStart) / 1e9;
            long gcCount0 = gcCount();
            long gcMillis0 = gcMillis();
            long jit0 = jitMillis();
            ThreadPlacement placement = watchThreads ? ThreadPlacement.start() : null;
            long cpu0 = processCpuNanos();
            long steppingCpu0 = threadCpuNanos();
            long simThreadsCpu0 = simThreadsCpuNanos();
            long[] machine0 = machineTicks();
            String loadBefore = loadAverage();
            w.profile(io.robomw.api.Clock.system(), true);
            double sim0 = w.time();
            long t0 = System.nanoTime();
            end = t0 + Math.round(measure * 1e9);
            List<String> perSecond = new ArrayList<>();
            long mark = t0;
            double simMark = sim0;
            long now;
            do {
                sim.runFor(Duration.ofMillis(Math.round(w.stepSeconds() * 1000)));
                now = System.nanoTime();
                if (now - mark >= 1_000_000_000L) {
                    perSecond.add(String.format(Locale.ROOT, "%.1f", (w.time() - simMark) / ((now - mark) / 1e9)));
                    mark = now;
                    simMark = w.time();
                }
            } while (now < end);
            double simSeconds = w.time() - sim0;
            double wall = (now - t0) / 1e9;
            long cpu = processCpuNanos() - cpu0;
            long steppingCpu = threadCpuNanos() - steppingCpu0;
            long simThreadsCpu = simThreadsCpuNanos() - simThreadsCpu0;
            long[] machine1 = machineTicks();
            long[] phases = w.phaseNanos();
            long[] parts = w.robotPartNanos();
            w.profile(null);
            String loadAfter = loadAverage();
            // Live heap after the run: the trajectories have grown with it; what they would add once full is counted from
            // their room now (each grows by doubling up to the world's max_points, 8 bytes a point).
            long heapAfterRun = (liveHeap() - heapBefore) / n;
            long toFull = 0;
            for (io.robomw.sim.SimRobot r : w.robots()) {
                toFull += 8L * (TRAJECTORY_POINTS - r.trajectory().capacity());
            }
            long heapFull = heapAfterRun + toFull / n;
            String placed = placement == null ? "(not watched; --placement)" : placement.stop();
            double rtf = simSeconds / wall;
            long stepsTaken = Math.round(simSeconds / w.stepSeconds());
            StringBuilder p = new StringBuilder();
            long inWorld = 0;
            for (SimWorld.Phase phase : SimWorld.Phase.values()) {
                long ns = phases[phase.ordinal()];
                inWorld += ns;
                p.append(String.format(Locale.ROOT, "%s %.1f µs, ", phase.name().toLowerCase(Locale.ROOT), ns / 1e3 / stepsTaken));
            }
            p.append(String.format(Locale.ROOT, "step listeners and rest %.1f µs", ((now - t0) - inWorld) / 1e3 / stepsTaken));
            StringBuilder q = new StringBuilder();
            long partsTotal = 0;
            for (SimWorld.RobotPart part : SimWorld.RobotPart.values()) {
                long ns = parts[part.ordinal()];
                partsTotal += ns;
                q.append(String.format(Locale.ROOT, "%s %.1f µs (%.0f ns a robot), ", part.name().toLowerCase(Locale.ROOT), ns / 1e3 / stepsTaken,
                        ns / (double) stepsTaken / n));
            }
            q.append(String.format(Locale.ROOT, "in all %.1f µs", partsTotal / 1e3 / stepsTaken));
            System.out.printf(Locale.ROOT, "SAMPLE N=%d %s: %.2f× real time over %.1f s wall (%d steps); per second: %s%n", n, key, rtf, wall, stepsTaken, perSecond);
            System.out.println("  per step (wall): " + p);
            System.out.println("  per step, the robots' parts (processor time, every thread; timed on every " + 8 + "th robot): " + q);
            System.out.printf(Locale.ROOT, "  CPU per step: %.1f µs for the process (%.2f processors busy on average), %.1f µs on the stepping thread; %d threads%n",
                    cpu / 1e3 / stepsTaken, cpu / 1e9 / wall, steppingCpu / 1e3 / stepsTaken, threads);
            System.out.printf(Locale.ROOT, "  CPU per step of the simulation's own threads (the stepping thread and the sim-worker threads; no JIT, no GC): %.1f µs, "
                    + "%.3f µs a robot%n", simThreadsCpu / 1e3 / stepsTaken, simThreadsCpu / 1e3 / stepsTaken / n);
            if (machine0 != null && machine1 != null) {
                double busy = (machine1[0] - machine0[0]) / 100.0 / wall;
                double others = Math.max(0, busy - cpu / 1e9 / wall);
                double steal = (machine1[1] - machine0[1]) / 100.0 / wall;
                System.out.printf(Locale.ROOT, "  the machine in the window: %.2f of %d processors busy, %.2f of them with other processes%s; steal %.2f%n",
                        busy, Runtime.getRuntime().availableProcessors(), others,
                        others > 0.1 ? " (NOT QUIET: this sample shared the processors)" : "", steal);
            }
            long jitInWindow = jitMillis() - jit0;
            System.out.printf(Locale.ROOT, "  warm-up %.1f s; GC in the window: %d collections, %d ms; JIT compilation in the window: %d ms%s; live heap per robot at load %d bytes%n",
                    warmedFor, gcCount() - gcCount0, gcMillis() - gcMillis0, jitInWindow,
                    jitInWindow > wall * 100 ? " (UNSTEADY: the JIT compiled for more than a tenth of the window)" : "", heapPerRobot);
            System.out.printf(Locale.ROOT, "  live heap per robot after the run %d bytes, with every trajectory full (%d points) %d bytes (%.2f KiB)%n",
                    heapAfterRun, TRAJECTORY_POINTS, heapFull, heapFull / 1024.0);
            System.out.printf(Locale.ROOT, "  world of %d robots built and its controller installed in %.1f s (not measured)%n", n, builtIn);
            System.out.println("  load average (1, 5, 15 min) before the window: " + loadBefore + "; after: " + loadAfter);
            System.out.println("  threads: " + placed);
            String id = "sim.n" + n + "." + key;
            System.out.println(io.robomw.sim.bench.SwarmBenchmark.line(id, rtf, "×"));
            if (key.equals("grid50") || key.equals("swarm50")) {
                // grid50 (dyn4j) keeps its historical ids; swarm50's carry the engine's name
                String prefix = "sim.n" + n + (key.equals("swarm50") ? ".swarm-" : ".");
                double physicsSeconds = phases[SimWorld.Phase.PHYSICS.ordinal()] / 1e9;
                System.out.println(line(prefix + "physics", simSeconds / physicsSeconds, "×"));
                System.out.println(line(prefix + "step-per-robot", physicsSeconds * 1e6 / stepsTaken / n, "µs"));
                System.out.println(line(prefix + "heap-per-robot", heapPerRobot / 1024.0, "KiB"));
                System.out.println(line(prefix + "heap-per-robot-full", heapFull / 1024.0, "KiB"));
            }
            // where a step's time goes: the physics (wall time of the stepping thread and its workers) and the
            // robots' parts (processor time summed over the threads), milliseconds per step
            System.out.println(line(id + ".ms.physics", phases[SimWorld.Phase.PHYSICS.ordinal()] / 1e6 / stepsTaken, "ms"));
            for (SimWorld.RobotPart part : SimWorld.RobotPart.values()) {
                System.out.println(line(id + ".ms." + part.name().toLowerCase(Locale.ROOT), parts[part.ordinal()] / 1e6 / stepsTaken, "ms"));
            }
            System.out.println(line(id + ".ms.cpu", cpu / 1e6 / stepsTaken, "ms"));
            System.out.println(line(id + ".ms.cpu-sim-threads", simThreadsCpu / 1e6 / stepsTaken, "ms"));
        } finally {
            deleteTree(dir);
        }
    }

    /** A {@code BENCH} line as {@code bench/all} collects them (the same as src-it's BenchReport.line). */
    static String line(String id, double value, String unit) {
        return String.format(Locale.ROOT, "BENCH %s %.6g %s", id, value, unit);
    }

    /** @return the machine's load average over 1, 5 and 15 minutes ({@code /proc/loadavg}), or "unknown" */
    private static String loadAverage() {
        try {
            String[] f = Files.readString(Path.of("/proc/loadavg")).trim().split("\\s+");
            return f[0] + " " + f[1] + " " + f[2];
        } catch (IOException | RuntimeException e) {
            return "unknown";
        }
    }

    private static long liveHeap() {
        java.lang.management.MemoryMXBean m = java.lang.management.ManagementFactory.getMemoryMXBean();
        for (int i = 0; i < 2; i++) {
            System.gc();
        }
        return m.getHeapMemoryUsage().getUsed();
    }

    /** @return CPU time of this process (every thread, the JIT and GC included), nanoseconds; -1 if unknown */
    private static long processCpuNanos() {
        return java.lang.management.ManagementFactory.getOperatingSystemMXBean() instanceof com.sun.management.OperatingSystemMXBean os
                ? os.getProcessCpuTime() : -1;
    }

    /**
     * The machine's busy time from {@code /proc/stat} (Linux): every processor's user, nice,
     * system, irq and softirq ticks (1/100 s), and the ticks the hypervisor stole. Other processes
     * compete with a sample at equal weight whatever their nice value when they run in another
     * session (the kernel's autogroups: a campaign started at nice 10 from its own shell is not
     * "in the background"), so a sample says how much of the machine they took.
     *
     * @return {busy, steal} ticks, or {@code null} where there is no {@code /proc/stat}
     */
    private static long[] machineTicks() {
        try {
            String[] f = Files.readAllLines(Path.of("/proc/stat")).get(0).trim().split("\\s+");
            long busy = 0;
            for (int i : new int[] {1, 2, 3, 6, 7}) {
                busy += Long.parseLong(f[i]);
            }
            return new long[] {busy, f.length > 8 ? Long.parseLong(f[8]) : 0};
        } catch (IOException | RuntimeException e) {
            return null;
        }
    }

    /**
     * @return CPU time of the simulation's own threads: the calling (stepping) thread and every live thread named
     *         {@code sim-worker-*}, nanoseconds; the JIT's and the collector's threads are not counted, so a loaded
     *         machine's longer compilation and collection do not count against the step
     */
    private static long simThreadsCpuNanos() {
        java.lang.management.ThreadMXBean t = java.lang.management.ManagementFactory.getThreadMXBean();
        long sum = t.getCurrentThreadCpuTime();
        for (java.lang.management.ThreadInfo info : t.getThreadInfo(t.getAllThreadIds())) {
            if (info != null && info.getThreadName().startsWith("sim-worker-")) {
                sum += Math.max(0, t.getThreadCpuTime(info.getThreadId()));
            }
        }
        return sum;
    }

    /** @return CPU time of the calling thread, nanoseconds */
    private static long threadCpuNanos() {
        return java.lang.management.ManagementFactory.getThreadMXBean().getCurrentThreadCpuTime();
    }

    private static long gcCount() {
        return java.lang.management.ManagementFactory.getGarbageCollectorMXBeans().stream().mapToLong(b -> Math.max(0, b.getCollectionCount())).sum();
    }

    private static long gcMillis() {
        return java.lang.management.ManagementFactory.getGarbageCollectorMXBeans().stream().mapToLong(b -> Math.max(0, b.getCollectionTime())).sum();
    }

    private static long jitMillis() {
        java.lang.management.CompilationMXBean c = java.lang.management.ManagementFactory.getCompilationMXBean();
        return c != null && c.isCompilationTimeMonitoringSupported() ? c.getTotalCompilationTime() : -1;
    }

    private static void deleteTree(Path dir) throws IOException {
        try (var walk = Files.walk(dir)) {
            for (Path p : walk.sorted(java.util.Comparator.reverseOrder()).toList()) {
                Files.deleteIfExists(p);
            }
        }
    }

    /** @return the real-time factor of one run */
    static double run(int n, Config config, double simSeconds) throws IOException {
        Path dir = Files.createTempDirectory("robomw-swarm");
        try (Simulation sim = Simulation.create(world(n, config, dir), Runtime.getRuntime().availableProcessors(), config.method())) {
            WanderController.install(sim, 10, 1);
            sim.runFor(Duration.ofSeconds(2));
            long start = System.nanoTime();
            sim.runFor(Duration.ofMillis(Math.round(simSeconds * 1000)));
            return simSeconds / ((System.nanoTime() - start) / 1e9);
        } finally {
            deleteTree(dir);
        }
    }

    /** The benchmark's world: N robots, one per square metre, their robot file written into {@code dir}. */
    static WorldDescription world(int n, Config config, Path dir) throws IOException {
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
        return new WorldDescription("swarm-" + n, side, side, true, 0.1, 0.8, List.of(), List.of(), placements, 1,
                config.physicsHz(), TRAJECTORY, config.engine(), "benchmark");
    }
}
