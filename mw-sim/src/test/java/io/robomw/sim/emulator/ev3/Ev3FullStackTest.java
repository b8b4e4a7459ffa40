package io.robomw.sim.emulator.ev3;

import io.robomw.api.Pose;
import io.robomw.api.ReturnType;
import io.robomw.api.Robot;
import io.robomw.api.Robots;
import io.robomw.sim.Simulation;
import io.robomw.sim.emulator.EmulatorStack;
import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.BeforeEach;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.Set;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * The real EV3 driver ({@code platform: ev3}, found by {@link java.util.ServiceLoader} through
 * {@link Robots#open}) byte for byte over a real pseudo-terminal through jSerialComm (or over TCP),
 * against the EV3 emulator, whose motors and sensors are a robot in a simulated world running at
 * four times real time: what only the EV3 does (its coasting outputs, its gyro, the example robot
 * file). What every brick does is {@link io.robomw.sim.emulator.EmulatorContractTest}. Checks are
 * on the simulated robot's true pose. Waits are on conditions checked at every world step, each
 * with a deadline; nothing sleeps.
 */
public class Ev3FullStackTest {

    public static final String ROBOT = """
            name: ev3-1
            platform: ev3
            connection: { %s }
            drive:
              wheel_diameter: 0.056
              track_width: 0.112
              max_speed: 0.30
              left:  { port: B }
              right: { port: C }
            body: { length: 0.20, width: 0.15, mass: 0.6, friction: 0.8 }
            sensors:
              - { name: bumper, type: touch, position: front, port: S1 }
              - { name: gyro, type: gyro, position: center, port: S2, conversion: { scale: -0.0174533 } }
              - { name: sonar, type: sonar, position: front, port: S4, conversion: { scale: 0.01 } }
            """;

    private static final double SPEED = 4.0;

    @TempDir
    Path dir;

    private EmulatorStack<Ev3Emulator> stack;
    private Robot robot;

    @BeforeEach
    void stack() {
        stack = new EmulatorStack<>(dir, ROBOT, "ev3-1", Ev3Emulator::bind);
    }

    @AfterEach
    void close() {
        stack.close();
    }

    /** A world with the robot at (x, 1.5) facing the wall at x = 3, the emulator on a pty, the driver on it. */
    private void startOnPty(double x) throws IOException {
        robot = stack.openOnPseudoTerminal(x, SPEED);
    }

    private Pose truePose() {
        return stack.truePose();
    }

    /** Closing the robot leaves its outputs coasting, not braked (a braked EV3 motor draws current until the brick is off). */
    @Test
    void shouldLeaveEveryOutputCoastingWhenTheRobotCloses() throws Exception {
        startOnPty(1.0);
        robot.move(0.1, 0.15);
        assertTrue(stack.emulator().braking("B"), "a finished move brakes");
        robot.close();

        for (String port : new String[]{"B", "C"}) {
            assertTrue(!stack.emulator().braking(port), "output " + port + " coasts after close");
        }
    }

    @Test
    void shouldReadAQuarterTurnOnTheGyro() throws Exception {
        startOnPty(1.5);
        robot.turn(Math.PI / 2, 1.0);
        assertEquals(90, Math.toDegrees(truePose().heading()), 2.0);
        assertEquals(90, robot.getValue("gyro", ReturnType.DEGREES), 2.0);
    }

    @Test
    void shouldDriveTheExampleRobotFileThroughTheEmulator() throws Exception {
        Path example = Path.of("..", "examples", "robots", "ev3-two-wheeled.yaml").toAbsolutePath().normalize();
        // a world may name robot files in its own tree only (issue 37): the example's robot file goes beside it
        Files.copy(example, dir.resolve("ev3-two-wheeled.yaml"), java.nio.file.StandardCopyOption.REPLACE_EXISTING);
        Files.writeString(dir.resolve("world.yaml"), """
                name: ev3-example
                arena: { width: 3, height: 3 }
                robots:
                  - { robot: "%s", name: ev3-1, x: 1.0, y: 1.5, heading: 0 }
                """.formatted("ev3-two-wheeled.yaml"));
        String text = Files.readString(example);
        assertTrue(text.contains("port: /dev/rfcomm0"), "the example names the Bluetooth serial port");
        try (Simulation sim = Simulation.load(dir.resolve("world.yaml"), Set.of("ev3-1")); Ev3Emulator emulator = Ev3Emulator.bind(sim, "ev3-1")) {
            String pty = emulator.startOnPseudoTerminal();
            sim.startRealTime(SPEED);
            Files.writeString(dir.resolve("driver.yaml"), text.replace("port: /dev/rfcomm0", "port: " + pty));
            try (Robot ev3 = Robots.open(dir.resolve("driver.yaml"))) {
                ev3.move(0.3, 0.2);
                assertEquals(1.3, sim.world().robot("ev3-1").pose().x(), 0.01);
                assertEquals(0.0, ev3.getValue("bumper", ReturnType.BOOLEAN));
                assertEquals(3.0 - (1.3 + 0.10), ev3.getValue("sonar", ReturnType.METERS), 0.02);
                assertEquals(0.0, ev3.getValue("gyro", ReturnType.DEGREES), 1.0);
            }
        }
    }
}
