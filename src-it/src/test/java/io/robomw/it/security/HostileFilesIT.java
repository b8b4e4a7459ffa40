package io.robomw.it.security;

import io.robomw.it.demo.MwProcess;
import org.junit.jupiter.api.Assumptions;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.concurrent.TimeUnit;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * Issue 37, found 7: a world file's {@code robot: /etc/shadow} was followed and the file's lines
 * came back in the error messages; {@code mw describe} on a FIFO nobody writes to hung. A real
 * {@code mw describe}, as a user who downloaded someone's world would run it.
 */
class HostileFilesIT {

    @TempDir
    Path dir;

    @Test
    void aWorldCannotMakeMwReadAndQuoteAFileOutsideItsTree() throws Exception {
        // Someone's private file, which the loader would quote (an unknown platform is named in the error).
        Path secret = Files.writeString(dir.resolve("private.yaml"), "name: x\nplatform: TOPSECRET-LINE\n");
        Path project = Files.createDirectories(dir.resolve("downloads/project/worlds"));
        Path world = Files.writeString(project.resolve("world.yaml"), """
                arena: { width: 4, height: 3 }
                robots:
                  - { robot: %s, name: r, x: 1, y: 1 }
                """.formatted(secret));
        try (MwProcess describe = MwProcess.start("describe-traversal", "describe", world.toString())) {
            assertEquals(2, describe.waitFor(Duration.ofSeconds(60)), describe.output());
            String said = describe.output() + Files.readString(Path.of("target", "it-logs", "describe-traversal.log"));
            assertTrue(said.contains("refused"), "the path is refused: " + said);
            assertFalse(said.contains("TOPSECRET"), "nothing of the other file comes back: " + said);
        }
    }

    @Test
    void describeRefusesAFifoAtOnce() throws Exception {
        Path fifo = dir.resolve("robot.yaml");
        Process mkfifo = new ProcessBuilder("mkfifo", fifo.toString()).start();
        Assumptions.assumeTrue(mkfifo.waitFor(10, TimeUnit.SECONDS) && mkfifo.exitValue() == 0, "mkfifo is available");
        try (MwProcess describe = MwProcess.start("describe-fifo", "describe", fifo.toString())) {
            assertEquals(2, describe.waitFor(Duration.ofSeconds(30)), "refused, not waiting for a writer: " + describe.output());
            assertTrue(Files.readString(Path.of("target", "it-logs", "describe-fifo.log")).contains("not a regular file"));
        }
    }
}
