package io.robomw.sim.world;

import io.robomw.config.description.DescriptionException;
import io.robomw.config.description.DescriptionException.Problem;
import io.robomw.config.yaml.Problems;
import io.robomw.sim.Simulation;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;
import org.junit.jupiter.params.ParameterizedTest;
import org.junit.jupiter.params.provider.ValueSource;

import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.List;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTimeoutPreemptively;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * A world file that starts a robot inside an obstacle, a wall or another robot is refused at the
 * robot's line, naming both and how deep they overlap, whatever the physics engine (the physics
 * used to push them apart silently at the first step).
 */
class OverlappingPlacementsTest {

    /** A robot 0.20 m long (x at heading 0) and 0.10 m wide; slow enough for the swarm engine. */
    private static final String ROBOT = """
            name: bot
            platform: sim
            drive: { wheel_diameter: 0.05, track_width: 0.1, max_speed: 0.2, left: { port: A }, right: { port: B } }
            body: { length: 0.20, width: 0.10 }
            """;

    @TempDir
    Path dir;

    private Path world(String engine, String obstacles, String robots) throws IOException {
        Files.writeString(dir.resolve("bot.yaml"), ROBOT);
        Path file = dir.resolve("world.yaml");
        Files.writeString(file, """
                name: crowded
                arena: { width: 4, height: 3 }
                physics: { engine: %s }
                obstacles:
                %s
                robots:
                %s
                """.formatted(engine, obstacles.indent(2).stripTrailing(), robots.indent(2).stripTrailing()));
        return file;
    }

    private static Problem onlyProblem(Path file) {
        DescriptionException e = assertThrows(DescriptionException.class, () -> new WorldLoader().load(file));
        assertEquals(1, e.problems().size(), e.getMessage());
        return e.problems().get(0);
    }

    @ParameterizedTest(name = "engine {0}")
    @ValueSource(strings = {"dyn4j", "swarm"})
    void shouldRefuseARobotOverlappingAnotherAtTheLaterOnesLineNamingBoth(String engine) throws IOException {
        Path file = world(engine, "- { circle: { x: 3, y: 2, radius: 0.1 } }", """
                - { robot: bot.yaml, name: first, x: 1.0, y: 1.0 }
                - { robot: bot.yaml, name: second, x: 1.15, y: 1.0 }
                """);

        Problem p = onlyProblem(file);

        assertEquals(file.toString(), p.file());
        assertEquals(8, p.line(), p.toString());
        assertEquals(5, p.column(), p.toString());
        assertEquals("'robots[1]': robot 'second' overlaps robot 'first' (robots[0], line 7) by 5.0 cm at the start; place it clear of it "
                + "(the physics would push them apart at the first step, and the world would start elsewhere than this file says)", p.message());
        assertThrows(DescriptionException.class, () -> Simulation.load(file).close(), "a simulation refuses it too");
    }

    @ParameterizedTest(name = "engine {0}")
    @ValueSource(strings = {"dyn4j", "swarm"})
    void shouldRefuseARobotInsideAnObstacleNamingTheObstacleAndItsLine(String engine) throws IOException {
        Path file = world(engine, """
                - { circle: { x: 3, y: 2, radius: 0.1 } }
                - { box: { x: 2, y: 1.5, width: 0.4, height: 0.4 } }
                """, "- { robot: bot.yaml, name: stuck, x: 2.25, y: 1.5 }");

        Problem p = onlyProblem(file);

        assertEquals(8, p.line(), p.toString());
        assertTrue(p.message().startsWith("'robots[0]': robot 'stuck' starts inside the box at (2, 1.5) (obstacles[1], line 6) by 5.0 cm at the start"),
                p.message());
    }

