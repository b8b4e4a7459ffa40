package io.robomw.sim.render;

import io.robomw.sim.Simulation;

import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;

/** A small world for picture tests: a 4 × 3 m walled arena, one box, one dark patch and one robot. */
final class TestWorld {

    static final String ROBOT = """
            name: scout
            platform: sim
            drive:
              wheel_diameter: 0.056
              track_width: 0.112
              max_speed: 0.30
              left:  { port: B }
              right: { port: C }
            body: { length: 0.20, width: 0.15, mass: 0.6, friction: 0.8 }
            sensors:
              - { name: sonar, type: sonar, position: front, port: S4 }
            """;

    private TestWorld() {
    }

    /**
     * @param dir     a folder for the files
     * @param x       the robot's start x
     * @param y       the robot's start y
     * @param heading the robot's start heading
     * @return the simulation
     * @throws IOException if the files cannot be written
     */
    static Simulation open(Path dir, double x, double y, double heading) throws IOException {
        Files.writeString(dir.resolve("scout.yaml"), ROBOT);
        Files.writeString(dir.resolve("world.yaml"), """
                name: picture
                arena: { width: 4, height: 3, wall_thickness: 0.1, floor: 0.8 }
                seed: 3
                physics_hz: 100
                obstacles:
                  - box: { x: 3.0, y: 2.5, width: 0.4, height: 0.4 }
                floor:
                  - { x: 0.2, y: 2.2, width: 0.6, height: 0.6, brightness: 0.05 }
                robots:
                  - { robot: scout.yaml, name: r1, x: %s, y: %s, heading: %s }
                """.formatted(x, y, heading));
        return Simulation.load(dir.resolve("world.yaml"));
    }
}
