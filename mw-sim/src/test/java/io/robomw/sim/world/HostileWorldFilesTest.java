package io.robomw.sim.world;

import io.robomw.api.RobotException;
import io.robomw.config.description.DescriptionException;
import io.robomw.config.description.DescriptionException.Problem;
import io.robomw.sim.Simulation;
import io.robomw.sim.sensing.RangeIndex;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.List;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTimeoutPreemptively;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * World files from the bad-input campaign of issue 15: infinite and absurd sizes that used to be
 * simulated or to end in {@code ArrayIndexOutOfBoundsException} in the range index or in dyn4j's
 * words without a location, an {@code arena:} without a value, a self-referencing alias in a
 * robot file the world names. Each is refused with the file, line and column.
 */
class HostileWorldFilesTest {

    private static final String ROBOT = """
            name: bot
            platform: sim
            drive: { wheel_diameter: 0.05, track_width: 0.1, max_speed: 0.3, left: { port: A }, right: { port: B } }
            """;

    @TempDir
    Path dir;

    private Path world(String yaml) throws IOException {
        Files.writeString(dir.resolve("bot.yaml"), ROBOT);
        Path file = dir.resolve("world.yaml");
        Files.writeString(file, yaml);
        return file;
    }

    private DescriptionException refused(String yaml) throws IOException {
        Path file = world(yaml);
        return assertTimeoutPreemptively(Duration.ofSeconds(10), () -> assertThrows(DescriptionException.class, () -> Simulation.load(file).close()));
    }

    private static void assertPlain(Problem p) {
        assertFalse(p.message().contains("\n"), p::toString);
        assertFalse(p.message().matches("(?s).*(Exception|Error|java\\.|dyn4j).*"), p::toString);
    }

    /** "line:key" of every problem, the key being the quoted path the message starts with. */
    private static List<String> where(DescriptionException e) {
        e.problems().forEach(HostileWorldFilesTest::assertPlain);
        return e.problems().stream().map(p -> p.line() + ":" + p.message().substring(0, p.message().indexOf('\'', 1) + 1)).toList();
    }

    @Test
    void hugeWallThicknessIsRefusedInsteadOfBreakingTheRangeIndex() throws IOException {
        DescriptionException e = refused("""
                arena: { width: 4, height: 3, wall_thickness: 1.0e+300 }
                """);

        assertEquals(List.of("1:'arena.wall_thickness'"), where(e));
        assertTrue(e.getMessage().contains("(0.001 to 10)"), e::getMessage);
    }

    @Test
    void infiniteAndAbsurdSizesAreRefusedEverywhere() throws IOException {
        DescriptionException e = refused("""
                arena: { width: 1.0e+400, height: 3 }
                obstacles:
                  - box: { x: 1, y: 1, width: 1.0e+400, height: 0.5, angle: 1.0e+300 }
                  - circle: { x: 1.0e+300, y: 1, radius: 0.2 }
                floor:
                  - { x: 0, y: 0, width: 1.0e+300, height: 1, color: 99999 }
                robots:
                  - { robot: bot.yaml, x: 1, y: 1, heading: 1.0e+400 }
                """);

        assertEquals(List.of("1:'arena.width'", "3:'obstacles[0].box.width'", "3:'obstacles[0].box.angle'", "4:'obstacles[1].circle.x'",
                "6:'floor[0].width'", "6:'floor[0].color'", "8:'robots[0].heading'"), where(e));
    }

    @Test
    void polygonPointAtInfinityIsRefusedWithItsLocation() throws IOException {
        DescriptionException e = refused("""
                arena: { width: 4, height: 3 }
                obstacles:
                  - polygon: [[0.5, 0.5], [1.0e+400, 0.5], [0.8, 1.0]]
                """);

        assertEquals(1, e.problems().size(), e::getMessage);
        Problem p = e.problems().get(0);
        assertEquals(3, p.line());
        assertTrue(p.message().contains("must be numbers of a usable size, got '1.0e+400'"), p::toString);
        assertPlain(p);
    }

