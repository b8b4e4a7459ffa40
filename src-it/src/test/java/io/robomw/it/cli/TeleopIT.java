package io.robomw.it.cli;

import io.robomw.testkit.Await;
import io.robomw.api.Robot;
import io.robomw.api.Robots;
import io.robomw.it.demo.MwProcess;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;

import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * {@code mw robot ADDRESS teleop} at a real terminal (tmux): keys drive a robot of a simulated
 * world served by {@code mw host --serve}; space stops it; x stops it and quits with status 0.
 */
class TeleopIT {

    private static final Duration WAIT = Duration.ofSeconds(60);

    @TempDir
    Path dir;

    @Test
    void keysDriveAServedRobot() throws Exception {
        Path key = dir.resolve("cluster.key");
        Files.writeString(key, "teleop test passphrase");
        Path password = Files.writeString(dir.resolve("robot.password"), "teleop robot\n");
        try (MwProcess host = MwProcess.start("teleop-host", "host", "--name", "tele", "--port", "0", "--world", "examples/worlds/arena.yaml",
                "--world-robot", "nxt", "--serve", "tcp://127.0.0.1:0", "--serve-password-file", password.toString(), "--key-file", key.toString())) {
            String served = host.await("robot nxt served at", WAIT);
            String address = served.substring(served.lastIndexOf(' ') + 1) + "?password-file=" + password;
            Path script = dir.resolve("teleop.sh");
            Files.writeString(script, "exec '" + Path.of(System.getProperty("java.home"), "bin", "java") + "' -cp '" + MwProcess.middlewareOnlyClassPath()
                    + "' io.robomw.cli.Mw robot " + address + " teleop --speed 0.2\n");
            try (Tmux terminal = new Tmux("mw-teleop-it-" + ProcessHandle.current().pid());
                 Robot watcher = Robots.remote(address)) {
                terminal.typeLine("bash " + script + "; echo TELEOP-EXIT=$?");
                terminal.awaitScreen("teleop nxt:", WAIT);

                terminal.press("w");
                terminal.awaitScreen("driving 0.20 m/s, 0.00 rad/s", WAIT);
                poseUntil(watcher, "x > 0.1 m after w", p -> p.x() > 0.1);

                terminal.press(" ");
                terminal.awaitScreen("stopped 0.00 m/s", WAIT);

                terminal.press("a");
                poseUntil(watcher, "heading > 0.3 rad after a", p -> p.heading() > 0.3);

                terminal.press("x");
                terminal.awaitScreen("TELEOP-EXIT=0", WAIT);
                String screen = terminal.screen();
                assertTrue(screen.contains("stopped; pose x "), screen);
            }
        }
    }

    private static void poseUntil(Robot robot, String what, java.util.function.Predicate<io.robomw.api.Pose> condition) {
        Await.until(what + " (pose " + robot.pose() + ")", WAIT, () -> condition.test(robot.pose()));
    }
}
