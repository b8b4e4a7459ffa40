package io.robomw.platform.ft.intelligent;

/**
 * The fischertechnik Intelligent Interface 30402 (RS-232, 9600 8N1): a fixed request and a fixed
 * reply, no framing, no checksum (fischertechnik documentation; libroboint, FTmodule).
 *
 * <pre>
 * request:  [cmd][motor byte]                 reply
 *   C1                                        [digital]                      (1 byte)
 *   C5                                        [digital][EX_hi][EX_lo]        (3 bytes)
 *   C9                                        [digital][EY_hi][EY_lo]        (3 bytes)
 * with the extension module: [cmd][motors][motors of the extension]
 *   C2                                        [digital][digital ext]         (2 bytes)
 *   C6                                        [dig][dig ext][EX_hi][EX_lo]   (4 bytes)
 *   CA                                        [dig][dig ext][EY_hi][EY_lo]   (4 bytes)
 *
 * motor byte: two bits per motor, M1 in bits 0-1 ... M4 in bits 6-7;
 *             01 = counter-clockwise ("left"), 10 = clockwise ("right"), 00 and 11 = off
 * digital:    bit i = input E(i+1)
 * analog:     10 bits, big-endian (high byte first)
 * </pre>
 *
 * The interface switches its motors off when no command arrives for about 300 ms: the driver
 * refreshes it every cycle. Stateless.
 */
public final class IntelligentInterfaceTelegram {

    /** Read the digital inputs. */
    public static final int DIGITAL = 0xC1;
    /** Read the digital inputs and EX. */
    public static final int ANALOG_EX = 0xC5;
    /** Read the digital inputs and EY. */
    public static final int ANALOG_EY = 0xC9;
    /** With the extension module: digital inputs of both. */
    public static final int EXT_DIGITAL = 0xC2;
    /** With the extension module: digital inputs and EX. */
    public static final int EXT_ANALOG_EX = 0xC6;
    /** With the extension module: digital inputs and EY. */
    public static final int EXT_ANALOG_EY = 0xCA;

    /** Motor bits: counter-clockwise. */
    public static final int CCW = 0b01;
    /** Motor bits: clockwise. */
    public static final int CW = 0b10;
    /** Motor outputs of one interface. */
    public static final int MOTORS = 4;
    /** Digital inputs of one interface. */
    public static final int INPUTS = 8;
    /** The interface's serial line speed, baud (8 data bits, no parity, 1 stop bit). */
    public static final int BAUD = 9600;

    /** How long the interface keeps its motors on without a command, milliseconds. */
    public static final int WATCHDOG_MILLIS = 300;

    private IntelligentInterfaceTelegram() {
    }

    /**
     * @param command   {@link #DIGITAL}, {@link #ANALOG_EX} or {@link #ANALOG_EY}
     * @param motorByte the motor byte
     * @return the request
     */
    public static byte[] request(int command, int motorByte) {
        return new byte[]{(byte) command, (byte) motorByte};
    }

    /**
     * @param command a command byte
     * @return the request's length, or −1 for a byte that is no command
     */
    public static int requestLength(int command) {
        return switch (command) {
            case DIGITAL, ANALOG_EX, ANALOG_EY -> 2;
            case EXT_DIGITAL, EXT_ANALOG_EX, EXT_ANALOG_EY -> 3;
            default -> -1;
        };
    }

    /**
     * @param command a command byte
     * @return its reply's length
     */
    public static int replyLength(int command) {
        return switch (command) {
            case DIGITAL -> 1;
            case ANALOG_EX, ANALOG_EY, EXT_DIGITAL -> command == EXT_DIGITAL ? 2 : 3;
            case EXT_ANALOG_EX, EXT_ANALOG_EY -> 4;
            default -> throw new IllegalArgumentException(String.format("0x%02X is not an Intelligent Interface command", command));
        };
    }

    /**
     * @param motor     0 for M1 ... 3 for M4
     * @param direction {@link #CCW}, {@link #CW}, or 0 for off
     * @param motorByte the byte so far
     * @return the byte with that motor's bits set
     */
    public static int withMotor(int motorByte, int motor, int direction) {
        int shift = motor * 2;
        return (motorByte & ~(0b11 << shift)) | (direction & 0b11) << shift;
    }

    /**
     * @param motorByte a motor byte
     * @param motor     0 for M1 ... 3 for M4
     * @return that motor's direction: {@link #CCW}, {@link #CW}, or 0 when off (both bits count as off)
     */
    public static int direction(int motorByte, int motor) {
        int bits = (motorByte >> (motor * 2)) & 0b11;
        return bits == 0b11 ? 0 : bits;
    }

    /**
     * @param reply a 3-byte analog reply
     * @return its 10-bit analog value (big-endian)
     */
    public static int analog(byte[] reply) {
        return ((reply[1] & 0xFF) << 8 | (reply[2] & 0xFF)) & 0x3FF;
    }

    /**
     * @param port an input name, E1..E8
     * @return its bit number 0..7, or −1 if it is no digital input
     */
    public static int digitalInput(String port) {
        if (port.length() == 2 && port.charAt(0) == 'E' && port.charAt(1) >= '1' && port.charAt(1) <= '8') {
            return port.charAt(1) - '1';
        }
        return -1;
    }
}