    @Test
    void degeneratePolygonsAreRefusedBeforeDyn4jSeesThem() throws IOException {
        DescriptionException e = refused("""
                arena: { width: 4, height: 3 }
                obstacles:
                  - polygon: [[0.5, 0.5], [0.5000001, 0.5], [0.6, 1.0]]
                  - polygon: [[0.5, 0.5], [2.5, 0.5], [1.5, 0.5000001]]
                  - polygon: [[2000, 0.5], [2.5, 0.5], [1.5, 1.5]]
                """);

        assertEquals(3, e.problems().size(), e::getMessage);
        assertTrue(e.problems().get(0).message().contains("closer than 1 mm"), e::getMessage);
        assertTrue(e.problems().get(1).message().contains("less than 1 mm²"), e::getMessage);
        assertTrue(e.problems().get(2).message().contains("between -1000 and 1000 metres"), e::getMessage);
    }

    @Test
    void arenaWithNoValueIsRefusedAtItsKey() throws IOException {
        DescriptionException e = refused("""
                name: empty
                arena:
                """);

        assertEquals(1, e.problems().size(), e::getMessage);
        Problem p = e.problems().get(0);
        assertEquals(2, p.line());
        assertEquals(1, p.column());
        assertTrue(p.message().contains("'arena' has no value; write a mapping of keys to values"), p::toString);
    }

    @Test
    void selfReferencingAliasInARobotFileTheWorldNamesIsRefusedInThatFile() throws IOException {
        Path file = world("""
                arena: { width: 4, height: 3 }
                robots:
                  - { robot: loop.yaml, x: 1, y: 1 }
                """);
        Files.writeString(dir.resolve("loop.yaml"), "name: loop\nplatform: sim\nconnection: &c { self: *c }\n");

        DescriptionException e = assertTimeoutPreemptively(Duration.ofSeconds(10),
                () -> assertThrows(DescriptionException.class, () -> Simulation.load(file).close()));

        Problem p = e.problems().get(0);
        assertTrue(p.file().endsWith("loop.yaml"), p::toString);
        assertEquals(3, p.line());
        assertTrue(p.message().contains("*c"), p::toString);
    }

    @Test
    void absurdSimulatorSensorOptionIsRefusedNamingTheSensorAndTheRange() throws IOException {
        Path file = world("""
                arena: { width: 4, height: 3 }
                robots:
                  - { robot: eyes.yaml, x: 1, y: 1 }
                """);
        Files.writeString(dir.resolve("eyes.yaml"), ROBOT.replace("name: bot", "name: eyes")
                + "sensors:\n  - { name: ir, type: infrared, position: front, port: S1, options: { rays: 1000000000 } }\n");

        RobotException e = assertTimeoutPreemptively(Duration.ofSeconds(10),
                () -> assertThrows(RobotException.class, () -> Simulation.load(file).close()));

        assertTrue(e.getMessage().matches(".*world\\.yaml: robot 'eyes' \\(.*eyes\\.yaml\\): sensor 'ir': option 'rays' must be a whole number from 1 to 100, "
                + "got '1000000000'.*"), e::getMessage);
    }

    @Test
    void selfReferencingAliasInTheWorldFileItselfIsRefusedAtTheAlias() throws IOException {
        DescriptionException e = refused("""
                arena: &a { width: 4, height: 3, inner: *a }
                """);

        Problem p = e.problems().get(0);
        assertTrue(p.file().endsWith("world.yaml"), p::toString);
        assertEquals(1, p.line());
        assertTrue(p.message().contains("*a"), p::toString);
        assertPlain(p);
    }

    @Test
    void duplicateKeysInTheWorldFileAreAnError() throws IOException {
        DescriptionException e = refused("""
                arena: { width: 4, height: 3, width: 5 }
                """);

        assertTrue(e.problems().stream().anyMatch(p -> p.line() == 1 && p.message().contains("width")
                && p.message().contains("appears twice")), e::getMessage);
    }

    @Test
    void worldFileAboveOneMebibyteIsRefusedWithoutReadingItAll() throws IOException {
        DescriptionException e = refused("arena: { width: 4, height: 3 }\n# " + "x".repeat(2 << 20) + "\n");

        assertTrue(e.getMessage().contains("larger than 1 MiB"), e::getMessage);
    }

