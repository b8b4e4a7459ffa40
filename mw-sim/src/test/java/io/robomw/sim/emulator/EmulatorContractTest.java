package io.robomw.sim.emulator;

import io.robomw.api.Pose;
import io.robomw.api.Position;
import io.robomw.api.ReturnType;
import io.robomw.api.Robot;
import io.robomw.api.RobotLinkException;
import io.robomw.api.SensorType;
import io.robomw.sim.Simulation;
import io.robomw.sim.emulator.ev3.Ev3Emulator;
import io.robomw.sim.emulator.ev3.Ev3FullStackTest;
import io.robomw.sim.emulator.ft.txt.TxtEmulator;
import io.robomw.sim.emulator.ft.txt.TxtEmulatorProtocolTest;
import io.robomw.sim.emulator.nxt.NxtEmulator;
import io.robomw.sim.emulator.nxt.NxtEmulatorTest;
import io.robomw.testkit.Await;
import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.io.TempDir;
import org.junit.jupiter.params.ParameterizedTest;
import org.junit.jupiter.params.provider.EnumSource;

import java.io.IOException;
import java.nio.file.Path;
import java.time.Duration;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.ExecutionException;
import java.util.concurrent.TimeUnit;
import java.util.function.BiFunction;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertInstanceOf;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * What every brick emulator stack promises, checked the same way on each: the real driver
 * ({@code Robots.open} on the brick's robot file) byte for byte over the emulator's pseudo-terminal
 * or TCP port, the emulator's motors and sensors a robot in a 3 m arena running at four times real
 * time, every check on the simulated robot's true pose. Each brick keeps its own tolerances (its
 * encoder resolution, its link) and its own tests of what only it does ({@link NxtEmulatorTest},
 * {@link Ev3FullStackTest}, {@link TxtEmulatorProtocolTest}).
 */
class EmulatorContractTest {

    /** How fast the worlds run: four simulated seconds a second. */
    private static final double SPEED = 4;

    /** A brick's stack and what it promises. */
    enum Brick {
        /** The NXT on a pseudo-terminal (an emulated Bluetooth link). */
        NXT(NxtEmulatorTest.ROBOT, "nxt-1", NxtEmulator::bind, Link.PSEUDO_TERMINAL, 0.01, 0.01, 2.0, Duration.ofSeconds(20), 0.03, false),
        /** The EV3 on a pseudo-terminal; its driver polls while idle, so a reconnect is seen before the next command. */
        EV3(Ev3FullStackTest.ROBOT, "ev3-1", Ev3Emulator::bind, Link.PSEUDO_TERMINAL, 0.01, 0.01, 2.0, Duration.ofSeconds(10), 0.005, true),
        /**
         * The TXT on TCP; its encoders count 63 pulses a motor turn, 2.79 mm of wheel travel and
         * 2.86° of heading per pulse of one wheel (see {@link TxtEmulatorProtocolTest#ROBOT}). Its
         * driver polls while idle: the link thread sends the cyclic exchange (the TXT's keep-alive)
         * every 100 ms. A sensor read is no probe of its link: it is answered from the last
         * exchange's inputs while they are less than 100 ms old, which may be the closed
         * emulator's.
         */
        TXT(TxtEmulatorProtocolTest.ROBOT, "txt-1", TxtEmulator::bind, Link.TCP, 0.02, 0.02, 5.0, Duration.ofSeconds(20), 0.03, true);

        final String robotFile;
        final String robotName;
        final BiFunction<Simulation, String, ? extends BrickEmulator> bind;
        final Link link;
        /** How far half a metre may end from its mark, along it and across it, metres. */
        final double moveWithin;
        /** How far a reconnected robot's 20 cm may end from its mark, metres. */
        final double reconnectedMoveWithin;
        /** How far a quarter turn may end from 90°, degrees. */
        final double turnWithinDegrees;
        /** How long the bumper may take to read pressed, driving at a wall 30 cm away at 0.1 m/s. */
        final Duration bumperWithin;
        /** How far the robot may coast after its emulator died, metres. */
        final double coastsWithin;
        /** Whether the driver polls while idle, so that a reconnect shows before the next command. */
        final boolean pollsWhileIdle;

        Brick(String robotFile, String robotName, BiFunction<Simulation, String, ? extends BrickEmulator> bind, Link link, double moveWithin,
              double reconnectedMoveWithin, double turnWithinDegrees, Duration bumperWithin, double coastsWithin, boolean pollsWhileIdle) {
            this.robotFile = robotFile;
            this.robotName = robotName;
            this.bind = bind;
            this.link = link;
            this.moveWithin = moveWithin;
            this.reconnectedMoveWithin = reconnectedMoveWithin;
            this.turnWithinDegrees = turnWithinDegrees;
            this.bumperWithin = bumperWithin;
            this.coastsWithin = coastsWithin;
            this.pollsWhileIdle = pollsWhileIdle;
        }
    }

    /** How a brick's driver reaches its emulator. */
    enum Link {
        /** A pseudo-terminal, as a serial port. */
        PSEUDO_TERMINAL,
        /** A TCP port on 127.0.0.1. */
        TCP
    }

    @TempDir
    Path dir;

    private EmulatorStack<BrickEmulator> stack;
    private Robot robot;

    @AfterEach
    void close() {
        if (stack != null) {
            stack.close();
        }
    }

    @SuppressWarnings("unchecked")
    private EmulatorStack<BrickEmulator> stack(Brick brick) {
        stack = new EmulatorStack<>(dir, brick.robotFile, brick.robotName, (BiFunction<Simulation, String, BrickEmulator>) brick.bind);
        return stack;
    }

