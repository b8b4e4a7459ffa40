package io.robomw.platform.ft.intelligent;

import io.robomw.api.Clock;
import io.robomw.api.spi.ConnectionSettings;
import io.robomw.api.spi.MotorChannel;
import io.robomw.api.spi.PlatformConfig;
import io.robomw.api.spi.PlatformServices;
import io.robomw.platform.brick.BrickChannel;
import io.robomw.platform.ft.FtMotors;
import io.robomw.platform.link.Communicator;
import io.robomw.platform.motor.MotorPlatform;
import io.robomw.platform.motor.MotorState;
import io.robomw.platform.testkit.Answer;
import io.robomw.platform.testkit.ScriptedLink;
import org.junit.jupiter.api.Test;

import java.io.IOException;
import java.time.Duration;
import java.util.List;
import java.util.Map;
import java.util.Optional;
import java.util.SplittableRandom;
import java.util.concurrent.locks.LockSupport;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * The driver against a scripted Intelligent Interface at the far end of a 9600-baud line, on a
 * host as loaded as a busy build machine: the line starts sending a write up to
 * {@value #LINE_HELD_MILLIS} ms after the host wrote it (a USB serial adapter's buffering, a kernel
 * that gets to it late), and the host loses the processor for up to {@value #HOST_AWAY_MILLIS} ms
 * after reading an answer. The interface takes each command as its two bytes arrive and answers
 * with its impulse switch as it is then; its motor turns at full speed while the last command it
 * took has it on, and its impulse wheel gives {@value #TICKS} transitions a turn.
 */
class IntelligentInterfaceLineTimingTest {

    private static final int TICKS = 16;
    private static final long LINE_HELD_MILLIS = 40;
    private static final long HOST_AWAY_MILLIS = 60;
    private static final long WIRE = IntelligentInterfaceMotorDriver.COMMAND_WIRE_NANOS;

    /** The interface and its line; one motor, M1, with its impulse switch on E1. */
    static final class TimedInterface {
        private final SplittableRandom random = new SplittableRandom(17);
        private long lineFree;
        private long replyLineFree;
        private long lastArrival = Long.MIN_VALUE;
        private int motorByte;
        /** The motor's true rotation, degrees, at the last command's arrival. */
        double degrees;
        int writes;
        int writesLeavingTheMotorOn;
        private final boolean hostAway;
        /** The host's end of the line: each write answered by the interface, each answer due when its last byte is back. */
        final ScriptedLink link = new ScriptedLink().named("timed interface")
                .answeringWith(this::take).afterReadingEachPiece(this::hostMayLoseTheProcessor);

        TimedInterface(boolean hostAway) {
            this.hostAway = hostAway;
        }

        /** Takes each command of a write as its two bytes arrive, and answers it with the switch as it is then. */
        private Answer take(byte[] data) {
            long held = hostAway ? random.nextLong(LINE_HELD_MILLIS * 1_000_000L) : 0;
            long start = Math.max(System.nanoTime() + held, lineFree);
            Answer answers = Answer.none();
            for (int i = 0; i + 1 < data.length; i += 2) {
                long arrives = start + (i / 2 + 1) * WIRE;
                if (lastArrival != Long.MIN_VALUE) {
                    long on = Math.min(arrives - lastArrival, IntelligentInterfaceTelegram.WATCHDOG_MILLIS * 1_000_000L);
                    int d = IntelligentInterfaceTelegram.direction(motorByte, 0);
                    int sign = d == IntelligentInterfaceTelegram.CW ? 1 : d == IntelligentInterfaceTelegram.CCW ? -1 : 0;
                    degrees += sign * FtMotors.DEGREES_PER_SECOND_AT_FULL_POWER * on / 1e9;
                }
                lastArrival = arrives;
                int command = data[i] & 0xFF;
                motorByte = data[i + 1] & 0xFF;
                int digital = switchClosed() ? 1 : 0;
                byte[] reply = command == IntelligentInterfaceTelegram.DIGITAL ? new byte[]{(byte) digital}
                        : new byte[]{(byte) digital, 0x01, 0x00};
                long replyStart = Math.max(arrives, replyLineFree);
                replyLineFree = replyStart + reply.length * WIRE / 2;
                answers = answers.and(Answer.of(reply).dueAt(replyLineFree));
                lineFree = arrives;
            }
            writes++;
            if (IntelligentInterfaceTelegram.direction(motorByte, 0) != 0) {
                writesLeavingTheMotorOn++;
            }
            return answers;
        }

        /** The switch starts mid-tooth: the first transition comes after half a tick. */
        private boolean switchClosed() {
            return Math.floorMod((long) Math.floor(degrees * TICKS / 360.0 + 0.5), 2) == 1;
        }

        /** The host reads the interface's answer, then may lose the processor. */
        private void hostMayLoseTheProcessor() {
            if (hostAway && random.nextInt(4) == 0) {
                LockSupport.parkNanos(random.nextLong(HOST_AWAY_MILLIS * 1_000_000L));
            }
        }
    }

    /** The driver under test, and the motor platform its readings go to. */
    private record Under(IntelligentInterfaceMotorDriver driver, MotorPlatform motors) {
        double degrees() {
            return motors.motorDegrees("M1");
        }
    }

    private static Under platform(TimedInterface line) throws IOException {
        Communicator c = new Communicator(line.link);
        c.open();
        BrickChannel channel = new BrickChannel("ft-test", c, Duration.ofMillis(500));
        PlatformConfig config = new PlatformConfig("ft-test", "ft-intelligent",
                new ConnectionSettings(Map.of("port", "/dev/ttyS0"), "test.yaml"),
                List.of(new MotorChannel("M1", MotorChannel.Role.LEFT_WHEEL, TICKS, Optional.of("E1"))), List.of(),
                Duration.ofMillis(10), Duration.ZERO, Clock.system(), PlatformServices.none(), io.robomw.api.spi.Cycling.OWN_THREADS, io.robomw.api.spi.FailurePolicy.logging());
        IntelligentInterfaceMotorDriver driver = new IntelligentInterfaceMotorDriver(config, channel, new IntelligentInterfaceInputs(config.clock()));
        return new Under(driver, new MotorPlatform(config, driver));
    }

    /** Runs the link side, a cycle every 10 ms, until the wheel's limited rotation ended (or 20 s passed). */
    private static void turn(Under under, double degreesPerSecond, double limit) throws IOException {
        IntelligentInterfaceMotorDriver motors = under.driver();
        motors.send(List.of(new MotorState("M1", degreesPerSecond, limit, MotorState.StopMode.BRAKE)), under.motors().feedback());
        long deadline = System.nanoTime() + Duration.ofSeconds(20).toNanos();
        int idle = 0;
        while (idle < 3 && System.nanoTime() < deadline) {
            long cycleStart = System.nanoTime();
            long before = motors.wheelCommandsOn();
            motors.poll(under.motors().feedback());
            idle = motors.wheelCommandsOn() == before ? idle + 1 : 0;
            LockSupport.parkNanos(Math.max(0, cycleStart + 10_000_000L - System.nanoTime()));
        }
    }

    @Test
    void shouldNeverLeaveAWheelOnWhenTheHostStopsWatching() throws Exception {
        TimedInterface line = new TimedInterface(true);
        Under under = platform(line);
        turn(under, 310, 360);
        assertTrue(line.writes > 20, "the link side wrote " + line.writes + " times");
        assertEquals(0, line.writesLeavingTheMotorOn, "writes that left the motor on for the host's absence");
        assertTrue(under.driver().bursts() > 0);
    }

    /**
     * A turn of the motor at half speed, then half a turn back: every transition counted although
     * the host was away up to 60 ms at a time (a tick takes 36 ms at full speed) and the line held
     * its writes up to 40 ms, so each rotation ends within half a tick (and one command's travel)
     * of its target, and the driver's count moves as the wheel does. (Where the count starts
     * within the first tick is unknown, as a real impulse wheel's phase is: rotations are compared.)
     */
    @Test
    void shouldCountEveryTransitionAndEndEachRotationWithinHalfATickOnALoadedHost() throws Exception {
        TimedInterface line = new TimedInterface(true);
        Under under = platform(line);
        double tick = 360.0 / TICKS;
        under.driver().poll(under.motors().feedback());
        double countAtStart = under.degrees();
        turn(under, 310, 360);
        assertEquals(360, line.degrees, tick / 2 + IntelligentInterfaceMotorDriver.SLOT_DEGREES, "the wheel after a turn forward");
        assertEquals(line.degrees, under.degrees() - countAtStart, tick / 2, "the driver's count against the wheel");
        double wheelThen = line.degrees;
        double countThen = under.degrees();
        turn(under, -310, 180);
        assertEquals(-180, line.degrees - wheelThen, tick / 2 + IntelligentInterfaceMotorDriver.SLOT_DEGREES, "the wheel's turn back");
        assertEquals(line.degrees - wheelThen, under.degrees() - countThen, tick / 2, "the driver's count against the wheel");
    }

    /**
     * On a quiet host a wheel at half duty turns at half speed: the commands it is on for follow
     * its duty of the time that passes, the gaps between bursts included.
     */
    @Test
    void shouldTurnAWheelAtItsDutyOfFullSpeedOnAQuietHost() throws Exception {
        TimedInterface line = new TimedInterface(false);
        Under under = platform(line);
        long start = System.nanoTime();
        turn(under, 310, 720);
        double seconds = (System.nanoTime() - start) / 1e9;
        // 720° at 310°/s take 2.3 s. Allow for the idle cycles that end the loop and a busy test
        // machine, whose late cycles leave fewer bursts.
        assertTrue(seconds < 2.3 * 2 + 0.5, "two turns at half speed took " + seconds + " s");
        assertTrue(seconds > 2.3 * 0.9, "two turns at half speed took only " + seconds + " s");
    }
}
