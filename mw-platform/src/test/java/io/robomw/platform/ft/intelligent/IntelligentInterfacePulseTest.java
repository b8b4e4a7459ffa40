package io.robomw.platform.ft.intelligent;

import io.robomw.api.Clock;
import io.robomw.api.spi.ConnectionSettings;
import io.robomw.api.spi.MotorChannel;
import io.robomw.api.spi.PlatformConfig;
import io.robomw.api.spi.PlatformServices;
import io.robomw.platform.brick.BrickChannel;
import io.robomw.platform.link.Communicator;
import io.robomw.platform.link.Link;
import io.robomw.platform.motor.MotorState;
import org.junit.jupiter.api.Test;

import java.io.IOException;
import java.time.Duration;
import java.util.ArrayDeque;
import java.util.Deque;
import java.util.List;
import java.util.Map;
import java.util.Optional;
import java.util.concurrent.locks.LockSupport;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * Pulsed wheel motors on a loaded host, against a hand-written Intelligent Interface on a 9600-baud
 * line: the interface takes each command as its two bytes arrive, so a motor is on from the
 * arrival of a command that switches it on to the arrival of the next that does not. The host is
 * made to lose the processor for {@value #HOST_AWAY_MILLIS} ms each time it reads an answer with
 * the motor on (as a busy machine does to the link thread). A pulse must still last its few
 * milliseconds: it is timed by the line, not by when the host gets round to switching the motor
 * off.
 */
class IntelligentInterfacePulseTest {

    private static final long HOST_AWAY_MILLIS = 30;
    private static final int TICKS = 40;

    /** The interface at the far end of a 9600-baud line, timing each command by its bytes. */
    static final class TimedInterface implements Link {
        private final Deque<Byte> replies = new ArrayDeque<>();
        private final Deque<Boolean> replyMotorOn = new ArrayDeque<>();
        private boolean open;
        private long lineFree;
        private long onSince = -1;
        long longestOnNanos;
        int onPeriods;

        @Override
        public void open() {
            open = true;
        }

        @Override
        public boolean isOpen() {
            return open;
        }

        @Override
        public void write(byte[] data, int off, int len) {
            long start = Math.max(System.nanoTime(), lineFree);
            for (int i = 0; i + 1 < len; i += 2) {
                long arrives = start + (i / 2 + 1) * IntelligentInterfaceMotorPlatform.COMMAND_WIRE_NANOS;
                boolean on = IntelligentInterfaceTelegram.direction(data[off + i + 1] & 0xFF, 0) != 0;
                if (on && onSince < 0) {
                    onSince = arrives;
                    onPeriods++;
                } else if (!on && onSince >= 0) {
                    longestOnNanos = Math.max(longestOnNanos, arrives - onSince);
                    onSince = -1;
                }
                replies.add((byte) 0);
                replies.add((byte) 0);
                replies.add((byte) 0);
                replyMotorOn.add(on);
                lineFree = arrives;
            }
        }

        @Override
        public int read(byte[] buf, int off, int len, Duration timeout) {
            if (replies.isEmpty()) {
                return 0;
            }
            if (replies.size() % 3 == 0 && Boolean.TRUE.equals(replyMotorOn.poll())) {
                // The host reads the interface's answer, then loses the processor.
                LockSupport.parkNanos(HOST_AWAY_MILLIS * 1_000_000L);
            }
            int n = 0;
            while (n < len && !replies.isEmpty() && (n == 0 || replies.size() % 3 != 0)) {
                buf[off + n++] = replies.poll();
            }
            return n;
        }

        @Override
        public String describe() {
            return "timed interface";
        }

        @Override
        public void close() {
            open = false;
        }
    }

    private static IntelligentInterfaceMotorPlatform platform(TimedInterface line) throws IOException {
        Communicator c = new Communicator(line);
        c.open();
        BrickChannel channel = new BrickChannel("ft-test", c, Duration.ofMillis(500));
        PlatformConfig config = new PlatformConfig("ft-test", "ft-intelligent",
                new ConnectionSettings(Map.of("port", "/dev/ttyS0"), "test.yaml"),
                List.of(new MotorChannel("M1", MotorChannel.Role.LEFT_WHEEL, TICKS, Optional.of("E1"))), List.of(),
                Duration.ofMillis(10), Duration.ZERO, Clock.system(), PlatformServices.none());
        return new IntelligentInterfaceMotorPlatform(config, channel, new IntelligentInterfaceInputs());
    }

    @Test
    void shouldKeepAPulsedMotorOnForItsWireTimeHoweverLateTheHostIs() throws Exception {
        TimedInterface line = new TimedInterface();
        IntelligentInterfaceMotorPlatform motors = platform(line);
        motors.runImpl(List.of(new MotorState("M1", 620, Double.POSITIVE_INFINITY, MotorState.StopMode.BRAKE)));
        // The link thread comes round only every 40 ms, far longer than half a tick at full speed
        // (7 ms): the platform pulses the wheel.
        for (int cycle = 0; cycle < 20 && motors.pulses() == 0; cycle++) {
            motors.pollFeedback();
            Thread.sleep(40);
        }
        assertTrue(motors.pulses() > 0, "the wheel was never pulsed");
        // Until the platform noticed the gaps, the wheel ran through them; from now on it is pulsed.
        line.longestOnNanos = 0;
        line.onPeriods = 0;
        for (int cycle = 0; cycle < 8; cycle++) {
            Thread.sleep(40);
            motors.pollFeedback();
        }
        assertTrue(line.onPeriods > 3, "the wheel was switched on only " + line.onPeriods + " times");
        // 5 ms asked for: three commands' bytes (6.25 ms) on, then the command that switches it off.
        assertEquals(3 * IntelligentInterfaceMotorPlatform.COMMAND_WIRE_NANOS / 1e6, line.longestOnNanos / 1e6, 0.01,
                "a pulse lasted " + line.longestOnNanos / 1e6 + " ms");
    }
}
