package io.robomw.sim.world;

import io.robomw.api.Pose;
import io.robomw.api.Robot;
import io.robomw.config.description.DescriptionException;
import io.robomw.config.description.DescriptionException.Problem;
import io.robomw.sim.Simulation;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.List;
import java.util.Set;
import java.util.stream.Collectors;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertNotEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTimeoutPreemptively;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * A world file's swarm entry ({@code swarms:}) places many robots from one robot file: as many as
 * it says, named after it, in its area, clear of each other and of everything placed before, the
 * same for the same seed; an area too small for the count is refused at the entry's line.
 */
class SwarmEntriesTest {

    /** A robot 0.20 m long and 0.10 m wide (its bounding circle 0.224 m across). */
    private static final String ROBOT = """
            name: bot
            platform: sim
            drive: { wheel_diameter: 0.05, track_width: 0.1, max_speed: 0.2, left: { port: A }, right: { port: B } }
            body: { length: 0.20, width: 0.10 }
            """;

    @TempDir
    Path dir;

    private Path world(String rest) throws IOException {
        Files.writeString(dir.resolve("bot.yaml"), ROBOT);
        Path file = dir.resolve("world.yaml");
        Files.writeString(file, """
                name: swarming
                arena: { width: 20, height: 10 }
                seed: 3
                """ + rest);
        return file;
    }

    @Test
    void shouldPlaceAsManyRobotsAsTheEntrySaysNamedAfterItInsideItsArea() throws IOException {
        Path file = world("""
                robots:
                  - { robot: bot.yaml, name: lone, x: 19, y: 9 }
                swarms:
                  - { robot: bot.yaml, count: 500, name: ant, area: { x: 1, y: 2, width: 8, height: 6 } }
                """);

        WorldDescription w = new WorldLoader().load(file);

        assertEquals(501, w.robots().size());
        assertEquals("lone", w.robots().get(0).name(), "the robots placed one by one come first");
        List<WorldDescription.RobotPlacement> ants = w.robots().subList(1, 501);
        for (int k = 0; k < 500; k++) {
            WorldDescription.RobotPlacement r = ants.get(k);
            assertEquals("ant-" + (k + 1), r.name());
            assertEquals(dir.resolve("bot.yaml"), r.description());
            Pose p = r.start();
            assertTrue(p.x() >= 1 && p.x() <= 9 && p.y() >= 2 && p.y() <= 8, r.name() + " in the area: " + p);
        }
        assertEquals(List.of(new WorldDescription.Swarm(dir.resolve("bot.yaml"), "ant", 500, 1, 2, 8, 6, w.swarms().get(0).seed(), 1)),
                w.swarms());
        assertEquals(500, ants.stream().map(r -> r.start().heading()).collect(Collectors.toSet()).size(), "headings drawn robot by robot");
    }

    @Test
    void shouldStartEveryRobotClearOfTheOthersTheObstaclesAndTheRobotsPlacedBefore() throws IOException {
        Path file = world("""
                obstacles:
                  - { circle: { x: 5, y: 5, radius: 1.5 } }
                  - { box: { x: 12, y: 5, width: 3, height: 0.5, angle: 0.7 } }
                robots:
                  - { robot: bot.yaml, name: lone, x: 15, y: 2 }
                swarms:
                  - { robot: bot.yaml, count: 1000, name: ant, area: { x: 0, y: 0, width: 10, height: 10 } }
                  - { robot: bot.yaml, count: 800, name: bee, area: { x: 9, y: 0, width: 11, height: 10 } }
                """);

        WorldDescription w = new WorldLoader().load(file);

        assertEquals(1801, w.robots().size());
        List<Pose> all = w.robots().stream().map(WorldDescription.RobotPlacement::start).toList();
        double diagonal = Math.hypot(0.20, 0.10);
        for (int i = 0; i < all.size(); i++) {
            Pose a = all.get(i);
            WorldDescription.RobotPlacement r = w.robots().get(i);
            assertTrue(Math.hypot(a.x() - 5, a.y() - 5) > 1.5 + diagonal / 2, () -> "clear of the disc: " + r);
            // the box in its own frame: 3 m along its x, 0.5 m across
            double bx = (a.x() - 12) * Math.cos(0.7) + (a.y() - 5) * Math.sin(0.7);
            double by = -(a.x() - 12) * Math.sin(0.7) + (a.y() - 5) * Math.cos(0.7);
            assertTrue(Math.hypot(Math.max(0, Math.abs(bx) - 1.5), Math.max(0, Math.abs(by) - 0.25)) > diagonal / 2, () -> "clear of the box: " + r);
            assertTrue(i == 0 || a.distanceTo(new Pose(15, 2, 0)) >= diagonal, () -> "clear of the lone robot: " + r);
            for (int j = i + 1; j < all.size(); j++) {
                int other = j;
                assertTrue(a.distanceTo(all.get(j)) >= diagonal, () -> r + " and " + w.robots().get(other) + " apart");
            }
        }
    }

