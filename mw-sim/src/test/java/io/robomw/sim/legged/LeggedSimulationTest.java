package io.robomw.sim.legged;

import io.robomw.api.Pose;
import io.robomw.api.Position;
import io.robomw.api.ReturnType;
import io.robomw.api.Robot;
import io.robomw.api.SensorType;
import io.robomw.api.UnsupportedActionException;
import io.robomw.sim.Simulation;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;

import static org.junit.jupiter.api.Assertions.assertAll;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * The example Aibo robot file on {@code platform: sim}: the legged drive's commands act on the
 * simulated quadruped through all three layers, as fast as the simulator goes.
 */
class LeggedSimulationTest {

    private static final Duration LIMIT = Duration.ofSeconds(120);
    static final Path AIBO = Path.of("../examples/robots/aibo.yaml");

    @TempDir
    Path dir;

    private Simulation world(double width, double x, double heading) throws IOException {
        // a world may name robot files in its own tree only (issue 37): the example's robot file goes beside it
        Files.copy(AIBO, dir.resolve("aibo.yaml"), java.nio.file.StandardCopyOption.REPLACE_EXISTING);
        Files.writeString(dir.resolve("world.yaml"), """
                name: dog-test
                arena: { width: %s, height: 3 }
                seed: 11
                robots:
                  - { robot: %s, name: aibo, x: %s, y: 1.5, heading: %s }
                """.formatted(width, "aibo.yaml", x, heading));
        return Simulation.load(dir.resolve("world.yaml"));
    }

    @Test
    void shouldWalkHalfAMetreShortByTheGaitsSlipAndCountItWholeInItsOwnPose() throws IOException {
        try (Simulation sim = world(4, 1.0, 0)) {
            Robot dog = sim.robot("aibo");
            Pose start = sim.world().robot("aibo").pose();

            sim.run(LIMIT, () -> dog.move(0.5, 0.1));

            Pose end = sim.world().robot("aibo").pose();
            double walked = end.x() - start.x();
            // slip 2 %: 0.49 m; jitter 3 % per step over 12.5 steps: σ = 0.03 × 0.5 / √12.5 ≈ 4 mm
            assertEquals(0.49, walked, 0.015, "walked " + walked);
            assertEquals(0.5, dog.pose().x(), 1e-6, "dead reckoning counts the commanded walk");
        }
    }

    @Test
    void shouldPerformItsActionsAndReadItsJoints() throws IOException {
        try (Simulation sim = world(4, 1.0, 0)) {
            Robot dog = sim.robot("aibo");
            double[] pan = new double[1];

            sim.run(LIMIT, () -> {
                dog.perform("head.pan", Math.toRadians(45));
                pan[0] = dog.getValue("head_pan", ReturnType.DEGREES);
                dog.perform("sit");
            });

            assertAll(
                    () -> assertEquals(45, pan[0], 1e-6),
                    () -> assertEquals(Quadruped.Posture.SIT, sim.world().robot("aibo").quadruped().posture()),
                    () -> assertThrows(UnsupportedActionException.class, () -> dog.perform("fly")),
                    () -> assertTrue(dog.actions().contains("tail.wag"), dog.actions()::toString));
        }
    }

    @Test
    void shouldSeeTheWallWithItsHeadAndFeelItWithItsFrontPaws() throws IOException {
        try (Simulation sim = world(2, 1.0, 0)) {
            Robot dog = sim.robot("aibo");
            double[] seen = new double[3];

            sim.run(LIMIT, () -> {
                seen[0] = dog.getValue(Position.FRONT, SensorType.INFRARED, ReturnType.METERS);
                dog.moveAsync(1.5, 0.2);
                // Each read takes a cycle of simulated time: read until a front paw presses, 10 s at most.
                for (int i = 0; i < 1000; i++) {
                    if (dog.getValue("paw_lf", ReturnType.BOOLEAN) > 0) {
                        break;
                    }
                }
                seen[1] = dog.getValue("paw_lf", ReturnType.BOOLEAN) + dog.getValue("paw_rf", ReturnType.BOOLEAN);
                seen[2] = dog.getValue("paw_lh", ReturnType.BOOLEAN);
                dog.stop();
            });

            assertAll(
                    () -> assertEquals(2 - 1.0 - 0.15, seen[0], 0.02, "the far head sensor sees the wall"),
                    () -> assertEquals(2, seen[1], "both front paws touch the wall"),
                    () -> assertEquals(0, seen[2], "a hind paw does not"));
        }
    }

    @Test
    void shouldSeeTheFloorWhenTheHeadLooksDown() throws IOException {
        try (Simulation sim = world(2.5, 1.0, 0)) {
            Robot dog = sim.robot("aibo");
            double[] seen = new double[2];

            sim.run(LIMIT, () -> {
                seen[0] = dog.getValue("head_far", ReturnType.METERS);
                dog.perform("head.tilt", Math.toRadians(-20));
                dog.perform("neck.tilt", Math.toRadians(-20));
                dog.perform("head.pan", 0);
                seen[1] = dog.getValue("head_far", ReturnType.METERS);
            });

            // head 0.22 m above the floor (its option height), looking 40° down: the floor 0.262 m ahead
            assertEquals(2.5 - 1.0 - 0.15, seen[0], 0.02, "level, it sees the wall");
            assertEquals(0.22 / Math.tan(Math.toRadians(40)), seen[1], 0.01, "looking down, it sees the floor");
        }
    }
}
