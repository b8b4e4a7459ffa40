package io.robomw.cli;

import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

/** {@code mw describe}: robot files get the checks {@code mw host} makes; world files are recognised. */
class DescribeCommandTest {

    private static final Path ROBOTS = Path.of("../examples/robots");
    private static final Path NXT = ROBOTS.resolve("nxt-two-wheeled.yaml");

    @TempDir
    Path dir;

    /** @return a copy of the NXT robot file with one text replaced */
    private Path nxtWith(String name, String text, String replacement) throws IOException {
        String yaml = Files.readString(NXT);
        assertTrue(yaml.contains(text), text);
        Path file = dir.resolve(name);
        Files.writeString(file, yaml.replace(text, replacement));
        return file;
    }

    @Test
    void everyExampleRobotFitsItsPlatform() throws IOException {
        try (var files = Files.list(ROBOTS)) {
            for (Path file : files.filter(f -> f.toString().endsWith(".yaml")).sorted().toList()) {
                CliRun run = CliRun.mw("describe", file.toString());
                assertEquals(0, run.status(), file + ": " + run.err());
                assertTrue(run.out().contains("robot '"), run.out());
            }
        }
    }

    @Test
    void aWorldFileIsDescribedWithItsRobots() {
        CliRun run = CliRun.mw("describe", "../examples/worlds/arena.yaml");
        assertEquals(0, run.status(), run.err());
        assertTrue(run.out().contains("world 'arena', arena 4.00 × 3.00 m with walls, 3 obstacles, 1 floor patch, 3 robots"), run.out());
        assertTrue(run.out().contains("robot 'nxt' at (2.60, 0.40)"), run.out());
        assertTrue(run.out().contains("robot 'nxt-1' on platform 'nxt'") && run.out().contains("on platform 'ft-intelligent'") && run.out().contains("on platform 'aibo'"), run.out());
    }

    @Test
    void aMisspelledPlatformIsNamedWithTheSpellingMeant() throws IOException {
        CliRun run = CliRun.mw("describe", nxtWith("nxtt.yaml", "platform: nxt", "platform: nxtt").toString());
        assertEquals(2, run.status());
        assertTrue(run.err().contains("unknown platform 'nxtt'; did you mean 'nxt'?"), run.err());
    }

    @Test
    void portsAndSensorTypesTheBrickLacksAreRefusedAsMwHostRefusesThem() throws IOException {
        Path badPort = nxtWith("s9.yaml", "port: S4", "port: S9");
        CliRun port = CliRun.mw("describe", badPort.toString());
        assertEquals(2, port.status());
        assertTrue(port.err().contains("does not fit platform 'nxt': the NXT has input ports S1 to S4, not 'S9'"), port.err());

        Path gyro = nxtWith("gyro.yaml", "type: sonar", "type: gyro");
        CliRun type = CliRun.mw("describe", gyro.toString());
        assertEquals(2, type.status());
        assertTrue(type.err().contains("sensor 'sonar': the NXT has no standard gyro sensor"), type.err());

        Path motor = nxtWith("motor.yaml", "right: { port: C }", "right: { port: D }");
        CliRun motorPort = CliRun.mw("describe", motor.toString());
        assertEquals(2, motorPort.status());
        assertTrue(motorPort.err().contains("the NXT has motor ports A, B and C, not 'D'"), motorPort.err());

        // mw host makes the same check before it opens the link: the same line, and nothing is opened.
        CliRun host = CliRun.mw("host", "--name", "h", "--port", "0", "--no-messaging", "--robot", gyro.toString());
        assertEquals(2, host.status());
        assertTrue(host.err().contains("sensor 'sonar': the NXT has no standard gyro sensor"), host.err());
    }

    /** @return what {@code mw describe} printed, standard output and error in one stream, in the order printed */
    private static String describedInOrder(Path file) {
        java.io.StringWriter both = new java.io.StringWriter();
        picocli.CommandLine cl = Mw.commandLine();
        java.io.PrintWriter w = new java.io.PrintWriter(both, true);
        cl.setOut(w);
        cl.setErr(w);
        assertEquals(2, cl.execute("describe", file.toString()));
        return both.toString();
    }

