package {{package}};

import io.robomw.api.Pose;
import io.robomw.sim.Simulation;
import org.junit.jupiter.api.Test;

import java.nio.file.Path;

import static org.junit.jupiter.api.Assertions.assertEquals;

/** The program on a simulated robot: the same code drives a brick or a robot served elsewhere. */
class {{Class}}Test {

    @Test
    void drivesASquareBackToWhereItStarted() {
        try (Simulation sim = Simulation.load(Path.of("src/test/resources/test-world.yaml"))) {
            sim.startRealTime(8);
            Pose end = {{Class}}.driveSquare(sim.robot("bot"));
            assertEquals(0, end.x(), 0.05, "odometry closes the square: " + end);
            assertEquals(0, end.y(), 0.05, "odometry closes the square: " + end);
        }
    }
}
