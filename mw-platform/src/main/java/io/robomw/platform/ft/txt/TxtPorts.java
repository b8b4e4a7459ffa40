package io.robomw.platform.ft.txt;

import io.robomw.api.spi.MotorChannel;
import io.robomw.api.spi.PlatformConfig;
import io.robomw.platform.ft.FtMotors;

import java.util.Collections;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Map;

/**
 * The TXT's port names and how a robot description wires them, shared by the driver and the
 * emulator: motor outputs M1..M4, universal inputs I1..I8, fast counters C1..C4.
 *
 * <p>A wheel's encoder pulses are counted on the counter its description names
 * ({@code counter: C2}); without one, motor Mi's encoder is on counter Ci, where the TXT's own
 * distance commands count it (fischertechnik encoder motors plug into the counter of the same
 * number). Only wheels have encoders: {@code encoder_ticks_per_revolution} is a property of the
 * drive.
 */
public final class TxtPorts {

    private TxtPorts() {
    }

    /**
     * @param port a motor port name
     * @return its index: M1 = 0 ... M4 = 3
     * @throws IllegalArgumentException if the TXT has no such output
     */
    public static int motor(String port) {
        return FtMotors.index(port, TxtProtocol.MOTORS);
    }

    /**
     * @param port an input port name
     * @return its index: I1 = 0 ... I8 = 7
     * @throws IllegalArgumentException if the TXT has no such input
     */
    public static int input(String port) {
        return numbered(port, 'I', TxtProtocol.INPUTS, "universal inputs");
    }

    /**
     * @param port a counter name
     * @return its index: C1 = 0 ... C4 = 3
     * @throws IllegalArgumentException if the TXT has no such counter
     */
    public static int counter(String port) {
        return numbered(port, 'C', TxtProtocol.COUNTERS, "fast counters");
    }

    private static int numbered(String port, char letter, int count, String what) {
        if (port.length() == 2 && port.charAt(0) == letter && port.charAt(1) >= '1' && port.charAt(1) < '1' + count) {
            return port.charAt(1) - '1';
        }
        throw new IllegalArgumentException("the TXT's " + what + " are " + letter + "1 to " + letter + count + ", not '" + port + "'");
    }

    /**
     * Which counter counts each wheel's encoder.
     *
     * @param motors a robot's motors ({@link PlatformConfig#motors()})
     * @param source where they were described, for error messages
     * @return wheel motor port to counter index, in wheel order (empty without a drive)
     * @throws IllegalArgumentException naming the description's file if a counter name is not C1..C4,
     *                                  or two wheels end up on one counter
     */
    public static Map<String, Integer> wheelCounters(List<MotorChannel> motors, String source) {
        Map<String, Integer> counters = new LinkedHashMap<>();
        for (MotorChannel w : motors.stream().filter(m -> m.role().wheel()).toList()) {
            int counter;
            try {
                counter = w.counter().map(TxtPorts::counter).orElseGet(() -> motor(w.port()));
            } catch (IllegalArgumentException e) {
                throw new IllegalArgumentException(source + ": wheel on " + w.port() + ": " + e.getMessage(), e);
            }
            if (counters.containsValue(counter)) {
                throw new IllegalArgumentException(source + ": both wheels are counted on C" + (counter + 1)
                        + "; give each wheel its own counter (counter: C1 .. C4; by default Mi is counted on Ci)");
            }
            counters.put(w.port(), counter);
        }
        return Collections.unmodifiableMap(counters);
    }
}
