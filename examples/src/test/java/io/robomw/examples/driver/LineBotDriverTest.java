package io.robomw.examples.driver;

import io.robomw.api.Position;
import io.robomw.api.ReturnType;
import io.robomw.api.Robot;
import io.robomw.api.RobotException;
import io.robomw.api.Robots;
import io.robomw.api.SensorType;
import io.robomw.api.spi.ConnectionSettings;
import io.robomw.api.spi.Cycling;
import io.robomw.api.spi.FailurePolicy;
import io.robomw.api.spi.MotorChannel;
import io.robomw.api.spi.PlatformConfig;
import io.robomw.api.spi.PlatformServices;
import io.robomw.api.spi.SensorChannel;
import io.robomw.api.Clock;
import io.robomw.platform.link.PseudoTerminal;
import io.robomw.testkit.Await;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.List;
import java.util.Map;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * The example driver end to end, as docs/writing-a-driver.md tests it: a program opens a robot file
 * with {@code platform: linebot} through {@link Robots#open}, which finds the driver through its
 * services file, and drives the emulated board over a real pseudo-terminal.
 */
class LineBotDriverTest {

    private static final double WHEEL_DIAMETER = 0.05;

    private static final String ROBOT = """
            name: tinker
            platform: linebot
            connection: { port: %s }
            drive:
              wheel_diameter: 0.05
              track_width: 0.12
              max_speed: 0.20
              left:  { port: A }
              right: { port: B }
            sensors:
              - { name: ranger, type: sonar, position: front, port: "1", conversion: { scale: 0.01 } }
              - { name: bumper, type: touch, position: back, port: "2" }
            """;

    @TempDir
    Path dir;

    private Path robotFile(PseudoTerminal pty) throws Exception {
        Path file = dir.resolve("tinker.yaml");
        Files.writeString(file, ROBOT.formatted(pty.devicePath()));
        return file;
    }

    @Test
    void aProgramMovesTheBoardsWheelsReadsItsRangerStopsAndClosesThroughRobotsOpen() throws Exception {
        try (PseudoTerminal pty = PseudoTerminal.open(); LineBotEmulator board = LineBotEmulator.serve(pty)) {
            board.input(1, 42);
            board.input(2, 0);
            try (Robot robot = Robots.open(robotFile(pty))) {
                assertEquals(0.42, robot.getValue(Position.FRONT, SensorType.SONAR, ReturnType.METERS), 1e-9, "42 cm, converted by the file");

                robot.move(0.10, 0.05);
                double wheel = 0.10 / (Math.PI * WHEEL_DIAMETER) * 360; // 229.2° per wheel
                // Stopped by its encoder over the link: the driver sees the rotation done at a poll and sends the stop, so a
                // busy machine's late poll lets the wheel turn on a little (24° at load 60-90 on 2 cores: 0.2 s at 115°/s).
                for (String port : List.of("A", "B")) {
                    double turned = board.degrees(port);
                    assertTrue(turned > wheel - 10 && turned < wheel * 1.25, port + " turned the move's rotation, " + wheel + "°: " + turned);
                }

                robot.stop();
                assertTrue(board.requests().containsAll(List.of("STOP A BRAKE", "STOP B BRAKE")), "braked: " + board.requests());
            }
            Await.until("closing left both motors coasting", Duration.ofSeconds(10),
                    () -> board.requests().containsAll(List.of("STOP A COAST", "STOP B COAST")));
            assertEquals(List.of("HELLO", "ZERO"), board.requests().subList(0, 2), "the driver checked the board and zeroed its encoders first");
        }
    }

    @Test
    void aReadTheBoardRefusesFailsNamingTheRobotAndTheBoardsError() throws Exception {
        try (PseudoTerminal pty = PseudoTerminal.open(); LineBotEmulator board = LineBotEmulator.serve(pty)) {
            board.input(1, 42); // no switch on input 2: the board answers ERR 3
            try (Robot robot = Robots.open(robotFile(pty))) {
                RobotException e = assertThrows(RobotException.class, () -> robot.getValue(Position.BACK, SensorType.TOUCH, ReturnType.BOOLEAN));
                assertTrue(e.getMessage().contains("tinker") && e.getMessage().contains("error 3 (bad port)"), e.getMessage());
                assertEquals(0.42, robot.getValue(Position.FRONT, SensorType.SONAR, ReturnType.METERS), 1e-9, "the link goes on");
            }
        }
    }

    @Test
    void checkNamesEveryPortAndSensorTheBoardDoesNotHave() {
        PlatformConfig config = new PlatformConfig("tinker", "linebot", new ConnectionSettings(Map.of(), "tinker.yaml"),
                List.of(MotorChannel.actuator("A"), MotorChannel.actuator("C")),
                List.of(new SensorChannel("ranger", SensorType.SONAR, "3", Map.of()), new SensorChannel("heading", SensorType.GYRO, "2", Map.of())),
                Duration.ofMillis(10), Duration.ZERO, Clock.system(), PlatformServices.none(), Cycling.OWN_THREADS, FailurePolicy.logging());
        List<String> problems = new LineBotPlatformProvider().check(config);
        assertEquals(4, problems.size(), problems.toString());
        assertTrue(problems.get(0).contains("none of port, host"), problems.get(0));
        assertTrue(problems.get(1).contains("motor ports A and B, not 'C'"), problems.get(1));
        assertTrue(problems.get(2).contains("inputs 1 and 2, not '3'"), problems.get(2));
        assertTrue(problems.get(3).contains("gyro"), problems.get(3));
    }
}
