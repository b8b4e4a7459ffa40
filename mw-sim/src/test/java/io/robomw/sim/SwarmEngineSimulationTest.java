package io.robomw.sim;

import io.robomw.api.Pose;
import io.robomw.api.Position;
import io.robomw.api.ReturnType;
import io.robomw.api.Robot;
import io.robomw.api.SensorType;
import io.robomw.config.description.DescriptionException;
import io.robomw.sim.world.WorldDescription.PhysicsEngine;
import io.robomw.sim.world.WorldLoader;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.concurrent.CompletableFuture;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * The swarm physics engine ({@code physics: { engine: swarm }}) under robots driven through all three
 * layers: the same programs end where the dyn4j engine's do, by the encoders' odometry and by the
 * true pose; the bumper presses at a wall; the world file's key is read and wrong values are named
 * with their line; worlds the engine cannot simulate are refused.
 */
class SwarmEngineSimulationTest {

    private static final Duration LIMIT = Duration.ofSeconds(120);

    @TempDir
    Path dir;

    private Path worldFile(double x, double y, double heading, String physics) throws IOException {
        Files.writeString(dir.resolve("scout.yaml"), SimulationTest.ROBOT.formatted(0));
        Path file = dir.resolve("world.yaml");
        Files.writeString(file, """
                name: test
                arena: { width: 4, height: 3 }
                seed: 7
                physics_hz: 50
                %s
                robots:
                  - { robot: scout.yaml, name: r1, x: %s, y: %s, heading: %s }
                """.formatted(physics, x, y, heading));
        return file;
    }

    private Simulation world(double x, double y, double heading, PhysicsEngine engine) throws IOException {
        return Simulation.load(worldFile(x, y, heading, "physics: { engine: " + engine.name().toLowerCase(java.util.Locale.ROOT) + " }"));
    }

    /** A metre, a quarter turn, half a metre, a half turn: the true pose and the robot's own odometry at the end. */
    private Pose[] driveAndTurn(PhysicsEngine engine) throws IOException {
        try (Simulation sim = world(1, 1, 0, engine)) {
            Robot r = sim.robot("r1");
            sim.run(LIMIT, () -> {
                r.move(1.0, 0.2);
                r.turn(Math.PI / 2, 1.0);
                r.move(0.5, 0.25);
                r.turn(Math.PI, 1.5);
            });
            return new Pose[] {sim.world().robot("r1").pose(), r.pose()};
        }
    }

    @Test
    void shouldDriveAKnownDistanceAndTurnAsTheDyn4jEngineDoes() throws Exception {
        Pose[] swarm = driveAndTurn(PhysicsEngine.SWARM);
        Pose[] dyn4j = driveAndTurn(PhysicsEngine.DYN4J);
        assertEquals(2.0, swarm[0].x(), 0.01, "true x: 1 m from x = 1");
        assertEquals(1.5, swarm[0].y(), 0.01, "true y: then 0.5 m up");
        assertEquals(-Math.PI / 2, swarm[0].heading(), Math.toRadians(2), "facing down after 90° and 180° (a step at 50 Hz turns 1.7°)");
        assertTrue(swarm[0].distanceTo(dyn4j[0]) < 0.005, "true poses within 5 mm: " + swarm[0] + " and " + dyn4j[0]);
        assertEquals(dyn4j[0].heading(), swarm[0].heading(), Math.toRadians(0.5), "true headings within half a degree");
        assertTrue(swarm[1].distanceTo(dyn4j[1]) < 0.005, "odometry from the encoders within 5 mm: " + swarm[1] + " and " + dyn4j[1]);
        assertEquals(dyn4j[1].heading(), swarm[1].heading(), Math.toRadians(0.5), "odometry headings within half a degree");
    }