    @Test
    void shouldPlaceTheSameForTheSameSeedAndOtherwiseForAnother() throws IOException {
        Path seven = world("""
                swarms:
                  - { robot: bot.yaml, count: 2000, seed: 7 }
                """);
        List<WorldDescription.RobotPlacement> first = new WorldLoader().load(seven).robots();
        List<WorldDescription.RobotPlacement> again = new WorldLoader().load(seven).robots();
        Path eight = world("""
                swarms:
                  - { robot: bot.yaml, count: 2000, seed: 8 }
                """);
        List<WorldDescription.RobotPlacement> other = new WorldLoader().load(eight).robots();

        assertEquals(first, again, "the same file, the same places and headings");
        assertEquals("bot-1", first.get(0).name(), "named after the robot file without a name");
        assertNotEquals(first.stream().map(WorldDescription.RobotPlacement::start).toList(),
                other.stream().map(WorldDescription.RobotPlacement::start).toList());
    }

    @Test
    void shouldGiveEveryRobotTheEntrysHeadingWhenItHasOne() throws IOException {
        Path file = world("""
                swarms:
                  - { robot: bot.yaml, count: 50, heading: 1.25 }
                """);

        Set<Double> headings = new WorldLoader().load(file).robots().stream().map(r -> r.start().heading()).collect(Collectors.toSet());

        assertEquals(Set.of(1.25), headings);
    }

    @Test
    void shouldRefuseAnAreaTooSmallForTheCountAtTheEntrysLineSayingHowManyFit() throws IOException {
        // 2 m × 1 m in squares of 0.234 m (the 0.224 m diagonal and 1 cm): 8 × 4 = 32 robots at most
        Path file = world("""
                obstacles:
                  - { circle: { x: 3, y: 3, radius: 0.2 } }
                swarms:
                  - { robot: bot.yaml, count: 10, name: few }
                  - { robot: bot.yaml, count: 40, name: many, area: { x: 5, y: 5, width: 2, height: 1 } }
                """);

        DescriptionException e = assertThrows(DescriptionException.class, () -> new WorldLoader().load(file));

        assertEquals(1, e.problems().size(), e.getMessage());
        Problem p = e.problems().get(0);
        assertEquals(file.toString(), p.file());
        assertEquals(8, p.line(), p.toString());
        assertEquals("'swarms[1]': 40 robots do not fit in the 2 × 1 m area at (5, 5): each robot of bot.yaml (0.2 × 0.1 m) needs a square "
                + "of 0.234 m (its diagonal and 10 mm), and only 32 of them are clear of the obstacles and robots placed before; make the "
                + "area larger or the count smaller", p.message());
        assertThrows(DescriptionException.class, () -> Simulation.load(file).close(), "a simulation refuses it too");
    }

    @Test
    void shouldRefuseAnAreaOutsideTheArenaAMissingCountAndANameTakenAlready() throws IOException {
        Path file = world("""
                robots:
                  - { robot: bot.yaml, name: bot-3, x: 1, y: 1 }
                swarms:
                  - { robot: bot.yaml, count: 10, area: { x: 15, y: 0, width: 10, height: 5 } }
                  - { robot: bot.yaml, name: ant }
                  - { robot: bot.yaml, count: 5 }
                """);

        DescriptionException e = assertThrows(DescriptionException.class, () -> new WorldLoader().load(file));

        List<String> messages = e.problems().stream().map(p -> p.line() + ": " + p.message()).toList();
        assertEquals(List.of(
                "7: 'swarms[0].area': the area (10 × 5 m at (15, 0)) must lie inside the 20 × 10 m arena",
                "8: missing key 'swarms[1].count': expected an integer from 1 to 1000000 (how many robots)"), messages,
                "the name is checked once the values are valid");

    }