    @Test
    void nonUtf8WorldFileIsRefusedInWords() throws IOException {
        Path file = dir.resolve("latin1.yaml");
        Files.write(file, "arena: { width: 4, height: 3 }\nname: caf\u00e9\n".getBytes(java.nio.charset.StandardCharsets.ISO_8859_1));

        DescriptionException e = assertThrows(DescriptionException.class, () -> Simulation.load(file).close());

        Problem p = e.problems().get(0);
        assertEquals(2, p.line(), p::toString);
        assertTrue(p.message().contains("UTF-8"), p::toString);
        assertPlain(p);
    }

    @Test
    void rangeIndexRefusesAreasItCannotGridInsteadOfOverflowing() {
        IllegalArgumentException huge = assertThrows(IllegalArgumentException.class,
                () -> new RangeIndex(-1e300, -1e300, 2e300, 2e300, 2.0, new double[0][], new double[0][]));
        assertTrue(huge.getMessage().contains("cells"), huge::getMessage);
        assertThrows(IllegalArgumentException.class,
                () -> new RangeIndex(0, 0, Double.POSITIVE_INFINITY, 1, 1, new double[0][], new double[0][]));
        assertThrows(IllegalArgumentException.class,
                () -> new RangeIndex(0, 0, 10, 10, 1, new double[][] {{0, 0, Double.NaN, 1}}, new double[0][]));
    }

    /** Issue 37: a world's {@code robot: /etc/shadow} was followed, and the file's lines came back in the error messages. */
    @Test
    void robotFilesOutsideTheWorldsTreeAreRefusedUnreadAndNeverQuoted() throws IOException {
        Path project = Files.createDirectories(dir.resolve("home/project"));
        Files.createDirectories(project.resolve("worlds"));
        Files.createDirectories(project.resolve("robots"));
        Files.writeString(project.resolve("robots/bot.yaml"), ROBOT);
        Path secret = Files.writeString(dir.resolve("secret.yaml"), "root: TOPSECRET-HASH\n");
        Files.createDirectories(project.resolve(".ssh"));
        Files.writeString(project.resolve(".ssh/id.yaml"), "key: TOPSECRET-KEY\n");
        Files.createSymbolicLink(project.resolve("robots/link.yaml"), secret);
        Path world = project.resolve("worlds/world.yaml");
        Files.writeString(world, """
                arena: { width: 4, height: 3 }
                robots:
                  - { robot: ../robots/bot.yaml, name: ok, x: 1, y: 1 }
                  - { robot: %s, name: absolute, x: 1, y: 1 }
                  - { robot: ../../../secret.yaml, name: climbing, x: 1, y: 1 }
                  - { robot: ../.ssh/id.yaml, name: hidden, x: 1, y: 1 }
                  - { robot: ../robots/link.yaml, name: linked, x: 1, y: 1 }
                """.formatted(secret));

        DescriptionException e = assertTimeoutPreemptively(Duration.ofSeconds(10),
                () -> assertThrows(DescriptionException.class, () -> Simulation.load(world).close()));

        assertEquals(List.of(4, 5, 6, 7), e.problems().stream().map(Problem::line).toList(), e::getMessage);
        assertTrue(e.problems().stream().allMatch(p -> p.message().contains("refused")), e::getMessage);
        assertFalse(e.getMessage().contains("TOPSECRET"), "no line of another file comes back: " + e.getMessage());
    }

    @Test
    void aWorldMayNameTheRobotFilesOfItsProject() throws IOException {
        Path project = Files.createDirectories(dir.resolve("home/project"));
        Files.createDirectories(project.resolve("worlds"));
        Files.createDirectories(project.resolve("robots"));
        Files.writeString(project.resolve("robots/bot.yaml"), ROBOT);
        Path world = Files.writeString(project.resolve("worlds/world.yaml"), """
                arena: { width: 4, height: 3 }
                robots:
                  - { robot: ../robots/bot.yaml, name: ok, x: 1, y: 1 }
                """);

        assertEquals("ok", new WorldLoader().load(world).robots().get(0).name());
    }
}
