package io.robomw.it.soak;

import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

import java.io.IOException;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.time.Instant;
import java.util.ArrayList;
import java.util.List;

/**
 * The long soak and kill runs (docs/reliability.md), run on demand in the soak profile, not by
 * {@code mvn verify}:
 *
 * <pre>
 * mvn -B -Psoak verify -pl src-it -am -Dtest=none -Dsurefire.failIfNoSpecifiedTests=false
 * </pre>
 *
 * 1,000 agents going round 4 host JVMs for 60 s; then 100 agents in flight for 60 s while the
 * durable host is killed with -9 every 10 s and restarted. The same checks as {@link SoakIT},
 * and the figures are written into docs/reliability.md (between its soak markers).
 */
class SoakRun {

    private static final String BEGIN = "<!-- soak figures: written by SoakRun -->";
    private static final String END = "<!-- end of soak figures -->";

    @TempDir
    Path dir;

    @Test
    void longSoakAndKillRuns() throws Exception {
        List<Soak.Figures> runs = new ArrayList<>();
        String load = Files.readString(Path.of("/proc/loadavg")).strip();
        try (Soak soak = new Soak(new Soak.Plan("soak-hop", 4, 1_000, Duration.ofSeconds(60), 2, null, Duration.ofMinutes(5)), dir.resolve("hop"))) {
            Files.createDirectories(dir.resolve("hop"));
            soak.start();
            runs.add(soak.run());
        }
        try (Soak soak = new Soak(new Soak.Plan("soak-kill", 4, 100, Duration.ofSeconds(60), 30, Duration.ofSeconds(10), Duration.ofMinutes(5)),
                dir.resolve("kill"))) {
            Files.createDirectories(dir.resolve("kill"));
            soak.start();
            runs.add(soak.run());
        }
        String loadAfter = Files.readString(Path.of("/proc/loadavg")).strip();
        write(runs, load, loadAfter);
        for (Soak.Figures f : runs) {
            SoakChecks.check(f);
        }
    }

    private static void write(List<Soak.Figures> runs, String load, String loadAfter) throws IOException {
        StringBuilder b = new StringBuilder(BEGIN).append("\n\n");
        b.append("Run of ").append(Instant.now().toString(), 0, 19).append("Z on ").append(machine()).append("; load average (1, 5, 15 min) ")
                .append(load.split(" ")[0]).append(", ").append(load.split(" ")[1]).append(", ").append(load.split(" ")[2]).append(" before and ")
                .append(loadAfter.split(" ")[0]).append(", ").append(loadAfter.split(" ")[1]).append(", ").append(loadAfter.split(" ")[2])
                .append(" after.\n\n");
        b.append("| run | agents sent | home | lost | stops run | run twice | reports lost | reports duplicated | interrupted by a kill | kills | time |\n");
        b.append("|---|---|---|---|---|---|---|---|---|---|---|\n");
        for (Soak.Figures f : runs) {
            b.append(String.format("| %s | %d | %d | **%d** | %d | **%d** | **%d** | **%d** | %d | %d | %.0f s |%n", title(f), f.sent(), f.home(), f.lost(),
                    f.stopsRun(), f.stopsRunTwice(), f.reportsLost(), f.reportsDuplicate(), f.interrupted(), f.kills(), f.seconds()));
        }
        b.append("\nEach host JVM before the run (after a warm-up) and after it (once idle), heap of its live objects after a full GC; bounds: ")
                .append(Soak.THREAD_BOUND).append(" threads, ").append(Soak.FILE_BOUND).append(" files, ").append(Soak.HEAP_BOUND_KIB / 1024)
                .append(" MiB more after than before.\n\n");
        b.append("| run | host | threads before → after | files before → after | heap before → after (MiB) |\n|---|---|---|---|---|\n");
        for (Soak.Figures f : runs) {
            for (Soak.HostRow r : f.rows()) {
                b.append(String.format("| %s | %s%s | %d → %d | %d → %d | %.1f → %.1f |%n", f.plan().name(), r.host().substring(r.host().lastIndexOf('/') + 1),
                        r.restarts() > 0 ? " (killed and restarted " + r.restarts() + " times; after = its last start)" : "", r.before().threads(),
                        r.after().threads(), r.before().files(), r.after().files(), r.before().heapKiB() / 1024.0, r.after().heapKiB() / 1024.0));
            }
        }
        b.append("\nWhat holds the most heap in each host after the run (`jcmd PID GC.class_histogram`):\n\n");
        for (Soak.Figures f : runs) {
            for (Soak.HostRow r : f.rows()) {
                b.append("- ").append(f.plan().name()).append(" ").append(r.host().substring(r.host().lastIndexOf('/') + 1)).append(": ")
                        .append(r.after().topClasses()).append("\n");
            }
        }
        b.append("\n").append(END);
        Path doc = Path.of("..", "docs", "reliability.md");
        String text = Files.readString(doc, StandardCharsets.UTF_8);
        int from = text.indexOf(BEGIN);
        int to = text.indexOf(END);
        if (from < 0 || to < from) {
            throw new IOException(doc + " has no soak markers (" + BEGIN + " ... " + END + ")");
        }
        Files.writeString(doc, text.substring(0, from) + b + text.substring(to + END.length()), StandardCharsets.UTF_8);
        Files.writeString(Path.of("target", "soak-figures.md"), b, StandardCharsets.UTF_8);
    }

    private static String title(Soak.Figures f) {
        return f.plan().agents() + " agents, " + f.plan().hosts() + " host JVMs, " + f.plan().duration().toSeconds() + " s"
                + (f.plan().killEvery() == null ? "" : ", the durable host killed -9 every " + f.plan().killEvery().toSeconds() + " s");
    }

    private static String machine() throws IOException {
        String cpu = Files.readAllLines(Path.of("/proc/cpuinfo")).stream().filter(l -> l.startsWith("model name")).findFirst()
                .map(l -> l.substring(l.indexOf(':') + 1).strip()).orElse("?");
        return Runtime.getRuntime().availableProcessors() + " cores (" + cpu + "), " + System.getProperty("java.vm.name") + " "
                + System.getProperty("java.version");
    }
}
