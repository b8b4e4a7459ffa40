package io.robomw.it.docs;

import io.robomw.it.demo.MwProcess;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.List;

import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * docs/first-agent-project.md, run as written against a fresh local Maven repository into which
 * RoboMW was installed ({@link FreshRepository}): {@code mw new agent} and {@code mw new program}
 * write projects that build offline with Maven (their tests run a simulated robot), the agent's
 * jar is dispatched to two agent hosts as it stands and its clones come home, and the program
 * runs against a virtual NXT.
 */
class FirstAgentProjectDocIT {

    @TempDir
    Path dir;

    @Test
    void thePageRunsAsWrittenFromAFreshRepository() throws Exception {
        Path repo = FreshRepository.create(dir);
        Path scratch = Files.createDirectories(dir.resolve("work"));
        List<String> commands = DocCommands.commands(MwProcess.CHECKOUT.resolve("docs/first-agent-project.md"));
        try (DocCommands doc = new DocCommands(scratch).maven(List.of("-o", "-B", "-Dmaven.repo.local=" + repo))) {
            StringBuilder all = new StringBuilder();
            for (String command : commands) {
                all.append(doc.run(command, Duration.ofMinutes(5)));
            }
            String out = all.toString();
            assertTrue(Files.isRegularFile(scratch.resolve("patrol/target/patrol-1.0-SNAPSHOT.jar")), doc.transcript());
            // each line names the host the clone was at and, as there are two, the clone
            assertTrue(out.matches("(?s).*\\[rmi://127\\.0\\.0\\.1:7101/a [0-9a-f]{8}] nxt at a drove 0\\.20 m.*"), "the clone at a reported:\n" + doc.transcript());
            assertTrue(out.matches("(?s).*\\[rmi://127\\.0\\.0\\.1:7102/b [0-9a-f]{8}] ft at b drove 0\\.20 m.*"), "the clone at b reported:\n" + doc.transcript());
            assertTrue(out.contains("nxt-1 drove a square; odometry ("), "the program ran:\n" + doc.transcript());
            assertTrue(Files.readString(scratch.resolve("patrol/pom.xml")).contains("<artifactId>mw-bom</artifactId>"));
        }
        assertTrue(Files.isDirectory(repo.resolve("io/robomw/mw-api/" + FreshRepository.VERSION)), "RoboMW came from the fresh repository");
    }
}
