package io.robomw.it.soak;

import java.io.IOException;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.List;
import java.util.concurrent.TimeUnit;
import java.util.regex.Matcher;
import java.util.regex.Pattern;
import java.util.stream.Stream;

/**
 * What one host JVM holds: its threads and open file descriptors (from /proc) and the heap its live
 * objects take after a full collection ({@code jcmd PID GC.class_histogram}, which collects first).
 *
 * @param threads  live threads
 * @param files    open file descriptors
 * @param heapKiB  heap the live objects take after a full GC, KiB
 * @param threadGroups the most numerous kinds of thread (names without their numbers), for when a bound is broken
 * @param topClasses   the classes holding the most heap after the full GC ({@code jcmd PID GC.class_histogram})
 */
public record HostFigures(int threads, int files, long heapKiB, String threadGroups, String topClasses) {


    /**
     * @param pid a JVM's process id
     * @return what it holds now
     * @throws IOException if /proc or jcmd cannot tell
     */
    static HostFigures of(long pid) throws IOException {
        Path proc = Path.of("/proc", Long.toString(pid));
        int threads = threadsOf(pid);
        int files = filesOf(pid);
        java.util.Map<String, Integer> groups = new java.util.TreeMap<>();
        Matcher name = Pattern.compile("(?m)^\"([^\"]*)\"").matcher(jcmd(pid, "Thread.print"));
        while (name.find()) {
            groups.merge(name.group(1).replaceAll("\\d+", "N"), 1, Integer::sum);
        }
        String top = groups.entrySet().stream().sorted(java.util.Map.Entry.<String, Integer>comparingByValue().reversed()).limit(6)
                .map(e -> e.getValue() + " " + e.getKey()).collect(java.util.stream.Collectors.joining(", "));
        // The class histogram runs a full collection first: its total is the heap the live objects hold.
        String histogram = jcmd(pid, "GC.class_histogram");
        long liveBytes = histogram.lines().map(String::trim).filter(l -> l.startsWith("Total")).map(l -> l.split("\\s+"))
                .mapToLong(f -> Long.parseLong(f[2])).findFirst().orElseThrow(() -> new IOException("jcmd " + pid + " GC.class_histogram has no total"));
        // Rows are "   1:   instances   bytes  class (module)"; jcmd's first line is "PID:".
        String classes = histogram.lines().map(l -> l.trim().split("\\s+")).filter(f -> f.length >= 4 && f[0].matches("\\d+:")).limit(6)
                .map(f -> f[3] + " " + Long.parseLong(f[2]) / 1024 + " KiB").collect(java.util.stream.Collectors.joining(", "));
        return new HostFigures(threads, files, liveBytes / 1024, top, classes);
    }

    /**
     * Writes a heap dump of a JVM's live objects ({@code jcmd PID GC.heap_dump}, which collects
     * first), for finding what holds what the figures show.
     *
     * @param pid  a JVM's process id
     * @param file where the dump goes (an .hprof file; it must not exist)
     * @throws IOException if jcmd cannot
     */
    static void heapDump(long pid, Path file) throws IOException {
        Files.createDirectories(file.toAbsolutePath().getParent());
        jcmd(pid, "GC.heap_dump " + file.toAbsolutePath());
    }

    /** @return a JVM's open file descriptors, from /proc */
    static int filesOf(long pid) throws IOException {
        try (Stream<Path> fds = Files.list(Path.of("/proc", Long.toString(pid), "fd"))) {
            return (int) fds.count();
        }
    }

    /** @return a JVM's live threads, from /proc */
    public static int threadsOf(long pid) throws IOException {
        for (String line : Files.readAllLines(Path.of("/proc", Long.toString(pid), "status"), StandardCharsets.UTF_8)) {
            if (line.startsWith("Threads:")) {
                return Integer.parseInt(line.substring("Threads:".length()).strip());
            }
        }
        throw new IOException("/proc/" + pid + "/status has no Threads line");
    }

    private static String jcmd(long pid, String command) throws IOException {
        Path jcmd = Path.of(System.getProperty("java.home"), "bin", "jcmd");
        List<String> argv = new java.util.ArrayList<>(List.of(jcmd.toString(), Long.toString(pid)));
        argv.addAll(List.of(command.split(" ")));
        Process p = new ProcessBuilder(argv).redirectErrorStream(true).start();
        try {
            String out = new String(p.getInputStream().readAllBytes(), StandardCharsets.UTF_8);
            if (!p.waitFor(60, TimeUnit.SECONDS) || p.exitValue() != 0) {
                throw new IOException("jcmd " + pid + " " + command + " failed: " + out);
            }
            return out;
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
            throw new IOException("interrupted", e);
        } finally {
            p.destroyForcibly();
        }
    }

    @Override
    public String toString() {
        return threads + " threads, " + files + " files, " + heapKiB / 1024 + " MiB heap";
    }

    /** @return the figures with the most numerous kinds of thread */
    String detailed() {
        return this + " (" + threadGroups + "; heap: " + topClasses + ")";
    }
}
