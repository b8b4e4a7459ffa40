package io.robomw.cli;

import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;
import picocli.CommandLine;

import java.io.IOException;
import java.io.PrintWriter;
import java.io.StringWriter;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.List;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTimeoutPreemptively;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * {@code mw describe}, {@code mw sim} and {@code mw host} on the files of issue 15's bad-input
 * campaign: exit 2, one line per problem naming the file, line and column, and no stack trace;
 * quickly, whatever the file (an endless device, a self-referencing alias).
 */
class BadFilesCommandTest {

    @TempDir
    Path dir;

    private record Run(int exitCode, String out, String err) {
        List<String> errLines() {
            return err.lines().toList();
        }
    }

    private static Run mw(String... args) {
        return assertTimeoutPreemptively(Duration.ofSeconds(30), () -> {
            StringWriter out = new StringWriter();
            StringWriter err = new StringWriter();
            CommandLine cl = Mw.commandLine();
            cl.setOut(new PrintWriter(out, true));
            cl.setErr(new PrintWriter(err, true));
            int code = cl.execute(args);
            return new Run(code, out.toString(), err.toString());
        });
    }

    private Path file(String name, String text) throws IOException {
        Path f = dir.resolve(name);
        Files.writeString(f, text);
        return f;
    }

    /** Exit 2, and every line of standard error is a problem at a place of {@code file} (or the count line above them). */
    private static void assertRefusedAt(Run run, Path file, String... fragments) {
        assertEquals(2, run.exitCode(), run.err());
        assertFalse(run.err().contains("Exception") || run.err().contains("\tat ") || run.err().contains("Error:"), run.err());
        for (String line : run.errLines()) {
            assertTrue(line.matches("\\d+ problems:") || line.matches("\\s*(mw host: )?" + java.util.regex.Pattern.quote(file.toString()) + ":\\d+:\\d+: .+"),
                    () -> "not a problem line: '" + line + "' in:\n" + run.err());
        }
        for (String f : fragments) {
            assertTrue(run.err().contains(f), () -> "expected '" + f + "' in:\n" + run.err());
        }
    }

    @Test
    void describeRefusesASelfReferencingAliasWithoutAStackOverflow() throws IOException {
        Path robot = file("loop.yaml", "name: x\nplatform: nxt\nconnection: &c { self: *c }\n");

        assertRefusedAt(mw("describe", robot.toString()), robot, ":3:24: the alias *c");
    }

    @Test
    void describeRefusesAnOverflowingGearRatioWithoutATrace() throws IOException {
        Path robot = file("gear.yaml", """
                name: x
                platform: nxt
                drive: {wheel_diameter: 0.056, track_width: 0.1, gear_ratio: 1.0e+400, max_speed: 0.3, left: {port: B}, right: {port: C}}
                """);

        assertRefusedAt(mw("describe", robot.toString()), robot, "'drive.gear_ratio' must be > 0 (0.001 to 10000), got '1.0e+400'");
    }

    @Test
    void describeRefusesASensorWithoutPortAndDuplicateConnectionKeys() throws IOException {
        Path robot = file("port.yaml", """
                name: x
                platform: nxt
                connection: {port: a, port: b}
                sensors:
                  - {name: s, type: touch, position: front, port: ~}
                """);

        assertRefusedAt(mw("describe", robot.toString()), robot, "2 problems:", "key 'connection.port' appears twice", "'sensors[0].port' has no value");
    }

    @Test
    void describeOfAnEndlessDeviceRefusesItWithoutReading() {
        Path zero = Path.of("/dev/zero");

        assertRefusedAt(mw("describe", zero.toString()), zero, "/dev/zero:1:1: this is not a regular file");
    }

    @Test
    void describeRefusesANonUtf8FileAtItsFirstBadByteInWords() throws IOException {
        Path robot = dir.resolve("latin1.yaml");
        Files.write(robot, "name: x\nplatform: nxt\nconnection: {port: 'Gr\u00fcn'}\n".getBytes(StandardCharsets.ISO_8859_1));

        assertRefusedAt(mw("describe", robot.toString()), robot, ":3:23: the file is not UTF-8 text");
    }

    @Test
    void simRefusesAHugeWallAndAnEmptyArenaWithTheirPlaces() throws IOException {
        Path wall = file("wall.yaml", "arena: { width: 4, height: 3, wall_thickness: 1.0e+300 }\n");
        Path empty = file("empty.yaml", "name: empty\narena:\n");

        assertRefusedAt(mw("sim", wall.toString()), wall, ":1:47: 'arena.wall_thickness' must be > 0 metres (0.001 to 10)");
        assertRefusedAt(mw("sim", empty.toString()), empty, ":2:1: 'arena' has no value");
    }

    @Test
    void simRefusesAnAbsurdSensorOptionInOneLine() throws IOException {
        file("eyes.yaml", """
                name: eyes
                platform: sim
                sensors:
                  - { name: ir, type: infrared, position: front, port: S1, options: { rays: 1000000000 } }
                """);
        Path world = file("world.yaml", "arena: { width: 4, height: 3 }\nrobots:\n  - { robot: eyes.yaml, x: 1, y: 1 }\n");

        Run run = mw("sim", world.toString());

        assertEquals(2, run.exitCode(), run.err());
        assertEquals(1, run.errLines().size(), run.err());
        assertTrue(run.err().contains("sensor 'ir': option 'rays' must be a whole number from 1 to 100"), run.err());
        assertFalse(run.err().contains("Exception"), run.err());
    }

    @Test
    void hostRefusesABadRobotFileWithoutStartingOrATrace() throws IOException {
        Path robot = file("loop.yaml", "name: x\nplatform: nxt\nconnection: &c { self: *c }\n");
        Path key = file("cluster.key", "a cluster passphrase for this test only");

        Run run = mw("host", "--name", "h", "--port", "0", "--robot", robot.toString(), "--key-file", key.toString());

        assertRefusedAt(run, robot, ":3:24: the alias *c");
    }
}
