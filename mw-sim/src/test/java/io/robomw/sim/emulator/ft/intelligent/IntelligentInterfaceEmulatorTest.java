package io.robomw.sim.emulator.ft.intelligent;

import io.robomw.api.Pose;
import io.robomw.api.Position;
import io.robomw.api.ReturnType;
import io.robomw.api.Robot;
import io.robomw.api.SensorType;
import io.robomw.platform.ft.intelligent.IntelligentInterfaceTelegram;
import io.robomw.platform.link.SerialLink;
import io.robomw.platform.link.SerialSettings;
import io.robomw.testkit.BusyThreads;
import io.robomw.sim.emulator.EmulatorStack;
import io.robomw.testkit.Await;
import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.BeforeEach;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

import java.io.IOException;
import java.nio.file.Path;
import java.time.Duration;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.TimeUnit;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * The real Intelligent Interface driver over a real pseudo-terminal through jSerialComm, against
 * the emulator bound to a simulated robot. The impulse wheel gives 16 transitions per motor turn:
 * 22.5° of motor, 11.0 mm of travel on 56 mm wheels, per tick; that is the resolution of every
 * distance below. The interface stops nothing by itself, so the driver's stop is as late as its
 * link's latency in wall-clock time: the precision tests run the world in real time.
 */
public class IntelligentInterfaceEmulatorTest {

    public static final String ROBOT = """
            name: ft-1
            platform: ft-intelligent
            connection: { %s }
            drive:
              wheel_diameter: 0.056
              track_width: 0.112
              max_speed: 0.30
              encoder_ticks_per_revolution: 16
              left:  { port: M1, counter: E1 }
              right: { port: M2, counter: E2 }
            body: { length: 0.20, width: 0.15, mass: 0.6, friction: 0.8 }
            sensors:
              - { name: bumper, type: touch, position: front, port: E3 }
              - name: range
                type: infrared
                position: front
                port: EX
                conversion: { table: [[80, 0.80], [150, 0.40], [300, 0.20], [600, 0.10], [900, 0.06]] }
            """;

    @TempDir
    Path dir;

    private EmulatorStack<IntelligentInterfaceEmulator> stack;
    private Robot robot;

    @BeforeEach
    void stack() {
        stack = new EmulatorStack<>(dir, ROBOT, "ft-1", IntelligentInterfaceEmulator::bind);
    }

    @AfterEach
    void close() {
        stack.close();
    }

    private void start(double x, double speed) throws IOException {
        robot = stack.openOnPseudoTerminal(x, speed);
    }

    /**
     * The robot's true pose once the world has caught up with the interface: the emulator's motors
     * run in real time and the world follows them a few steps late (more when a loaded host held
     * the simulation up), so a pose read the moment a command returns may not show all of it yet.
     */
    private Pose truePose() throws InterruptedException {
        stack.awaitStep(() -> stack.emulator().worldCaughtUp(), Duration.ofSeconds(10), "the world caught up with the interface's motors");
        return stack.truePose();
    }

    @Test
    void shouldMoveHalfAMetreWithinTwoCentimetresByCountingImpulses() throws Exception {
        start(0.5, 1);
        robot.move(0.5, 0.15);
        assertEquals(1.0, truePose().x(), 0.02);
        assertEquals(0, stack.emulator().watchdogTrips());
    }

    @Test
    void shouldTurnQuarterWithinFiveDegrees() throws Exception {
        start(1.5, 1);
        robot.turn(Math.PI / 2, 1.0);
        assertEquals(90, Math.toDegrees(truePose().heading()), 5.0);
    }

    /**
     * With two threads keeping the cores busy, the link thread's polls come late now and then:
     * ticks a late poll could not show are counted from the motor's on-time, and while polls come
     * late the wheels are pulsed, so the move ends within the same two centimetres.
     */
    @Test
    @SuppressWarnings("try")
    void shouldMoveHalfAMetreWithinTwoCentimetresWhileTwoBusyThreadsLoadTheMachine() throws Exception {
        try (BusyThreads load = new BusyThreads(2)) {
            start(0.5, 1);
            robot.move(0.5, 0.15);
        }
        assertEquals(1.0, truePose().x(), 0.02);
    }

    @Test
    @SuppressWarnings("try")
    void shouldTurnQuarterWithinFiveDegreesWhileTwoBusyThreadsLoadTheMachine() throws Exception {
        try (BusyThreads load = new BusyThreads(2)) {
            start(1.5, 1);
            robot.turn(Math.PI / 2, 1.0);
        }
        assertEquals(90, Math.toDegrees(truePose().heading()), 5.0);
    }

    @Test
    void shouldReadBumperOnDigitalInputPressedAgainstWall() throws Exception {
        start(2.5, 2);
        assertEquals(0.0, robot.getValue(Position.FRONT, SensorType.TOUCH, ReturnType.BOOLEAN));
        CompletableFuture<Void> move = robot.moveAsync(0.5, 0.1);
        Await.until("the bumper reads pressed", Duration.ofSeconds(20),
                () -> robot.getValue(Position.FRONT, SensorType.TOUCH, ReturnType.BOOLEAN) == 1.0, () -> "; robot at " + stack.truePose());
        robot.stop();
        Exception ended = assertThrows(Exception.class, () -> move.get(5, TimeUnit.SECONDS));
        assertFalse(ended instanceof java.util.concurrent.TimeoutException, "the blocked move ended by the stop, not by the 5 s wait: " + ended);
        assertTrue(truePose().x() + 0.10 <= 3.005, "at the wall, not through it: " + truePose());
    }

