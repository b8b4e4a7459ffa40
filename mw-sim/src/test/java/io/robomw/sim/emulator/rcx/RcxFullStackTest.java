package io.robomw.sim.emulator.rcx;

import io.robomw.api.Pose;
import io.robomw.api.Position;
import io.robomw.api.ReturnType;
import io.robomw.api.Robot;
import io.robomw.api.RobotLinkException;
import io.robomw.api.SensorType;
import io.robomw.sim.emulator.EmulatorStack;
import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

import java.nio.file.Path;
import java.time.Duration;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.ExecutionException;
import java.util.concurrent.TimeUnit;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertInstanceOf;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * The real RCX driver ({@code platform: rcx}), byte for byte over a real pseudo-terminal through
 * jSerialComm, against the RCX emulator behind its echoing IR tower at 2400 baud, whose motors and
 * sensors are a robot in a simulated world running in real time (the link's timing is the
 * robot's). Checks are on the simulated robot's true pose.
 *
 * <p>The robot counts each wheel with a rotation sensor geared 1:1 to its motor: 16 counts a
 * turn, 22.5° of motor, 11.0 mm of travel on 56 mm wheels; every packet takes about 0.12 s, so
 * each wheel is read about four times a second. That is the resolution of every distance below.
 */
public class RcxFullStackTest {

    public static final String ROBOT = """
            name: rcx-1
            platform: rcx
            connection: { %s }
            drive:
              wheel_diameter: 0.056
              track_width: 0.112
              max_speed: 0.20
              encoder_ticks_per_revolution: 16
              left:  { port: A, counter: S1 }
              right: { port: C, counter: S3 }
            body: { length: 0.20, width: 0.15, mass: 0.6, friction: 0.8 }
            sensors:
              - { name: bumper, type: touch, position: front, port: S2 }
            """;

    static final String LIGHT_ROBOT = """
            name: rcx-1
            platform: rcx
            connection: { %s }
            drive:
              wheel_diameter: 0.056
              track_width: 0.112
              max_speed: 0.20
              left:  { port: A }
              right: { port: C }
            body: { length: 0.20, width: 0.15, mass: 0.6, friction: 0.8 }
            sensors:
              - { name: floor, type: light, position: bottom, port: S2, conversion: { scale: 0.01 } }
            """;

    @TempDir
    Path dir;

    private EmulatorStack<RcxEmulator> stack;
    private Robot robot;

    @AfterEach
    void close() {
        if (stack != null) {
            stack.close();
        }
    }

    private void start(String template, double x) throws Exception {
        stack = new EmulatorStack<>(dir, template, "rcx-1", RcxEmulator::bind);
        robot = stack.openOnPseudoTerminal(x, 1);
    }

    private Pose truePose() {
        return stack.truePose();
    }

    @Test
    void shouldMoveHalfAMetreWithinTwoCentimetresByItsRotationSensors() throws Exception {
        start(ROBOT, 0.5);
        robot.move(0.5, 0.10);
        assertEquals(1.0, truePose().x(), 0.02);
        assertEquals(1.5, truePose().y(), 0.02);
    }

    @Test
    void shouldTurnQuarterWithinSixDegrees() throws Exception {
        start(ROBOT, 1.5);
        robot.turn(Math.PI / 2, 0.5);
        assertEquals(90, Math.toDegrees(truePose().heading()), 6.0);
    }

    @Test
    void shouldReadBumperPressedAgainstWall() throws Exception {
        start(ROBOT, 2.6);
        assertEquals(0.0, robot.getValue(Position.FRONT, SensorType.TOUCH, ReturnType.BOOLEAN));
        CompletableFuture<Void> move = robot.moveAsync(0.5, 0.1);
        io.robomw.sim.SimMotors body = io.robomw.sim.SimMotors.of(stack.sim().world(), "rcx-1").orElseThrow();
        stack.awaitStep(() -> body.siValue("bumper") >= 0.5, Duration.ofSeconds(20), "the robot's bumper touched the wall");
        assertEquals(1.0, robot.getValue(Position.FRONT, SensorType.TOUCH, ReturnType.BOOLEAN));
        robot.stop();
        Exception ended = assertThrows(Exception.class, () -> move.get(5, TimeUnit.SECONDS));
        assertFalse(ended instanceof java.util.concurrent.TimeoutException, "the blocked move ended by the stop, not by the 5 s wait: " + ended);
    }

    @Test
    void shouldReadLightFromFloorInPercent() throws Exception {
        start(LIGHT_ROBOT, 1.0);
        assertEquals(80.0, robot.getValue(Position.BOTTOM, SensorType.LIGHT, ReturnType.PERCENT), 1.0,
                "the arena floor's brightness 0.8, as the firmware's percent mode scales it");
    }

    @Test
    void shouldReportLostLinkWhenEmulatorDiesMidMove() throws Exception {
        start(ROBOT, 0.5);
        CompletableFuture<Void> move = robot.moveAsync(1.0, 0.1);
        double before = truePose().x();
        stack.awaitStep(() -> truePose().x() > before + 0.05, Duration.ofSeconds(10), "the robot started moving");
        stack.emulator().close();
        ExecutionException e = assertThrows(ExecutionException.class, () -> move.get(2, TimeUnit.SECONDS));
        assertInstanceOf(RobotLinkException.class, e.getCause());
        double stoppedAt = truePose().x();
        stack.awaitHalfASimulatedSecond();
        assertEquals(stoppedAt, truePose().x(), 0.01, "the robot stopped with its brick");
    }

    @Test
    void shouldLeaveItsMotorsFloatingWhenTheRobotCloses() throws Exception {
        start(ROBOT, 0.5);
        robot.move(0.05, 0.10);
        stack.awaitStep(() -> !stack.emulator().floating("A"), Duration.ofSeconds(5), "a finished move brakes");
        robot.close();
        assertTrue(stack.emulator().floating("A") && stack.emulator().floating("C"), "closed: every output floats");
    }
}
