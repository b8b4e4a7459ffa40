package io.robomw.sim.platform;

import io.robomw.api.Pose;
import io.robomw.api.Position;
import io.robomw.api.ReturnType;
import io.robomw.api.Robot;
import io.robomw.api.SensorType;
import io.robomw.api.spi.Cycling;
import io.robomw.api.spi.MotorCommand;
import io.robomw.api.spi.MotorTarget;
import io.robomw.api.spi.PlatformServices;
import io.robomw.api.spi.RobotPlatform;
import io.robomw.config.robot.DescriptionRobotFactory;
import io.robomw.sim.SimWorld;
import io.robomw.sim.Simulation;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.List;
import java.util.Set;
import java.util.concurrent.CompletableFuture;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * The verbs' contracts on the simulator's platform (its link serviced inline, on the simulation's
 * cycling thread): {@code stop()} returns once the stop was applied, so the next command is
 * admitted; cancelling a command's future brakes its motors at the next cycle.
 */
class SimPlatformVerbsTest {

    private static final Duration LIMIT = Duration.ofSeconds(120);

    @TempDir
    Path dir;

    private Simulation world() throws IOException {
        return world(Set.of());
    }

    /** The world, leaving the robots named {@code platformsOfTheirOwn} for the test to open a platform for. */
    private Simulation world(Set<String> platformsOfTheirOwn) throws IOException {
        Files.writeString(dir.resolve("scout.yaml"), """
                name: scout
                platform: nxt
                connection: { port: /dev/rfcomm0 }
                drive:
                  wheel_diameter: 0.056
                  track_width: 0.112
                  max_speed: 0.30
                  left:  { port: B }
                  right: { port: C }
                body: { length: 0.20, width: 0.15, mass: 0.6, friction: 0.8 }
                sensors:
                  - { name: sonar, type: sonar, position: front, port: S4, conversion: { scale: 0.01 } }
                """);
        Files.writeString(dir.resolve("world.yaml"), """
                name: verbs
                arena: { width: 4, height: 3 }
                seed: 7
                physics_hz: 100
                robots:
                  - { robot: scout.yaml, name: r1, x: 0.5, y: 1.5, heading: 0 }
                """);
        return Simulation.load(dir.resolve("world.yaml"), platformsOfTheirOwn);
    }

    private static Pose truePose(Simulation sim) {
        return sim.world().robot("r1").pose();
    }

    @Test
    void aMoveAfterStopIsAdmittedAndRuns() throws Exception {
        try (Simulation sim = world()) {
            Robot r = sim.robot("r1");
            double[] stoppedAt = new double[1];
            sim.run(LIMIT, () -> {
                r.moveAsync(1.0, 0.2);
                for (int i = 0; i < 20; i++) {
                    r.getValue(Position.FRONT, SensorType.SONAR, ReturnType.CENTIMETERS); // a cycle or so each
                }
                r.stop();
                stoppedAt[0] = truePose(sim).x();
                r.move(0.10, 0.1); // refused as "held by 'stop'" if the stop still held the wheels
            });
            assertTrue(stoppedAt[0] > 0.5, "the robot had moved before the stop: " + stoppedAt[0]);
            assertEquals(stoppedAt[0] + 0.10, truePose(sim).x(), 0.01, "the move after the stop ran its 10 cm");
        }
    }

    @Test
    void aCancelledCommandBrakesItsMotorsAtTheNextCycle() throws Exception {
        try (Simulation sim = world(Set.of("r1"))) {
            SimWorld world = sim.world();
            RobotPlatform platform = new SimPlatformProvider().open(DescriptionRobotFactory.platformConfig(world.robot("r1").description(),
                    PlatformServices.none().with(SimWorld.class, world), world.clock(), Cycling.BY_OWNER));
            try {
                CompletableFuture<Void> move = platform.run(MotorCommand.of("move", List.of(
                        MotorTarget.rotate("B", 3600, 400), MotorTarget.rotate("C", 3600, 400))));
                sim.runFor(Duration.ofMillis(500));
                double moving = truePose(sim).x();
                assertTrue(moving > 0.55, "the move was under way: " + moving);

                move.cancel(true);
                sim.runFor(Duration.ofMillis(200));
                double braked = truePose(sim).x();
                sim.runFor(Duration.ofSeconds(2));
                assertEquals(braked, truePose(sim).x(), 0.002, "the cancelled command's motors were braked; it does not drive on");
                assertTrue(braked < moving + 0.05, "it stopped within a few cycles of the cancel: " + moving + " -> " + braked);
            } finally {
                platform.close();
            }
        }
    }

    @Test
    void stopAllCompletesWithinTheCycleThatAppliedIt() throws Exception {
        try (Simulation sim = world(Set.of("r1"))) {
            SimWorld world = sim.world();
            RobotPlatform platform = new SimPlatformProvider().open(DescriptionRobotFactory.platformConfig(world.robot("r1").description(),
                    PlatformServices.none().with(SimWorld.class, world), world.clock(), Cycling.BY_OWNER));
            try {
                platform.run(MotorCommand.of("move", List.of(MotorTarget.rotate("B", 3600, 400), MotorTarget.rotate("C", 3600, 400))));
                sim.runFor(Duration.ofMillis(200));
                CompletableFuture<Void> stop = platform.stopAll();
                assertFalse(stop.isDone(), "not before a cycle applied it");
                sim.runFor(Duration.ofMillis(10));
                assertTrue(stop.isDone() && !stop.isCompletedExceptionally(), "handed to the simulated motors in the cycle that applied it");
                double at = truePose(sim).x();
                sim.runFor(Duration.ofSeconds(1));
                assertEquals(at, truePose(sim).x(), 0.005, "stopped");
            } finally {
                platform.close();
            }
        }
    }
}