    @Test
    void shouldReadInfraRedDistanceThroughAnalogInputAndItsTable() throws Exception {
        start(2.5, 2);
        double expected = 3.0 - (2.5 + 0.10);
        assertEquals(expected, robot.getValue(Position.FRONT, SensorType.INFRARED, ReturnType.METERS), 0.01);
    }

    @Test
    void shouldKeepInterfaceAliveWhileApplicationThreadIsBlockedForTwoSeconds() throws Exception {
        start(0.5, 1);
        long t0 = System.nanoTime();
        robot.move(0.30, 0.15);
        long blockedNanos = System.nanoTime() - t0;
        assertTrue(blockedNanos >= Duration.ofSeconds(2).toNanos(), "the application thread was blocked in move() for 2 s, was "
                + blockedNanos / 1_000_000 + " ms");
        assertEquals(0, stack.emulator().watchdogTrips(), "the platform refreshed the interface all along");
        assertEquals(0.8, truePose().x(), 0.02);
    }

    /**
     * The impulse wheel is on the motor's shaft: it turns only while the motor is on. A robot
     * pushed against a wall and pulsed forward (on for 21 ms, off for 21 ms, as a driver's bursts
     * do) is read all along; while its motors are off, its impulse switches must not change. (The
     * emulator once placed the switch by the world's wheel plus the motor's rotation not yet carried
     * out: each pulse moved it forward, and the world's next steps, holding the wheel, moved it back
     * while the motor was off, across an edge and back again on the next pulse: two transitions a
     * pulse that no real wheel makes, which a driver counts as forward travel.)
     */
    @Test
    void shouldNotTurnTheImpulseWheelsWhileTheMotorsAreOffAgainstAWall() throws Exception {
        // Facing the east wall, front bumper touching it: the body cannot move forward.
        String pty = stack.startOnPseudoTerminal(3.0 - 0.10, 1);
        try (SerialLink link = new SerialLink(pty, SerialSettings.of(9600, 8, SerialSettings.Parity.NONE, 1))) {
            link.open();
            int bothForward = IntelligentInterfaceTelegram.withMotor(IntelligentInterfaceTelegram.withMotor(0, 0, IntelligentInterfaceTelegram.CW),
                    1, IntelligentInterfaceTelegram.CW);
            int counters = 0b11;
            int changesWhileOff = 0;
            for (int pulse = 0; pulse < 20; pulse++) {
                for (int motorByte : new int[]{bothForward, 0}) {
                    int previous = -1;
                    // 10 commands of 2.1 ms each: 21 ms with the motors on (13° of motor), then 21 ms off.
                    for (int i = 0; i < 10; i++) {
                        byte[] request = IntelligentInterfaceTelegram.request(IntelligentInterfaceTelegram.DIGITAL, motorByte);
                        link.write(request, 0, request.length);
                        byte[] reply = new byte[1];
                        assertEquals(1, link.read(reply, 0, 1, Duration.ofSeconds(2)));
                        int switches = reply[0] & counters;
                        // Each answer shows the switches as its command arrived: from the second
                        // off command on, the motors were off since the last answer.
                        if (motorByte == 0 && previous >= 0 && switches != previous) {
                            changesWhileOff++;
                        }
                        previous = switches;
                    }
                }
            }
            assertEquals(0, changesWhileOff, "the impulse switches changed while the motors were off");
        }
    }

    @Test
    void shouldStopMotorsWhenDriverStopsRefreshing() throws Exception {
        String pty = stack.startOnPseudoTerminal(0.5, 1);
        try (SerialLink link = new SerialLink(pty, SerialSettings.of(9600, 8, SerialSettings.Parity.NONE, 1))) {
            link.open();
            int bothForward = IntelligentInterfaceTelegram.withMotor(IntelligentInterfaceTelegram.withMotor(0, 0, IntelligentInterfaceTelegram.CW),
                    1, IntelligentInterfaceTelegram.CW);
            byte[] request = IntelligentInterfaceTelegram.request(IntelligentInterfaceTelegram.DIGITAL, bothForward);
            // Timed from before the write: the interface's 300 ms count from the command's arrival,
            // which is after it; a time taken after reading the answer would start late by however
            // long a busy machine kept this thread from waking.
            long sent = System.nanoTime();
            link.write(request, 0, request.length);
            byte[] reply = new byte[1];
            assertEquals(1, link.read(reply, 0, 1, Duration.ofSeconds(2)));
            Await.until("the motors started", Duration.ofSeconds(2), () -> stack.emulator().motorsOn());
            Await.until("the interface stopped its motors about 300 ms after the last command", Duration.ofSeconds(2),
                    () -> !stack.emulator().motorsOn());
            long off = System.nanoTime() - sent;
            assertTrue(off >= Duration.ofMillis(290).toNanos(), "not before 300 ms: " + off / 1_000_000 + " ms");
            assertEquals(1, stack.emulator().watchdogTrips());
        }
    }
}
