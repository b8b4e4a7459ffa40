package io.robomw.bench;

import java.lang.management.ManagementFactory;
import java.lang.management.ThreadInfo;
import java.lang.management.ThreadMXBean;
import java.util.HashMap;
import java.util.Locale;
import java.util.Map;
import java.util.stream.Collectors;

/**
 * The CPU time of this JVM's threads between two moments, for telling which side of a throughput
 * run was busy: {@code ThreadCpu before = ThreadCpu.now(); ...; before.since()}.
 *
 * @param nanosById CPU time per live thread id at the snapshot
 * @param wallNanos {@link System#nanoTime()} at the snapshot
 */
record ThreadCpu(Map<Long, Long> nanosById, long wallNanos) {

    /** @return the CPU time of every live thread now */
    static ThreadCpu now() {
        ThreadMXBean mx = ManagementFactory.getThreadMXBean();
        Map<Long, Long> m = new HashMap<>();
        for (long id : mx.getAllThreadIds()) {
            m.put(id, mx.getThreadCpuTime(id));
        }
        return new ThreadCpu(m, System.nanoTime());
    }

    /** @return the threads that used more than 1 % of the time since this snapshot, busiest first: "name 93%, ..." */
    String since() {
        ThreadMXBean mx = ManagementFactory.getThreadMXBean();
        long wall = System.nanoTime() - wallNanos;
        Map<String, Long> used = new HashMap<>();
        for (long id : mx.getAllThreadIds()) {
            long cpu = mx.getThreadCpuTime(id);
            ThreadInfo info = mx.getThreadInfo(id);
            if (cpu < 0 || info == null) {
                continue;
            }
            used.merge(info.getThreadName(), cpu - nanosById.getOrDefault(id, 0L), Long::sum);
        }
        return used.entrySet().stream()
                .filter(e -> e.getValue() * 100 > wall)
                .sorted(Map.Entry.<String, Long>comparingByValue().reversed())
                .map(e -> String.format(Locale.ROOT, "%s %.0f%%", e.getKey(), e.getValue() * 100.0 / wall))
                .collect(Collectors.joining(", ", String.format(Locale.ROOT, "over %.2f s: ", wall / 1e9), ""));
    }
}