    @Test
    void shouldRefuseARobotInACircleAPolygonAndAWallEachAtItsOwnLine() throws IOException {
        Path file = world("dyn4j", """
                - { circle: { x: 3, y: 2, radius: 0.2 } }
                - { polygon: [[1, 2], [1.5, 2], [1.25, 2.5]] }
                """, """
                - { robot: bot.yaml, name: in-circle, x: 3.25, y: 2 }
                - { robot: bot.yaml, name: in-polygon, x: 1.25, y: 2.1 }
                - { robot: bot.yaml, name: in-wall, x: 0.05, y: 1, heading: 0 }
                - { robot: bot.yaml, name: free, x: 2, y: 1 }
                """);

        DescriptionException e = assertThrows(DescriptionException.class, () -> new WorldLoader().load(file));

        List<String> where = e.problems().stream().map(p -> p.line() + ": " + p.message().substring(0, p.message().indexOf(" at the start"))).toList();
        assertEquals(List.of(
                "8: 'robots[0]': robot 'in-circle' starts inside the circle at (3, 2) (obstacles[0], line 5) by 5.0 cm",
                "9: 'robots[1]': robot 'in-polygon' starts inside the polygon (obstacles[1], line 6) by 15.0 cm",
                "10: 'robots[2]': robot 'in-wall' starts inside the arena's left wall (x < 0) (arena, line 2) by 5.0 cm"), where);
    }

    @Test
    void shouldAcceptRobotsThatTouchOrThatARotationKeepsClear() throws IOException {
        // Side by side, touching; end to end, a millimetre apart; turned a quarter, 0.10 m wide
        // along x, just clear of a box that the robot unturned would reach into.
        Path file = world("dyn4j", "- { box: { x: 2.2, y: 1, width: 0.2, height: 0.2 } }", """
                - { robot: bot.yaml, name: a, x: 1.0, y: 1.0 }
                - { robot: bot.yaml, name: b, x: 1.0, y: 1.1 }
                - { robot: bot.yaml, name: c, x: 1.201, y: 1.0 }
                - { robot: bot.yaml, name: d, x: 2.05, y: 1.0, heading: 1.5707963 }
                - { robot: bot.yaml, name: e, x: 0.1, y: 0.05 }
                """);

        assertEquals(5, new WorldLoader().load(file).robots().size());
    }

    @Test
    void shouldCheckTenThousandRobotsWithoutComparingEveryPair() {
        Placements placements = new Placements();
        org.yaml.snakeyaml.error.Mark mark = new org.yaml.snakeyaml.error.Mark("test", 0, 0, 0, new int[0], 0);
        for (int i = 0; i < 10_000; i++) {
            placements.robot("robot 'r" + i + "'", "robots[" + i + "]", mark, 0.2, 0.1, 0.5 + (i % 100) * 0.5, 0.5 + (i / 100) * 0.5, 0);
        }
        Problems problems = new Problems("swarm.yaml");

        assertTimeoutPreemptively(Duration.ofSeconds(60), () -> placements.check(problems));

        assertTrue(problems.isEmpty());
        assertEquals(0, placements.narrowphaseTests(), "robots 0.3 m apart: the broadphase gives no candidate pair, where all pairs are 50 million");
    }

    @Test
    void shouldReportTheOverlapsOfACrowdAtTheCostOfItsNeighboursOnly() {
        Placements placements = new Placements();
        org.yaml.snakeyaml.error.Mark mark = new org.yaml.snakeyaml.error.Mark("test", 0, 0, 0, new int[0], 0);
        for (int i = 0; i < 10_000; i++) {
            // rows 0.15 m apart along x: each robot (0.20 long) overlaps its neighbours in the row by 5 cm
            placements.robot("robot 'r" + i + "'", "robots[" + i + "]", mark, 0.2, 0.1, 0.5 + (i % 100) * 0.15, 0.5 + (i / 100) * 0.5, 0);
        }
        Problems problems = new Problems("swarm.yaml");

        placements.check(problems);

        assertEquals(100 * 99, problems.count(), "each robot but the first of a row overlaps the one before");
        assertEquals(100 * 99, placements.narrowphaseTests(), "only neighbours were tested");
    }

    @Test
    void shouldLoadEveryExampleWorld() throws IOException {
        try (var files = Files.list(Path.of("../examples/worlds"))) {
            for (Path f : files.filter(f -> f.toString().endsWith(".yaml")).toList()) {
                assertTrue(new WorldLoader().load(f).robots().size() > 0, f.toString());
            }
        }
    }
}