    @Test
    void shouldPressTheBumperAndStopAtTheWall() throws Exception {
        try (Simulation sim = world(3.5, 1.5, 0, PhysicsEngine.SWARM)) {
            Robot r = sim.robot("r1");
            double[] pressed = new double[2];
            sim.run(LIMIT, () -> {
                pressed[0] = r.getValue(Position.FRONT, SensorType.TOUCH, ReturnType.BOOLEAN);
                CompletableFuture<Void> drive = r.moveAsync(1.0, 0.2);
                while (r.getValue(Position.FRONT, SensorType.TOUCH, ReturnType.BOOLEAN) == 0.0) {
                    assertFalse(drive.isDone(), "the 1 m move cannot finish: the wall is 0.4 m away");
                }
                pressed[1] = 1.0;
                r.stop();
            });
            assertEquals(0.0, pressed[0], "not pressed in the open");
            assertEquals(1.0, pressed[1], "pressed at the wall");
            double front = sim.world().robot("r1").pose().x() + 0.10;
            assertTrue(front <= 4.0 + 0.005 && front >= 3.98, "the front at the wall, not through it: " + front);
            sim.runFor(Duration.ofSeconds(1));
            assertEquals(front, sim.world().robot("r1").pose().x() + 0.10, 0.002, "stopped");
        }
    }

    @Test
    void shouldReadThePhysicsKeyAndNameAWrongEngineWithItsLine() throws Exception {
        assertEquals(PhysicsEngine.SWARM, new WorldLoader().load(worldFile(1, 1, 0, "physics: { engine: swarm }")).engine());
        assertEquals(PhysicsEngine.DYN4J, new WorldLoader().load(worldFile(1, 1, 0, "physics: { engine: dyn4j }")).engine());
        assertEquals(PhysicsEngine.DYN4J, new WorldLoader().load(worldFile(1, 1, 0, "")).engine(), "the default");
        DescriptionException e = assertThrows(DescriptionException.class,
                () -> new WorldLoader().load(worldFile(1, 1, 0, "physics: { engine: bullet, gravity: 9.81 }")));
        assertEquals(2, e.problems().size(), e::getMessage);
        String all = e.getMessage();
        assertTrue(all.contains("physics.engine") && all.contains("bullet") && all.contains("dyn4j") && all.contains("swarm"), all);
        assertTrue(all.contains("gravity"), all);
        assertTrue(all.contains("world.yaml"), "names the file: " + all);
        assertTrue(e.problems().stream().allMatch(p -> p.line() == 5), all);
        DescriptionException notMapping = assertThrows(DescriptionException.class,
                () -> new WorldLoader().load(worldFile(1, 1, 0, "physics: swarm")));
        assertTrue(notMapping.getMessage().contains("physics"), notMapping.getMessage());
    }

    @Test
    void shouldRefuseARobotFastEnoughToPassThroughAWallInOneStep() throws Exception {
        Path file = worldFile(1, 1, 0, "physics: { engine: swarm }");
        Files.writeString(file, Files.readString(file).replace("physics_hz: 50", "physics_hz: 2"));
        RuntimeException e = assertThrows(RuntimeException.class, () -> Simulation.load(file).close());
        assertTrue(e.getMessage().contains("world.yaml") && e.getMessage().contains("'r1'") && e.getMessage().contains("physics_hz"),
                e.getMessage());
        // the same world on dyn4j loads
        Files.writeString(file, Files.readString(file).replace("engine: swarm", "engine: dyn4j"));
        Simulation.load(file).close();
    }

    @Test
    void shouldRefuseTheDyn4jRayCastsOnTheSwarmEngine() throws Exception {
        var description = new WorldLoader().load(worldFile(1, 1, 0, "physics: { engine: swarm }"));
        IllegalArgumentException e = assertThrows(IllegalArgumentException.class,
                () -> Simulation.create(description, 1, SimWorld.RangeMethod.DYN4J_RAYCAST).close());
        assertTrue(e.getMessage().contains("dyn4j"), e.getMessage());
    }
}
