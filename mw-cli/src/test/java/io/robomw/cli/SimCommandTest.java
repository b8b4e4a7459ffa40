package io.robomw.cli;

import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;
import picocli.CommandLine;

import javax.imageio.ImageIO;
import java.awt.GraphicsEnvironment;
import java.awt.image.BufferedImage;
import java.io.IOException;
import java.io.PrintWriter;
import java.io.StringWriter;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.Arrays;
import java.util.regex.Matcher;
import java.util.regex.Pattern;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;
import static org.junit.jupiter.api.Assumptions.assumeTrue;

/** {@code mw sim} through picocli, as the launcher runs it, on the example worlds. */
class SimCommandTest {

    /** Tests run in the module's folder; the examples are one level up. */
    private static final Path ARENA = Path.of("../examples/worlds/arena.yaml");

    @TempDir
    Path dir;

    /** Exit code, standard output and standard error of one run. */
    private record Run(int exitCode, String out, String err) {
    }

    private static Run mw(String... args) {
        StringWriter out = new StringWriter();
        StringWriter err = new StringWriter();
        CommandLine cl = Mw.commandLine();
        cl.setOut(new PrintWriter(out, true));
        cl.setErr(new PrintWriter(err, true));
        int code = cl.execute(args);
        return new Run(code, out.toString(), err.toString());
    }

    /** @return the "driven (m)" column of a robot's summary row */
    private static double driven(Run run, String robot) {
        Matcher m = Pattern.compile("(?m)^" + robot + "\\s+\\S+\\s+\\S+\\s+\\S+\\s+(\\S+)$").matcher(run.out());
        assertTrue(m.find(), "no summary row for " + robot + " in:\n" + run.out());
        return Double.parseDouble(m.group(1));
    }

    @Test
    void shouldDriveSquaresOnExampleArenaAndWritePng() throws IOException {
        Path png = dir.resolve("out.png");
        Run run = mw("sim", ARENA.toString(), "--png", png.toString(), "--program", "square");
        assertEquals(0, run.exitCode(), run.err());
        BufferedImage image = ImageIO.read(png.toFile());
        assertEquals(1000, image.getWidth());
        assertEquals(2.0, driven(run, "nxt"), 0.05, "four 0.5 m sides");
        assertEquals(2.0, driven(run, "ft"), 0.05, "the fischertechnik robot drives its square too");
    }

    @Test
    void shouldExitTwoWithFileLineAndColumnForInvalidWorld() throws IOException {
        Path world = dir.resolve("broken.yaml");
        Files.writeString(world, """
                name: broken
                arena: { width: -4, height: 3 }
                """);
        Run run = mw("sim", world.toString());
        assertEquals(2, run.exitCode());
        assertTrue(run.err().matches("(?s).*broken\\.yaml:2:\\d+: .*width.*"), run.err());
    }

    @Test
    void shouldExitTwoWithFileLineAndColumnForInvalidRobotFile() throws IOException {
        Files.writeString(dir.resolve("bad-robot.yaml"), """
                name: bad
                platform: sim
                drive: { wheel_diameter: -1, track_width: 0.1, max_speed: 0.2, left: { port: A }, right: { port: B } }
                """);
        Path world = dir.resolve("world.yaml");
        Files.writeString(world, """
                arena: { width: 2, height: 2 }
                robots:
                  - { robot: bad-robot.yaml, x: 1, y: 1 }
                """);
        Run run = mw("sim", world.toString());
        assertEquals(2, run.exitCode());
        assertTrue(run.err().matches("(?s).*bad-robot\\.yaml:3:\\d+: .*wheel_diameter.*"), run.err());
    }

    @Test
    void shouldExitOneAndStillDrawWhenSquareRunsOverDuration() {
        Path png = dir.resolve("short.png");
        Run run = mw("sim", ARENA.toString(), "--png", png.toString(), "--program", "square", "--duration", "2");
        assertEquals(1, run.exitCode());
        assertTrue(run.err().contains("did not finish within 2.0 s"), run.err());
        assertTrue(Files.isRegularFile(png), "the picture shows how far the robots got");
    }

    @Test
    void shouldGiveSameSummaryForSameWorldInFastMode() {
        Run first = mw("sim", ARENA.toString(), "--program", "wander", "--duration", "10");
        Run second = mw("sim", ARENA.toString(), "--program", "wander", "--duration", "10", "--fast");
        assertEquals(0, first.exitCode(), first.err());
        assertEquals(rows(first), rows(second), "bit for bit, so the printed poses are equal");
    }

    private static String rows(Run run) {
        return Arrays.stream(run.out().split("\n")).filter(l -> l.startsWith("nxt") || l.startsWith("ft")).reduce("", (a, b) -> a + b + "\n");
    }

    @Test
    void shouldRunSquareInRealTimeUntilDuration() {
        // The square takes about 8.5 simulated seconds; at 64 times real time a program thread that
        // a loaded machine holds up for 25 ms loses 1.6 of them, so the run gets 60 (under a second).
        Run run = mw("sim", ARENA.toString(), "--realtime", "--speed", "64", "--duration", "60", "--program", "square", "--side", "0.1");
        assertEquals(0, run.exitCode(), run.err());
        assertEquals(0.4, driven(run, "nxt"), 0.02);
    }

    @Test
    void shouldRefuseViewWithoutDisplay() {
        assumeTrue(GraphicsEnvironment.isHeadless(), "this machine has a display");
        Run run = mw("sim", ARENA.toString(), "--view");
        assertEquals(2, run.exitCode());
        assertTrue(run.err().contains("--view needs a display"), run.err());
    }

    @Test
    void shouldRefuseViewWithFast() {
        Run run = mw("sim", ARENA.toString(), "--view", "--fast");
        assertEquals(2, run.exitCode());
        assertTrue(run.err().contains("cannot be combined with --fast"), run.err());
    }

    @Test
    void shouldRefuseRealTimeWithFast() {
        Run run = mw("sim", ARENA.toString(), "--realtime", "--fast");
        assertEquals(2, run.exitCode());
        assertTrue(run.err().contains("mutually exclusive"), run.err());
    }

    @Test
    void shouldRefuseUnknownProgram() {
        Run run = mw("sim", ARENA.toString(), "--program", "dance");
        assertEquals(2, run.exitCode());
        assertTrue(run.err().contains("'dance' is not a program; choose square, wander or none"), run.err());
    }
}
