package io.robomw.sim.emulator.nxt;

import io.robomw.api.Pose;
import io.robomw.api.Position;
import io.robomw.api.ReturnType;
import io.robomw.api.Robot;
import io.robomw.api.RobotException;
import io.robomw.api.SensorType;
import io.robomw.platform.nxt.NxtTelegram;
import io.robomw.sim.emulator.EmulatorStack;
import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.BeforeEach;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;
import org.junit.jupiter.params.ParameterizedTest;
import org.junit.jupiter.params.provider.ValueSource;

import java.io.IOException;
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
 * The real NXT driver, byte for byte over a real pseudo-terminal through jSerialComm (or TCP),
 * against the NXT emulator, whose motors and sensors are a robot in a simulated world running at
 * four times real time: what only the NXT does (its firmware's tacho limits, its polling, its
 * idle outputs, its light sensor, its refusals). What every brick does (moves, turns, the
 * ultrasonic sensor, over I²C here, the bumper, a dying or returning emulator) is
 * {@link io.robomw.sim.emulator.EmulatorContractTest}. Checks are on the simulated robot's true pose.
 */
public class NxtEmulatorTest {

    public static final String ROBOT = """
            name: nxt-1
            platform: nxt
            connection: { %s }
            drive:
              wheel_diameter: 0.056
              track_width: 0.112
              max_speed: 0.30
              left:  { port: B }
              right: { port: C }
            body: { length: 0.20, width: 0.15, mass: 0.6, friction: 0.8 }
            sensors:
              - { name: sonar, type: sonar, position: front, port: S4, conversion: { scale: 0.01 } }
              - { name: bumper, type: touch, position: front, port: S1 }
              - { name: floor, type: light, position: bottom, port: S3, conversion: { scale: 0.000977517 } }
            """;

    @TempDir
    Path dir;

    private EmulatorStack<NxtEmulator> stack;
    private Robot robot;

    @BeforeEach
    void stack() {
        stack = new EmulatorStack<>(dir, ROBOT, "nxt-1", NxtEmulator::bind);
    }

    @AfterEach
    void close() {
        stack.close();
    }

    /** A world with the robot at (x, 1.5) facing the wall at x = 3, the emulator on a pty, the driver on it. */
    private void start(double x) throws IOException {
        robot = stack.openOnPseudoTerminal(x, 4);
    }

    private Pose truePose() {
        return stack.truePose();
    }

    /**
     * A move pre-empted by a turn, then a move again: the firmware adds each tacho limit to the
     * target of the last one, so a driver that only sent limits would see the turn's backward
     * wheel stop at once and its forward wheel run on to the move's old target. Each command must
     * end its own rotation from where the robot is when it arrives.
     */
    @Test
    void shouldEndAMovePreemptedByATurnAndThenAMoveWhereTheyShould() throws Exception {
        start(0.5);
        preemptedMoveTurnMove(0.01, 2.0);
    }

    /**
     * On firmware without UPDATE_RESET_COUNT the platform stops rotations by the encoder, as late as
     * its link and cycle: this world runs in real time, so those delays are what a real robot sees.
     * On a busy host (a CI machine running the suite on two processors) a wheel's stop can come
     * 70-150 ms late, 1-2 cm at 0.15 m/s, so the second move is held to 2.5 cm here (1 cm with
     * UPDATE_RESET_COUNT, where the brick stops itself); a driver that sent only tacho limits would
     * miss by tens of centimetres (the forward wheel running on to the first move's target). Each
     * wheel is stopped by its own encoder, so the two late stops can differ by up to about 1 cm
     * (150 - 70 ms at 0.15 m/s): over the 11.2 cm track, 5° of heading (2° with UPDATE_RESET_COUNT;
     * 2.1° was seen once in CI, 2026-11-25).
     */
    @Test
    void shouldEndAPreemptedMoveTurnAndMoveWhereTheyShouldOnFirmwareWithoutUpdateResetCount() throws Exception {
        stack = new EmulatorStack<>(dir, ROBOT, "nxt-1", NxtEmulator::bindLegacyFirmware);
        robot = stack.openOnPseudoTerminal(0.5, 1);
        preemptedMoveTurnMove(0.025, 5.0);
    }

