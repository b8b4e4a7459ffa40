package io.robomw.bench.jade;

import org.junit.jupiter.api.Test;

import java.nio.file.Files;
import java.nio.file.Path;
import java.util.Locale;

import static org.junit.jupiter.api.Assertions.assertEquals;

/**
 * Runs {@link JadeMoveBaseline} for 0 B, 10 KB and 1 MB payloads (200 warm-up and 1000 measured
 * round trips each) and writes {@code target/benchmarks/jade-move.md}. Not part of the normal
 * test run (the name does not end in IT); run it with
 * {@code mvn -B -Pbench verify -pl src-it -am -Dtest=none -Dsurefire.failIfNoSpecifiedTests=false -Dit.test=JadeMoveBaselineRun}.
 */
class JadeMoveBaselineRun {

    static final int WARMUP = 200;
    static final int ITERATIONS = 1000;
    static final int[] PAYLOADS = {0, 10 * 1024, 1024 * 1024};

    @Test
    void run() throws Exception {
        StringBuilder md = new StringBuilder("| JADE 4.3 doMove A→B→A, 2 JVMs on loopback, warm agent | p50 µs | p99 µs | round trips |\n|---|---:|---:|---:|\n");
        try (JadeMoveBaseline jade = JadeMoveBaseline.start()) {
            // The first measurement in fresh container JVMs runs mostly interpreted and would be about
            // twice as slow as the next ones: one discarded pass warms the JVMs (JIT) first.
            JadeMoveBaseline.RoundTrips jvmWarmup = jade.measure(0, 0, 2 * ITERATIONS);
            System.out.printf(Locale.ROOT, "JADE doMove A->B->A %8d B  p50 %8.1f µs  p99 %8.1f µs  (JVM warm-up pass, discarded)%n",
                    jvmWarmup.payloadBytes(), jvmWarmup.p50Micros(), jvmWarmup.p99Micros());
            for (int payload : PAYLOADS) {
                JadeMoveBaseline.RoundTrips r = jade.measure(payload, WARMUP, ITERATIONS);
                assertEquals(ITERATIONS, r.nanos().length);
                System.out.printf(Locale.ROOT, "JADE doMove A->B->A %8d B  p50 %8.1f µs  p99 %8.1f µs  (%d round trips after %d warm-up)%n",
                        payload, r.p50Micros(), r.p99Micros(), ITERATIONS, WARMUP);
                md.append(String.format(Locale.ROOT, "| %s | %.1f | %.1f | %d |%n", label(payload), r.p50Micros(), r.p99Micros(), ITERATIONS));
            }
        }
        Path out = Path.of("target", "benchmarks", "jade-move.md");
        Files.createDirectories(out.getParent());
        Files.writeString(out, md.toString());
        System.out.println();
        System.out.println(md);
        System.out.println("written to " + out.toAbsolutePath());
    }

    private static String label(int bytes) {
        if (bytes >= 1024 * 1024) {
            return bytes / (1024 * 1024) + " MB payload";
        }
        return bytes >= 1024 ? bytes / 1024 + " KB payload" : bytes + " B payload";
    }
}
