package io.robomw.it.net;

import java.io.IOException;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.nio.file.StandardOpenOption;
import java.time.Instant;
import java.time.temporal.ChronoUnit;

/**
 * The figures of the network scenarios, one line per scenario run, appended to
 * {@code target/network-figures.md} (docs/reliability.md quotes a run's lines, with its date and
 * the machine's load).
 */
final class NetFigures {

    private NetFigures() {
    }

    /**
     * @param scenario what ran
     * @param figures  what it measured, as text
     */
    static synchronized void record(String scenario, String figures) {
        try {
            String load = Files.readString(Path.of("/proc/loadavg")).strip().split(" ")[0];
            Files.writeString(Path.of("target", "network-figures.md"),
                    "| " + Instant.now().truncatedTo(ChronoUnit.SECONDS) + " | " + scenario + " | " + figures + " | " + load + " |\n",
                    StandardCharsets.UTF_8, StandardOpenOption.CREATE, StandardOpenOption.APPEND);
        } catch (IOException e) {
            System.err.println("network figures not written: " + e);
        }
    }
}