    @Test
    void anUnknownPlatformIsReportedWithTheFilesOtherProblems() throws IOException {
        Path file = dir.resolve("two-problems.yaml");
        Files.writeString(file, Files.readString(NXT).replace("platform: nxt", "platform: nxtt").replace("cycle_hz: 100", "cycle_hz: 5000"));

        CliRun run = CliRun.mw("describe", file.toString());

        assertEquals(2, run.status());
        assertTrue(run.err().contains("2 problems:"), run.err());
        assertTrue(run.err().contains("two-problems.yaml:5:11: 'platform': unknown platform 'nxtt'; did you mean 'nxt'?"), run.err());
        assertTrue(run.err().contains("two-problems.yaml:9:11: 'cycle_hz' must be between 1 and 1000, got '5000'"), run.err());
        assertEquals("", run.out(), "a file that cannot be read is not described");
    }

    @Test
    void everyProblemIsPrintedBeforeTheDescription() throws IOException {
        String printed = describedInOrder(nxtWith("nxtt.yaml", "platform: nxt", "platform: nxtt"));

        int problem = printed.indexOf("unknown platform 'nxtt'");
        int description = printed.indexOf("robot 'nxt-1' on platform 'nxtt'");
        assertTrue(problem >= 0 && description > problem, printed);
    }

    @Test
    void aWorldOfTwoHundredRobotsFromOneFileDescribesThatFileOnce() throws IOException {
        Files.copy(NXT, dir.resolve("nxt.yaml"));
        StringBuilder world = new StringBuilder("name: swarm\narena: { width: 10, height: 10 }\nrobots:\n");
        for (int i = 0; i < 200; i++) {
            world.append(String.format(java.util.Locale.ROOT, "  - { robot: nxt.yaml, name: n%d, x: %.2f, y: %.2f }%n", i, 0.5 + (i % 20) * 0.45, 0.5 + (i / 20) * 0.5));
        }
        Files.writeString(dir.resolve("world.yaml"), world);

        CliRun run = CliRun.mw("describe", dir.resolve("world.yaml").toString());

        assertEquals(0, run.status(), run.err());
        assertEquals(1, run.out().split("robot 'nxt-1' on platform 'nxt'", -1).length - 1, run.out());
        assertTrue(run.out().contains("robot file " + dir.resolve("nxt.yaml") + ", for 200 robots: 'n0', 'n1', "), run.out());
        assertTrue(run.out().contains("'n19' and 180 more\n"), run.out());
        assertTrue(run.out().contains("robot 'n19' at (9.05, 0.50)") && !run.out().contains("robot 'n20' at"), run.out());
        assertTrue(run.out().contains("  ... and 180 more robots\n"), run.out());
    }

    @Test
    void aSwarmEntryIsDescribedAsItsCountAndOneRobotFile() throws IOException {
        Files.copy(NXT, dir.resolve("nxt.yaml"));
        Files.writeString(dir.resolve("world.yaml"), """
                name: crowd
                arena: { width: 100, height: 100 }
                robots:
                  - { robot: nxt.yaml, name: scout, x: 99, y: 99 }
                swarms:
                  - { robot: nxt.yaml, count: 10000, name: bot, seed: 5, area: { x: 0, y: 0, width: 90, height: 90 } }
                """);

        CliRun run = CliRun.mw("describe", dir.resolve("world.yaml").toString());

        assertEquals(0, run.status(), run.err());
        assertTrue(run.out().contains(", 10001 robots, "), run.out());
        assertTrue(run.out().contains("  robot 'scout' at (99.00, 99.00)"), run.out());
        assertTrue(run.out().contains("  swarm 'bot': 10000 robots ('bot-1' to 'bot-10000') from " + dir.resolve("nxt.yaml")
                + ", placed by seed 5 in 90.00 × 90.00 m at (0.00, 0.00)\n"), run.out());
        assertTrue(run.out().contains("robot file " + dir.resolve("nxt.yaml") + ", for 10001 robots: 'scout', swarm 'bot' (10000)\n"), run.out());
        assertTrue(!run.out().contains("robot 'bot-1' at") && !run.out().contains("more robots"), "a swarm's robots are not listed one by one: " + run.out());
        assertEquals(1, run.out().split("robot 'nxt-1' on platform 'nxt'", -1).length - 1, run.out());
    }
}
