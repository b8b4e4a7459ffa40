package io.robomw.cli;

import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

import java.nio.file.Files;
import java.nio.file.Path;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.TimeUnit;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

/** {@code mw replay}: the README's form with {@code --png} writes the picture and exits. */
class ReplayCommandTest {

    private static final Path ARENA = Path.of("../examples/worlds/arena.yaml");

    @TempDir
    Path dir;

    @Test
    void replayWithPngWritesThePictureAndExitsWithoutKeepingAConsole() throws Exception {
        Path recording = dir.resolve("run.mcap");
        CliRun sim = CliRun.mw("sim", ARENA.toString(), "--fast", "--program", "square", "--side", "0.1", "--duration", "30s", "--record", recording.toString());
        assertEquals(0, sim.status(), sim.toString());
        Path png = dir.resolve("run.png");
        // As README.md gives it (no --no-console): it must end by itself, not wait for Ctrl-C.
        CliRun replay = CompletableFuture.supplyAsync(() -> CliRun.mw("replay", recording.toString(), "--speed", "0", "--png", png.toString()))
                .get(120, TimeUnit.SECONDS);
        assertEquals(0, replay.status(), replay.toString());
        assertTrue(Files.size(png) > 0, "the picture was written");
        assertTrue(replay.out().contains("wrote " + png), replay.out());
        assertFalse(replay.out().contains("console at"), "no page was opened: " + replay.out());
    }

    @Test
    void consoleAndNoConsoleTogetherAreAUsageError() {
        CliRun run = CliRun.mw("replay", "x.mcap", "--png", "x.png", "--console", "--no-console");
        assertEquals(2, run.status(), run.toString());
        assertTrue(run.err().contains("--console and --no-console contradict each other"), run.err());
    }
}
