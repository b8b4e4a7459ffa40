package io.robomw.it.cli;

import io.robomw.testkit.Ports;
import io.robomw.it.demo.MwProcess;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.List;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * {@code mw up}: the quickstart's setup (examples/quickstart-up.yaml, with free ports and a key of
 * the test's) comes up from one file (each host opened its robot file, written by its emulator,
 * with the real driver, or it would not be ready), the hosts answer, and stopping {@code mw up}
 * stops every process it started.
 */
class UpIT {

    private static final Duration WAIT = Duration.ofSeconds(90);

    @TempDir
    Path dir;

    @Test
    void ctrlCAtTheTerminalStopsTheProcessesLastFirstAndOnlyMwUpGetsIt() throws Exception {
        Path key = dir.resolve("cluster.key");
        Files.writeString(key, "up test passphrase");
        int nxtPort = Ports.free();
        int ftPort = Ports.free();
        String setup = Files.readString(MwProcess.CHECKOUT.resolve("examples/quickstart-up.yaml"))
                .replace("worlds/arena.yaml", MwProcess.CHECKOUT.resolve("examples/worlds/arena.yaml").toString())
                .replace("../cluster.key", key.toString())
                .replace("--port 1099", "--port " + nxtPort).replace("--port 1100", "--port " + ftPort);
        Path file = dir.resolve("up.yaml");
        Files.writeString(file, setup);
        Path script = dir.resolve("up.sh");
        Files.writeString(script, "exec '" + Path.of(System.getProperty("java.home"), "bin", "java") + "' -Dmw.home='" + MwProcess.CHECKOUT + "' -cp '"
                + MwProcess.middlewareOnlyClassPath() + "' io.robomw.cli.Mw up '" + file + "'\n");
        try (Tmux terminal = new Tmux("mw-up-it-" + ProcessHandle.current().pid())) {
            terminal.typeLine("bash " + script + "; echo UP-EXIT=$?");
            terminal.awaitScreen("[mw up] 4 processes up", WAIT);
            terminal.ctrlC(); // SIGINT to the terminal's foreground process group, as a person's Ctrl-C
            terminal.awaitScreen("[mw up] stopped 4 processes", WAIT);
            String screen = terminal.screen();
            List<String> names = List.of("ft-host", "nxt-host", "ft-brick", "nxt-brick");
            int last = -1;
            for (String name : names) {
                String stopped = "[mw up] " + name + " stopped (exit status 143)"; // SIGTERM from mw up, not the terminal's SIGINT (130)
                int at = screen.indexOf(stopped);
                assertTrue(at > last, "'" + stopped + "' comes after the one before, last started first:\n" + screen);
                last = at;
            }
        }
    }

    @Test
    void theQuickstartComesUpFromOneFileAndGoesDownWithIt() throws Exception {
        Path key = dir.resolve("cluster.key");
        Files.writeString(key, "up test passphrase");
        int nxtPort = Ports.free();
        int ftPort = Ports.free();
        String setup = Files.readString(MwProcess.CHECKOUT.resolve("examples/quickstart-up.yaml"))
                .replace("worlds/arena.yaml", MwProcess.CHECKOUT.resolve("examples/worlds/arena.yaml").toString())
                .replace("../cluster.key", key.toString())
                .replace("--port 1099", "--port " + nxtPort).replace("--port 1100", "--port " + ftPort);
        Path file = dir.resolve("up.yaml");
        Files.writeString(file, setup);
        List<ProcessHandle> children;
        try (MwProcess up = MwProcess.start("up", "up", file.toString())) {
            up.await("[mw up] 4 processes up", WAIT);
            try (MwProcess agents = MwProcess.start("up-agents", "agents", "--key-file", key.toString(), "rmi://127.0.0.1:" + nxtPort + "/nxt")) {
                agents.await("0 agents at rmi://127.0.0.1:" + nxtPort + "/nxt", WAIT);
                assertEquals(0, agents.waitFor(WAIT));
            }
            children = up.children();
            assertEquals(4, children.size(), "one JVM per process: " + children);
        }
        for (ProcessHandle c : children) {
            c.onExit().get(30, java.util.concurrent.TimeUnit.SECONDS);
            assertFalse(c.isAlive(), "stopped with mw up: " + c.info());
        }
    }
}