    @Test
    void shouldRefuseASwarmsRobotFileOutsideTheWorldFilesTreeWithoutReadingIt() throws IOException {
        // the examples' robot files are outside the temporary directory's tree (its folder, or the one above)
        Path outside = Path.of("..", "examples", "robots", "nxt-two-wheeled.yaml").toAbsolutePath().normalize();
        Path file = world("""
                swarms:
                  - { robot: %s, count: 3, name: far }
                """.formatted(outside));

        DescriptionException e = assertThrows(DescriptionException.class, () -> new WorldLoader().load(file));

        assertEquals(1, e.problems().size(), e.getMessage());
        Problem p = e.problems().get(0);
        assertEquals(5, p.line(), p.toString());
        assertTrue(p.message().startsWith("'swarms[0].robot': refused: " + outside + " is outside "), p.message());
    }

    @Test
    void shouldRefuseASwarmWhoseRobotsNamesAreTakenAlready() throws IOException {
        Path file = world("""
                robots:
                  - { robot: bot.yaml, name: bot-3, x: 1, y: 1 }
                swarms:
                  - { robot: bot.yaml, count: 2, area: { x: 5, y: 0, width: 5, height: 5 } }
                  - { robot: bot.yaml, count: 5, name: ant, area: { x: 10, y: 0, width: 5, height: 5 } }
                  - { robot: bot.yaml, count: 3, name: ant, area: { x: 15, y: 0, width: 5, height: 5 } }
                """);

        DescriptionException e = assertThrows(DescriptionException.class, () -> new WorldLoader().load(file));

        assertEquals(List.of("9: 'swarms[2].name': swarm 'ant' names its robots ant-1 to ant-3, but another robot is named 'ant-1' already; "
                + "give the swarm another name"), e.problems().stream().map(p -> p.line() + ": " + p.message()).toList(),
                "bot-1 and bot-2 are free; ant-1 is the other swarm's");
        Files.writeString(file, Files.readString(file).replace("count: 2, area", "count: 4, area"));
        e = assertThrows(DescriptionException.class, () -> new WorldLoader().load(file));
        assertTrue(e.getMessage().contains("7:5: 'swarms[0].name': swarm 'bot' names its robots bot-1 to bot-4, but another robot is named 'bot-3' "
                + "already"), e.getMessage());
    }

    @Test
    void shouldOpenASwarmsRobotsThroughAllThreeLayers() throws Exception {
        Path file = world("""
                physics_hz: 50
                physics: { engine: swarm }
                swarms:
                  - { robot: bot.yaml, count: 20, name: ant }
                """);

        try (Simulation sim = Simulation.load(file)) {
            assertEquals(20, sim.robots().size());
            Robot ant = sim.robot("ant-7");
            Pose before = sim.world().robot("ant-7").pose();
            sim.run(Duration.ofSeconds(10), () -> ant.move(0.1, 0.1));
            assertEquals(0.1, sim.world().robot("ant-7").pose().distanceTo(before), 0.01, "it drove its 10 cm");
        }
    }

    @Test
    void shouldLoadAHundredThousandRobotsFromOneEntryInSeconds() throws IOException {
        Files.writeString(dir.resolve("bot.yaml"), ROBOT);
        Path file = dir.resolve("big.yaml");
        Files.writeString(file, """
                arena: { width: 320, height: 320 }
                swarms:
                  - { robot: bot.yaml, count: 100000 }
                """);

        WorldDescription w = assertTimeoutPreemptively(Duration.ofSeconds(60), () -> new WorldLoader().load(file));

        assertEquals(100_000, w.robots().size());
        assertEquals("bot-100000", w.robots().get(99_999).name());
    }
}
