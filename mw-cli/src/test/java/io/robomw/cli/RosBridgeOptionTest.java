package io.robomw.cli;

import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.LinkedHashMap;
import java.util.Map;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/** --rosbridge's options: the token from a file, what is printed, and what it cannot be combined with. */
class RosBridgeOptionTest {

    private static final Path ARENA = Path.of("../examples/worlds/arena.yaml");

    @Test
    void theTokenIsTheFilesFirstLine(@TempDir Path dir) throws IOException {
        Path file = dir.resolve("token");
        Files.writeString(file, "  s3cret-token-of-some-length \nsecond line\n");
        assertEquals("s3cret-token-of-some-length", RosBridgeOption.token(file));
        Files.writeString(file, "\n");
        IOException e = assertThrows(IOException.class, () -> RosBridgeOption.token(file));
        assertTrue(e.getMessage().contains("is empty"), e.getMessage());
    }

    @Test
    void theAddressLineSaysWhichNamespaceEachRobotHas() {
        Map<String, String> ns = new LinkedHashMap<>();
        ns.put("nxt", "nxt");
        ns.put("nxt-1", "nxt_1");
        assertEquals("robots: /nxt, nxt-1 as /nxt_1", RosBridgeOption.describe(ns));
        assertEquals("no robots", RosBridgeOption.describe(Map.of()));
    }

    @Test
    void aWorldServedToRosClientsRunsInRealTimeSoNotWithFast() {
        CliRun run = CliRun.mw("sim", ARENA.toString(), "--rosbridge", "0", "--fast");
        assertEquals(Mw.USER_ERROR, run.status());
        assertTrue(run.err().contains("--rosbridge runs the world in real time"), run.err());
    }

    @Test
    void aBindBeyondThisMachineWithoutATokenIsRefused() {
        CliRun run = CliRun.mw("rosbridge", "../examples/robots/nxt-two-wheeled.yaml", "--bind", "0.0.0.0", "--port", "0");
        assertEquals(Mw.USER_ERROR, run.status());
        assertTrue(run.err().contains("needs an access token"), "refused before the robot's link is opened: " + run.err());
    }
}
