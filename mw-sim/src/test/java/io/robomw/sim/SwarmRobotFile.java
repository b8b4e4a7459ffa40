package io.robomw.sim;

import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.Locale;
import java.util.function.IntFunction;

/** The swarm tests' robot file: a 12 cm two-wheeled robot with 8 infra-red range sensors around it. */
final class SwarmRobotFile {

    private SwarmRobotFile() {
    }

    /**
     * @param robot  where to write it
     * @param rateHz each sensor's reading rate (by its number, 0-7), as the file writes it
     */
    static void write(Path robot, IntFunction<String> rateHz) throws IOException {
        StringBuilder sensors = new StringBuilder();
        for (int i = 0; i < 8; i++) {
            sensors.append(String.format(Locale.ROOT,
                    "  - { name: ir%d, type: infrared, position: center, port: S%d, options: { angle: %.6f, x: %.4f, y: %.4f, max_range: 0.5, "
                            + "noise: 0.01, rate_hz: %s } }%n",
                    i, i, i * Math.PI / 4, 0.06 * Math.cos(i * Math.PI / 4), 0.06 * Math.sin(i * Math.PI / 4), rateHz.apply(i)));
        }
        Files.writeString(robot, """
                name: bot
                platform: sim
                cycle_hz: 10
                drive: { wheel_diameter: 0.056, track_width: 0.112, max_speed: 0.3, left: { port: B }, right: { port: C } }
                body: { length: 0.12, width: 0.12, mass: 0.3 }
                sensors:
                """ + sensors);
    }
}
