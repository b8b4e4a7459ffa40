package io.robomw.sim.emulator.nxt;

import io.robomw.platform.nxt.NxtTelegram;

import java.nio.charset.StandardCharsets;
import java.util.Arrays;

/**
 * The LEGO ultrasonic sensor's I²C registers, as a client reads them through LSWRITE/LSREAD
 * (LEGO Hardware Developer Kit, appendix 7; register map as nxt-python's {@code Ultrasonic} and
 * protocols §1.6 give it). A read starts at a register address and returns what the sensor keeps
 * there, zero-padded to the length asked for:
 *
 * <pre>
 * 0x00  version          "V1.0"      (8 bytes)
 * 0x08  product id       "LEGO"      (8 bytes)
 * 0x10  sensor type      "Sonar"     (8 bytes)
 * 0x14  units            "10E-2m"    (7 bytes)
 * 0x40  measurement interval (continuous mode)
 * 0x41  command: 0 off, 1 single shot, 2 continuous (the default), 3 event capture, 4 warm reset
 * 0x42..0x49  measurements 0..7, centimetres (255: nothing in range); only the first is the
 *       nearest echo, the others read 0 in continuous mode
 * 0x51  scale factor (1), 0x52 scale divisor (1)
 * </pre>
 * Writes ({@code tx = [0x02, register, value...]}) store the values; other addresses read 0.
 *
 * <p>Not thread-safe: the emulator guards it with its firmware lock.
 */
final class NxtUltrasonic {

    /** Register of the version string. */
    static final int VERSION = 0x00;
    /** Register of the product id. */
    static final int PRODUCT_ID = 0x08;
    /** Register of the sensor type. */
    static final int SENSOR_TYPE = 0x10;
    /** Register of the measurement units. */
    static final int UNITS = 0x14;
    /** Register of the continuous-measurement interval. */
    static final int INTERVAL = 0x40;
    /** Register of the command (mode). */
    static final int COMMAND = 0x41;
    /** Register of the scale factor. */
    static final int SCALE_FACTOR = 0x51;
    /** Register of the scale divisor. */
    static final int SCALE_DIVISOR = 0x52;
    /** Continuous measurement, the sensor's default mode. */
    static final int CONTINUOUS = 2;
    /** What a measurement register reads when nothing is in range. */
    static final int NOTHING_IN_RANGE = 255;

    private final byte[] written = new byte[256];

    NxtUltrasonic() {
        written[COMMAND] = CONTINUOUS;
        written[SCALE_FACTOR] = 1;
        written[SCALE_DIVISOR] = 1;
    }

    /**
     * @param register the first register
     * @param length   how many bytes
     * @param metres   the distance to the nearest object
     * @return the bytes the sensor answers
     */
    byte[] read(int register, int length, double metres) {
        byte[] out = new byte[length];
        byte[] text = switch (register) {
            case VERSION -> ascii("V1.0");
            case PRODUCT_ID -> ascii("LEGO");
            case SENSOR_TYPE -> ascii("Sonar");
            case UNITS -> ascii("10E-2m");
            default -> null;
        };
        if (text != null) {
            System.arraycopy(text, 0, out, 0, Math.min(length, text.length));
            return out;
        }
        for (int i = 0; i < length; i++) {
            int r = register + i;
            if (r == NxtTelegram.ULTRASONIC_DISTANCE) {
                out[i] = (byte) centimetres(metres);
            } else if (r > NxtTelegram.ULTRASONIC_DISTANCE && r <= NxtTelegram.ULTRASONIC_DISTANCE + 7) {
                out[i] = 0;
            } else if (r < written.length) {
                out[i] = written[r];
            }
        }
        return out;
    }

    /**
     * @param register the first register
     * @param values   the bytes written from there on
     */
    void write(int register, byte[] values) {
        for (int i = 0; i < values.length && register + i < written.length; i++) {
            written[register + i] = values[i];
        }
    }

    /** @return the command register: 2 continuous, 0 off ... */
    int command() {
        return written[COMMAND] & 0xFF;
    }

    private static int centimetres(double metres) {
        return (int) Math.max(0, Math.min(NOTHING_IN_RANGE, Math.round(metres * 100)));
    }

    private static byte[] ascii(String s) {
        return Arrays.copyOf(s.getBytes(StandardCharsets.US_ASCII), s.length() + 1);
    }
}