    /**
     * @param within        how far the second move may end from its line and its 30 cm, metres
     * @param headingWithin how far the heading may end from a quarter turn, after the turn and after the move, degrees
     */
    private void preemptedMoveTurnMove(double within, double headingWithin) throws Exception {
        CompletableFuture<Void> longMove = robot.moveAsync(1.0, 0.15);
        stack.awaitStep(() -> truePose().x() > 0.7, Duration.ofSeconds(20), "the robot drove 20 cm");
        robot.turn(Math.PI / 2, 1.0);
        ExecutionException preempted = assertThrows(ExecutionException.class, () -> longMove.get(5, TimeUnit.SECONDS));
        assertInstanceOf(io.robomw.api.CommandPreemptedException.class, preempted.getCause());
        Pose afterTurn = truePose();
        assertEquals(90, Math.toDegrees(afterTurn.heading()), headingWithin, "the turn turned a quarter from where the move was cut: " + afterTurn);
        assertEquals(1.5, afterTurn.y(), 0.01, "and on the spot");

        robot.move(0.3, 0.15);

        Pose end = truePose();
        assertEquals(afterTurn.x(), end.x(), within, "the second move went straight along the new heading: " + end);
        assertEquals(afterTurn.y() + 0.3, end.y(), within, "and 30 cm: " + end);
        assertEquals(90, Math.toDegrees(end.heading()), headingWithin, "the second move kept the heading: " + end);
    }

    /**
     * Over Bluetooth every telegram costs a round trip, so the driver reads only the motors that
     * matter: the gripper on A, at rest, is read about once a second while the wheels are read
     * every cycle.
     */
    @Test
    void shouldPollTheWheelsThatTurnEveryCycleAndTheGripperAtRestSeldom() throws Exception {
        stack = new EmulatorStack<>(dir, ROBOT.replace("sensors:", "actuators:\n  - { name: gripper, port: A, actions: { open: { degrees: 90, speed: 180 } } }\nsensors:"),
                "nxt-1", NxtEmulator::bind);
        start(0.5);
        long gripperBefore = stack.emulator().telegrams(NxtTelegram.GETOUTPUTSTATE, 0);
        long wheelBefore = stack.emulator().telegrams(NxtTelegram.GETOUTPUTSTATE, 1);
        long t0 = System.nanoTime();
        robot.move(0.4, 0.15);
        double seconds = (System.nanoTime() - t0) / 1e9;
        long gripper = stack.emulator().telegrams(NxtTelegram.GETOUTPUTSTATE, 0) - gripperBefore;
        long wheel = stack.emulator().telegrams(NxtTelegram.GETOUTPUTSTATE, 1) - wheelBefore;
        assertTrue(wheel >= 5 * seconds, "the wheel B was read " + wheel + " times in " + seconds + " s");
        assertTrue(gripper <= seconds + 2, "the gripper A at rest was read " + gripper + " times in " + seconds + " s");
    }

    /**
     * Closing the robot leaves every output idle (no power, no brake, no regulation), as the
     * brick's own stop does, rather than braked and regulated, drawing current until the brick
     * is switched off.
     */
    @Test
    void shouldLeaveEveryOutputCoastingWhenTheRobotCloses() throws Exception {
        start(0.5);
        robot.move(0.1, 0.15);
        robot.close();

        for (int port = 0; port < 3; port++) {
            byte[] state = stack.emulator().handle(new byte[]{0x00, 0x06, (byte) port});
            assertEquals(0x00, state[5], "output " + port + ": mode byte (MOTORON, BRAKE, REGULATED all off)");
            assertEquals(0x00, state[6], "output " + port + ": regulation idle");
            assertEquals(0x00, state[8], "output " + port + ": run state idle");
        }
    }

    @Test
    void shouldReadLightFromFloor() throws Exception {
        start(1.0);
        assertEquals(80.0, robot.getValue(Position.BOTTOM, SensorType.LIGHT, ReturnType.PERCENT), 0.2);
    }

    @ParameterizedTest(name = "status 0x{0}")
    @ValueSource(strings = {"BE", "C0", "DD", "FF"})
    void brickThatRefusesEveryCommandFailsTheMoveAtOnceWithItsStatusAndTelegram(String hex) throws Exception {
        int status = Integer.parseInt(hex, 16);
        start(0.5);
        stack.emulator().refuseEverythingWith(status);
        long asked = System.nanoTime();

        RobotException e = assertThrows(RobotException.class, () -> robot.move(0.5, 0.2));

        long millis = (System.nanoTime() - asked) / 1_000_000;
        assertTrue(millis < 3000, "the refusal took " + millis + " ms to reach the caller (it waited for the motor, 11 s, before)");
        assertTrue(e.getMessage().contains("NXT refused") && e.getMessage().contains("status 0x" + hex)
                && e.getMessage().contains("telegram "), e.getMessage());
        assertFalse(e.getMessage().contains("blocked"), "the brick's refusal is not the motor's fault: " + e.getMessage());

        stack.emulator().refuseEverythingWith(0);
        robot.move(0.1, 0.2);
    }
}