    /** The robot at (x, 1.5) facing the wall at x = 3, its emulator serving, its driver open on it. */
    private void start(Brick brick, double x) throws IOException {
        stack(brick);
        if (brick.link == Link.PSEUDO_TERMINAL) {
            robot = stack.openOnPseudoTerminal(x, SPEED);
        } else {
            stack.openOnTcp(3, x, SPEED);
            robot = stack.robot();
        }
    }

    private Pose truePose() {
        return stack.truePose();
    }

    @ParameterizedTest
    @EnumSource(Brick.class)
    void shouldMoveTheSimulatedRobotHalfAMetre(Brick brick) throws Exception {
        start(brick, 0.5);

        robot.move(0.5, 0.15);

        assertEquals(1.0, truePose().x(), brick.moveWithin);
        assertEquals(1.5, truePose().y(), brick.moveWithin);
    }

    @ParameterizedTest
    @EnumSource(Brick.class)
    void shouldTurnAQuarter(Brick brick) throws Exception {
        start(brick, 1.5);

        robot.turn(Math.PI / 2, 1.0);

        assertEquals(90, Math.toDegrees(truePose().heading()), brick.turnWithinDegrees);
    }

    @ParameterizedTest
    @EnumSource(Brick.class)
    void shouldReadTheDistanceToTheWallWithItsUltrasonicSensor(Brick brick) throws Exception {
        start(brick, 2.0);
        double expected = 3.0 - (2.0 + 0.10);

        assertEquals(expected * 100, robot.getValue(Position.FRONT, SensorType.SONAR, ReturnType.CENTIMETERS), 2.0);
    }

    @ParameterizedTest
    @EnumSource(Brick.class)
    void shouldReadTheBumperPressedAgainstTheWall(Brick brick) throws Exception {
        start(brick, 2.6);
        assertEquals(0.0, robot.getValue(Position.FRONT, SensorType.TOUCH, ReturnType.BOOLEAN));

        CompletableFuture<Void> drive = robot.moveAsync(0.5, 0.1);

        Await.until("the bumper reads pressed", brick.bumperWithin, () -> robot.getValue(Position.FRONT, SensorType.TOUCH, ReturnType.BOOLEAN) == 1.0,
                () -> "; robot at " + truePose());
        robot.stop();
        assertTrue(truePose().x() + 0.10 <= 3.005, "at the wall, not through it: " + truePose());
        Exception ended = assertThrows(Exception.class, () -> drive.get(5, TimeUnit.SECONDS));
        assertFalse(ended instanceof java.util.concurrent.TimeoutException, "the blocked move ended by the stop, not by the 5 s wait: " + ended);
    }

    @ParameterizedTest
    @EnumSource(Brick.class)
    void shouldFailTheMoveWithALinkErrorWithinASecondWhenTheEmulatorDiesAndLeaveTheRobotStopped(Brick brick) throws Exception {
        start(brick, 0.5);
        CompletableFuture<Void> move = robot.moveAsync(1.0, 0.1);
        double before = truePose().x();
        stack.awaitStep(() -> truePose().x() > before + 0.05, Duration.ofSeconds(10), "the robot started moving");

        long killed = System.nanoTime();
        stack.emulator().close();

        ExecutionException e = assertThrows(ExecutionException.class, () -> move.get(1, TimeUnit.SECONDS));
        long tookNanos = System.nanoTime() - killed;
        assertInstanceOf(RobotLinkException.class, e.getCause());
        assertTrue(tookNanos < Duration.ofSeconds(1).toNanos(), "reported after " + tookNanos / 1_000_000 + " ms");
        double stoppedAt = truePose().x();
        stack.awaitHalfASimulatedSecond();
        assertEquals(stoppedAt, truePose().x(), brick.coastsWithin, "the robot stopped with its brick");
    }

    /**
     * The emulator closes and a new one serves on the same port: the driver reconnects by itself,
     * without the robot being opened again. A driver that polls while idle has reconnected once it
     * has polled the new emulator, and its next move must work at once; the others reconnect at
     * their next command (here a sensor read), which may fail with a link error until they have.
     */
    @ParameterizedTest
    @EnumSource(Brick.class)
    void shouldReconnectOverTcpWhenTheEmulatorComesBackWithoutReopeningTheRobot(Brick brick) throws Exception {
        int port = stack(brick).openOnTcp(4, 0.5, SPEED);
        robot = stack.robot();
        robot.move(0.2, 0.15);
        assertEquals(0.7, truePose().x(), brick.reconnectedMoveWithin);

        stack.emulator().close();
        BrickEmulator second = stack.newEmulator();
        second.startOnTcp("127.0.0.1", port);
        double before = truePose().x();
        if (brick.pollsWhileIdle) {
            stack.awaitStep(() -> second.framesServed() >= 3, Duration.ofSeconds(10), "the driver reconnected and polled the new emulator");
            robot.move(0.2, 0.15);
        } else {
            // Its next command finds the link gone and reconnects. The probe is a sensor read, not a move: a move whose
            // reply times out on a busy machine has already started on a brick that finishes its rotation by itself
            // (the NXT's tacho limit), and a second try would add its 20 cm to the first's.
            RobotLinkException[] last = new RobotLinkException[1];
            Await.until("the driver reconnected", Duration.ofSeconds(10), () -> {
                try {
                    robot.getValue(Position.FRONT, SensorType.TOUCH, ReturnType.BOOLEAN);
                    return true;
                } catch (RobotLinkException e) {
                    last[0] = e;
                    return false;
                }
            }, () -> "; last: " + last[0]);
            before = truePose().x();
            robot.move(0.2, 0.15);
        }

        assertEquals(before + 0.2, truePose().x(), brick.reconnectedMoveWithin);
    }
}
