package io.robomw.sim.bench;

import java.io.IOException;
import java.nio.file.DirectoryStream;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.HashMap;
import java.util.LinkedHashMap;
import java.util.Locale;
import java.util.Map;
import java.util.concurrent.atomic.AtomicBoolean;
import java.util.stream.Collectors;

/**
 * Where this JVM's threads ran during a window (Linux): a sampling thread reads
 * {@code /proc/self/task/TID/stat} every 5 ms and, per thread, counts the samples it was running
 * and on which processor, and how often its processor changed between two samples (migrations);
 * at the end it adds each thread's CPU time ({@code utime + stime}) and its voluntary and
 * involuntary context switches ({@code /proc/self/task/TID/status}) over the window. For telling
 * whether two busy threads shared one processor while the other idled, and whether a thread was
 * pre-empted. A diagnostic of the swarm benchmark, not a test.
 */
final class ThreadPlacement {

    private static final Path TASKS = Path.of("/proc/self/task");
    private static final long TICK_NANOS = 1_000_000_000L / 100; // USER_HZ

    /** What is known of one thread. */
    private static final class Seen {
        String name;
        long cpuTicks0 = -1;
        long cpuTicks;
        long voluntary0 = -1;
        long involuntary0 = -1;
        long voluntary;
        long involuntary;
        int running;
        int lastCpu = -1;
        int migrations;
        final Map<Integer, Integer> onCpu = new HashMap<>();
    }

    private final Map<String, Seen> threads = new LinkedHashMap<>();
    private final AtomicBoolean stop = new AtomicBoolean();
    private final Thread sampler;
    private final long start = System.nanoTime();
    private int samples;
    private int workersTogether;
    private int workersApart;

    private ThreadPlacement() {
        snapshot(true);
        sampler = new Thread(this::loop, "placement-sampler");
        sampler.setDaemon(true);
        sampler.start();
    }

    /** @return a sampler running from now */
    static ThreadPlacement start() {
        return new ThreadPlacement();
    }

    private void loop() {
        while (!stop.get()) {
            sample();
            java.util.concurrent.locks.LockSupport.parkNanos(5_000_000);
        }
    }

    private synchronized void sample() {
        samples++;
        java.util.List<Integer> stepCpus = new java.util.ArrayList<>();
        try (DirectoryStream<Path> tasks = Files.newDirectoryStream(TASKS)) {
            for (Path t : tasks) {
                String[] stat = stat(t);
                if (stat == null) {
                    continue;
                }
                Seen s = threads.computeIfAbsent(t.getFileName().toString(), k -> new Seen());
                s.name = stat[0];
                if (!stat[1].equals("R")) {
                    continue;
                }
                int cpu = Integer.parseInt(stat[37]);
                s.running++;
                s.onCpu.merge(cpu, 1, Integer::sum);
                if (s.lastCpu >= 0 && s.lastCpu != cpu) {
                    s.migrations++;
                }
                s.lastCpu = cpu;
                if (s.name.startsWith("sim-worker-") || s.name.equals("main") || s.name.equals("java")) {
                    stepCpus.add(cpu);
                }
            }
        } catch (IOException e) {
            // a thread ended while being read; skip this sample
        }
        if (stepCpus.size() >= 2) {
            if (new java.util.HashSet<>(stepCpus).size() < stepCpus.size()) {
                workersTogether++;
            } else {
                workersApart++;
            }
        }
    }

    /** @return [name, state, fields after the state...] with the name's parentheses removed, or null */
    private static String[] stat(Path task) {
        try {
            String line = Files.readString(task.resolve("stat"));
            int open = line.indexOf('(');
            int close = line.lastIndexOf(')');
            String name = line.substring(open + 1, close);
            String[] rest = line.substring(close + 2).split(" ");
            // rest[0] is the state (field 3); field n is rest[n - 3]; the processor is field 39
            String[] out = new String[rest.length + 1];
            out[0] = name;
            System.arraycopy(rest, 0, out, 1, rest.length);
            // out[1] state; utime field 14 = out[12], stime field 15 = out[13], processor field 39 = out[37]
            return out;
        } catch (IOException | RuntimeException e) {
            return null;
        }
    }

    private synchronized void snapshot(boolean first) {
        try (DirectoryStream<Path> tasks = Files.newDirectoryStream(TASKS)) {
            for (Path t : tasks) {
                String[] stat = stat(t);
                if (stat == null) {
                    continue;
                }
                Seen s = threads.computeIfAbsent(t.getFileName().toString(), k -> new Seen());
                s.name = stat[0];
                long cpu = Long.parseLong(stat[12]) + Long.parseLong(stat[13]);
                long[] cs = switches(t);
                if (first || s.cpuTicks0 < 0) {
                    s.cpuTicks0 = first ? cpu : 0;
                    s.voluntary0 = first ? cs[0] : 0;
                    s.involuntary0 = first ? cs[1] : 0;
                }
                s.cpuTicks = cpu;
                s.voluntary = cs[0];
                s.involuntary = cs[1];
            }
        } catch (IOException e) {
            // leave what was read
        }
    }

    private static long[] switches(Path task) {
        long[] out = new long[2];
        try {
            for (String l : Files.readAllLines(task.resolve("status"))) {
                if (l.startsWith("voluntary_ctxt_switches:")) {
                    out[0] = Long.parseLong(l.substring(l.indexOf(':') + 1).trim());
                } else if (l.startsWith("nonvoluntary_ctxt_switches:")) {
                    out[1] = Long.parseLong(l.substring(l.indexOf(':') + 1).trim());
                }
            }
        } catch (IOException | RuntimeException e) {
            // the thread ended
        }
        return out;
    }

    /** @return the busy threads of the window (over 2 % CPU), busiest first: CPU %, processors, migrations, switches */
    String stop() {
        stop.set(true);
        try {
            sampler.join(1000);
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
        }
        snapshot(false);
        double wallTicks = (System.nanoTime() - start) / (double) TICK_NANOS;
        String busy;
        synchronized (this) {
            busy = threads.values().stream()
                    .filter(s -> s.cpuTicks - s.cpuTicks0 > wallTicks * 0.02 && s.cpuTicks0 >= 0)
                    .sorted((a, b) -> Long.compare(b.cpuTicks - b.cpuTicks0, a.cpuTicks - a.cpuTicks0))
                    .map(s -> String.format(Locale.ROOT, "%s %.0f%% cpu (running in %d%% of samples, on %s; %d migrations; %d voluntary, %d involuntary switches)",
                            s.name, 100 * (s.cpuTicks - s.cpuTicks0) / wallTicks, samples == 0 ? 0 : 100 * s.running / samples,
                            s.onCpu.entrySet().stream().sorted(Map.Entry.comparingByKey())
                                    .map(e -> "cpu" + e.getKey() + " " + e.getValue()).collect(Collectors.joining("/")),
                            s.migrations, s.voluntary - s.voluntary0, s.involuntary - s.involuntary0))
                    .collect(Collectors.joining("; "));
            busy += String.format(Locale.ROOT, "; samples with two or more of the stepping thread and the sim workers running: sharing a processor %d, each on its own %d (of %d)",
                    workersTogether, workersApart, samples);
        }
        return busy;
    }
}
