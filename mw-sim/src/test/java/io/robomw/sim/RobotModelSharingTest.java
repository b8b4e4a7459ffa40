package io.robomw.sim;

import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertNotEquals;
import static org.junit.jupiter.api.Assertions.assertSame;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * The robots of one robot file share its sensor models (one set for a swarm of 100,000), yet each
 * reads what is in front of it, and a noisy sensor's noise is each robot's own.
 */
class RobotModelSharingTest {

    @TempDir
    Path dir;

    @Test
    void shouldShareOneRobotFilesSensorModelsWhileEachRobotReadsItsOwnSurroundingsAndNoise() throws IOException {
        Files.writeString(dir.resolve("bot.yaml"), """
                name: bot
                platform: sim
                drive: { wheel_diameter: 0.056, track_width: 0.112, max_speed: 0.3, left: { port: B }, right: { port: C } }
                body: { length: 0.12, width: 0.12, mass: 0.3 }
                sensors:
                  - { name: ahead, type: infrared, position: front, port: S1, options: { max_range: 0.5 } }
                  - { name: noisy, type: infrared, position: front, port: S2, options: { max_range: 0.5, noise: 0.01 } }
                """);
        Files.writeString(dir.resolve("world.yaml"), """
                name: sharing
                arena: { width: 4, height: 2 }
                seed: 3
                robots:
                  - { robot: bot.yaml, name: near, x: 3.6, y: 0.5, heading: 0 }
                  - { robot: bot.yaml, name: far, x: 1.0, y: 0.5, heading: 0 }
                  - { robot: bot.yaml, name: twin, x: 3.6, y: 1.5, heading: 0 }
                """);
        try (Simulation sim = Simulation.load(dir.resolve("world.yaml"))) {
            sim.runFor(Duration.ofMillis(300));
            SimRobot near = sim.world().robot("near");
            SimRobot far = sim.world().robot("far");
            SimRobot twin = sim.world().robot("twin");
            assertSame(near.sensors(), far.sensors(), "one model set for the robots of one file");
            assertSame(near.rangeSensors(), twin.rangeSensors());
            SensorModel ahead = near.sensors().get("ahead");
            SensorModel noisy = near.sensors().get("noisy");
            // the wall at x = 4 is 0.4 m from the centre, 0.34 m from the front edge where the sensor sits
            assertEquals(0.34, near.latest(ahead), 0.01, "near the wall");
            assertEquals(0.5, far.latest(ahead), 1e-9, "nothing within range: its longest range");
            assertEquals(near.latest(ahead), twin.latest(ahead), 1e-12, "the same place against the same wall reads the same");
            // the same true distance, but each robot draws its noise from a generator of its own
            assertTrue(Math.abs(near.latest(noisy) - 0.34) < 0.06, "noisy reading near 0.34 m: " + near.latest(noisy));
            assertNotEquals(near.latest(noisy), twin.latest(noisy), "each robot's noise is its own");
        }
    }
}
