package io.robomw.platform.rcx;

import java.util.Arrays;

/**
 * The LEGO RCX's packets on its infra-red link (standard RIS 1.x/2.0 firmware), as the serial IR
 * tower carries them at 2400 baud, 8 data bits, odd parity, 1 stop bit (protocols §3; NQC's
 * {@code rcxlib/RCX_PipeTransport.cpp}, Kekoa Proudfoot's opcode reference). Every byte after the
 * header is followed by its complement; the checksum is the sum of the opcode and the data bytes
 * (not their complements, not the header), modulo 256:
 *
 * <pre>
 * offset 0   55 FF 00          header
 *        3   op  ~op           opcode (bit 3, 0x08, may be the toggle bit)
 *        5   d1  ~d1 ...       data bytes, each with its complement
 *        5+2n cs ~cs           cs = (op + d1 + ... + dn) &amp; 0xFF
 * reply:     55 FF 00  ~op op  r1 ~r1 ... cs ~cs        the reply opcode is the complement of the
 *                                                       request's, toggle bit included
 * </pre>
 *
 * The serial tower hears its own transmission: the host reads an exact echo of every packet it
 * sent before the brick's reply. The brick takes a packet whose opcode byte equals the previous
 * one's as a retransmission; senders flip the toggle bit when they send the same opcode twice in a
 * row (as NQC does).
 *
 * <table>
 *   <caption>Opcodes used (request, data bytes; reply data bytes)</caption>
 *   <tr><th>op</th><th>name</th><th>request data</th><th>reply data</th></tr>
 *   <tr><td>10</td><td>Alive</td><td>–</td><td>–</td></tr>
 *   <tr><td>12</td><td>Get value</td><td>source, argument</td><td>value s16 LE</td></tr>
 *   <tr><td>13</td><td>Set motor power</td><td>motors, source (2 constant), power 0..7</td><td>–</td></tr>
 *   <tr><td>15</td><td>Get versions</td><td>key 01 03 05 07 0B</td><td>ROM u16, u16, firmware u16, u16 (big-endian)</td></tr>
 *   <tr><td>21</td><td>Set motor on/off</td><td>motors | 0x80 on, | 0x40 off (brake), | 0x00 float</td><td>–</td></tr>
 *   <tr><td>23</td><td>Play tone</td><td>frequency u16 LE, duration (1/100 s)</td><td>–</td></tr>
 *   <tr><td>30</td><td>Get battery</td><td>–</td><td>millivolts u16 LE</td></tr>
 *   <tr><td>32</td><td>Set sensor type</td><td>sensor 0..2, type</td><td>–</td></tr>
 *   <tr><td>42</td><td>Set sensor mode</td><td>sensor 0..2, slope | mode</td><td>–</td></tr>
 *   <tr><td>50</td><td>Stop all tasks</td><td>–</td><td>–</td></tr>
 *   <tr><td>51</td><td>Play sound</td><td>sound 0..5</td><td>–</td></tr>
 *   <tr><td>E1</td><td>Set motor direction</td><td>motors | 0x80 forward, | 0x40 flip, | 0x00 reverse</td><td>–</td></tr>
 * </table>
 *
 * <p>Stateless. Decoders throw {@link IllegalArgumentException} saying what is wrong with the
 * bytes.
 */
public final class RcxPacket {

    /** The header every packet starts with. */
    public static final byte[] HEADER = {0x55, (byte) 0xFF, 0x00};
    /** Bytes of the header. */
    public static final int HEADER_LENGTH = 3;
    /** The toggle bit of an opcode. */
    public static final int TOGGLE = 0x08;

    /** Alive. */
    public static final int ALIVE = 0x10;
    /** Get value. */
    public static final int GET_VALUE = 0x12;
    /** Set motor power. */
    public static final int SET_MOTOR_POWER = 0x13;
    /** Get versions. */
    public static final int GET_VERSIONS = 0x15;
    /** Set motor on/off. */
    public static final int SET_MOTOR_ON_OFF = 0x21;
    /** Play tone. */
    public static final int PLAY_TONE = 0x23;
    /** Get battery. */
    public static final int GET_BATTERY = 0x30;
    /** Set sensor type. */
    public static final int SET_SENSOR_TYPE = 0x32;
    /** Set sensor mode. */
    public static final int SET_SENSOR_MODE = 0x42;
    /** Stop all tasks. */
    public static final int STOP_ALL_TASKS = 0x50;
    /** Play sound. */
    public static final int PLAY_SOUND = 0x51;
    /** Set motor direction. */
    public static final int SET_MOTOR_DIRECTION = 0xE1;

    /** Motor bits: output A. */
    public static final int MOTOR_A = 0x01;
    /** Output B. */
    public static final int MOTOR_B = 0x02;
    /** Output C. */
    public static final int MOTOR_C = 0x04;
    /** Set motor on/off: on. */
    public static final int ON = 0x80;
    /** Set motor on/off: off, braking. */
    public static final int OFF = 0x40;
    /** Set motor on/off: float (coast). */
    public static final int FLOAT = 0x00;
    /** Set motor direction: forward. */
    public static final int FORWARD = 0x80;
    /** Set motor direction: reverse. */
    public static final int REVERSE = 0x00;
    /** Set motor direction: flip. */
    public static final int FLIP = 0x40;

    /** Value sources (Get value, Set motor power): a variable. */
    public static final int SOURCE_VARIABLE = 0;
    /** A timer, 1/100 s. */
    public static final int SOURCE_TIMER = 1;
    /** A constant (Set motor power only). */
    public static final int SOURCE_CONSTANT = 2;
    /** A motor's state: bits 0-2 power, 0x08 reverse, 0x40 off, 0x80 on. */
    public static final int SOURCE_MOTOR_STATE = 3;
    /** A sensor's value in its mode. */
    public static final int SOURCE_SENSOR_VALUE = 9;
    /** A sensor's type. */
    public static final int SOURCE_SENSOR_TYPE = 10;
    /** A sensor's mode. */
    public static final int SOURCE_SENSOR_MODE = 11;
    /** A sensor's raw value, 0..1023. */
    public static final int SOURCE_SENSOR_RAW = 12;
    /** A sensor's boolean value. */
    public static final int SOURCE_SENSOR_BOOLEAN = 13;

    /** Sensor type: raw. */
    public static final int TYPE_RAW = 0;
    /** Sensor type: touch. */
    public static final int TYPE_TOUCH = 1;
    /** Sensor type: temperature. */
    public static final int TYPE_TEMPERATURE = 2;
    /** Sensor type: light (the sensor is powered). */
    public static final int TYPE_LIGHT = 3;
    /** Sensor type: rotation (powered, 16 counts per turn). */
    public static final int TYPE_ROTATION = 4;
    /** Sensor mode: raw 0..1023. */
    public static final int MODE_RAW = 0x00;
    /** Sensor mode: boolean. */
    public static final int MODE_BOOLEAN = 0x20;
    /** Sensor mode: transition count. */
    public static final int MODE_EDGE = 0x40;
    /** Sensor mode: pulse count. */
    public static final int MODE_PULSE = 0x60;
    /** Sensor mode: percent of full scale. */
    public static final int MODE_PERCENT = 0x80;
    /** Sensor mode: degrees Celsius. */
    public static final int MODE_CELSIUS = 0xA0;
    /** Sensor mode: degrees Fahrenheit. */
    public static final int MODE_FAHRENHEIT = 0xC0;
    /** Sensor mode: angle (rotation counts). */
    public static final int MODE_ANGLE = 0xE0;

    /** The key Get versions wants. */
    public static final byte[] VERSIONS_KEY = {0x01, 0x03, 0x05, 0x07, 0x0B};

    private RcxPacket() {
    }

    /**
     * @param opcode an opcode, with or without its toggle bit
     * @return how many data bytes its request carries, or -1 if it is not an opcode this codec knows
     */
    public static int requestDataLength(int opcode) {
        return switch (opcode & ~TOGGLE & 0xFF) {
            case ALIVE, GET_BATTERY, STOP_ALL_TASKS -> 0;
            case SET_MOTOR_ON_OFF, SET_MOTOR_DIRECTION, PLAY_SOUND -> 1;
            case GET_VALUE, SET_SENSOR_TYPE, SET_SENSOR_MODE -> 2;
            case SET_MOTOR_POWER, PLAY_TONE -> 3;
            case GET_VERSIONS -> 5;
            default -> -1;
        };
    }

    /**
     * @param opcode a request opcode, with or without its toggle bit
     * @return how many data bytes its reply carries, or -1 if it is not an opcode this codec knows
     */
    public static int replyDataLength(int opcode) {
        return switch (opcode & ~TOGGLE & 0xFF) {
            case GET_VALUE, GET_BATTERY -> 2;
            case GET_VERSIONS -> 8;
            default -> requestDataLength(opcode) < 0 ? -1 : 0;
        };
    }

    /**
     * @param dataBytes data bytes in a packet
     * @return the packet's length on the wire
     */
    public static int wireLength(int dataBytes) {
        return HEADER_LENGTH + 2 + 2 * dataBytes + 2;
    }

    /**
     * Encodes a packet.
     *
     * @param opcode the opcode byte (a request's, with its toggle bit, or a reply's)
     * @param data   its data bytes
     * @return the bytes on the wire
     */
    public static byte[] encode(int opcode, byte... data) {
        byte[] out = new byte[wireLength(data.length)];
        System.arraycopy(HEADER, 0, out, 0, HEADER_LENGTH);
        int at = HEADER_LENGTH;
        int sum = opcode & 0xFF;
        out[at++] = (byte) opcode;
        out[at++] = (byte) ~opcode;
        for (byte d : data) {
            out[at++] = d;
            out[at++] = (byte) ~d;
            sum += d & 0xFF;
        }
        out[at++] = (byte) sum;
        out[at] = (byte) ~sum;
        return out;
    }

    /**
     * @param request a request opcode byte, toggle bit included
     * @return the opcode byte its reply carries
     */
    public static int replyOpcode(int request) {
        return ~request & 0xFF;
    }

    /**
     * Decodes a packet: checks the header, every complement and the checksum.
     *
     * @param packet the bytes of one whole packet
     * @return its opcode byte and data bytes
     * @throws IllegalArgumentException naming what is wrong
     */
    public static Decoded decode(byte[] packet) {
        if (packet.length < wireLength(0) || (packet.length - wireLength(0)) % 2 != 0) {
            throw new IllegalArgumentException("an RCX packet is 7 + 2n bytes long, got " + packet.length + ": " + hex(packet));
        }
        for (int i = 0; i < HEADER_LENGTH; i++) {
            if (packet[i] != HEADER[i]) {
                throw new IllegalArgumentException("an RCX packet starts 55 FF 00, got " + hex(Arrays.copyOf(packet, HEADER_LENGTH)));
            }
        }
        int pairs = (packet.length - HEADER_LENGTH) / 2;
        byte[] values = new byte[pairs];
        for (int i = 0; i < pairs; i++) {
            int b = packet[HEADER_LENGTH + 2 * i] & 0xFF;
            int c = packet[HEADER_LENGTH + 2 * i + 1] & 0xFF;
            if ((b ^ c) != 0xFF) {
                throw new IllegalArgumentException(String.format("byte %d of the RCX packet, %02X, is followed by %02X, not its complement %02X: %s",
                        HEADER_LENGTH + 2 * i, b, c, ~b & 0xFF, hex(packet)));
            }
            values[i] = (byte) b;
        }
        int sum = 0;
        for (int i = 0; i < pairs - 1; i++) {
            sum += values[i] & 0xFF;
        }
        int checksum = values[pairs - 1] & 0xFF;
        if ((sum & 0xFF) != checksum) {
            throw new IllegalArgumentException(String.format("RCX packet checksum is %02X, its bytes add up to %02X: %s", checksum, sum & 0xFF, hex(packet)));
        }
        return new Decoded(values[0] & 0xFF, Arrays.copyOfRange(values, 1, pairs - 1));
    }

    /**
     * A decoded packet.
     *
     * @param opcode the opcode byte
     * @param data   the data bytes
     */
    public record Decoded(int opcode, byte[] data) {
        /** Copies the data. */
        public Decoded {
            data = data.clone();
        }

        /** @return the first two data bytes as a signed 16-bit little-endian value */
        public int s16() {
            if (data.length < 2) {
                throw new IllegalArgumentException("the RCX reply carries " + data.length + " data bytes, not a 16-bit value");
            }
            return (short) ((data[0] & 0xFF) | (data[1] & 0xFF) << 8);
        }

        /** @return the first two data bytes as an unsigned 16-bit little-endian value */
        public int u16() {
            return s16() & 0xFFFF;
        }
    }

    // ---- requests ----

    /**
     * @param source   a value source
     * @param argument its argument (sensor 0..2, variable 0..31 ...)
     * @return the data of Get value
     */
    public static byte[] getValue(int source, int argument) {
        return new byte[]{(byte) source, (byte) argument};
    }

    /**
     * @param motors motor bits
     * @param power  0..7
     * @return the data of Set motor power, with the power as a constant
     */
    public static byte[] setMotorPower(int motors, int power) {
        if (power < 0 || power > 7) {
            throw new IllegalArgumentException("RCX motor power is 0..7, got " + power);
        }
        return new byte[]{(byte) motors, SOURCE_CONSTANT, (byte) power};
    }

    /**
     * @param motors motor bits
     * @param state  {@link #ON}, {@link #OFF} or {@link #FLOAT}
     * @return the data of Set motor on/off
     */
    public static byte[] setMotorOnOff(int motors, int state) {
        return new byte[]{(byte) (motors | state)};
    }

    /**
     * @param motors    motor bits
     * @param direction {@link #FORWARD}, {@link #REVERSE} or {@link #FLIP}
     * @return the data of Set motor direction
     */
    public static byte[] setMotorDirection(int motors, int direction) {
        return new byte[]{(byte) (motors | direction)};
    }

    /**
     * @param sensor 0..2
     * @param type   a sensor type
     * @return the data of Set sensor type
     */
    public static byte[] setSensorType(int sensor, int type) {
        return new byte[]{(byte) sensor, (byte) type};
    }

    /**
     * @param sensor 0..2
     * @param mode   slope | mode
     * @return the data of Set sensor mode
     */
    public static byte[] setSensorMode(int sensor, int mode) {
        return new byte[]{(byte) sensor, (byte) mode};
    }

    /**
     * @param hertz     frequency
     * @param hundredths duration, 1/100 s
     * @return the data of Play tone
     */
    public static byte[] playTone(int hertz, int hundredths) {
        return new byte[]{(byte) hertz, (byte) (hertz >> 8), (byte) hundredths};
    }

    /**
     * @param opcode an opcode byte
     * @return its name, for messages
     */
    public static String name(int opcode) {
        int op = opcode & 0xFF;
        int base = op & ~TOGGLE;
        if (requestDataLength(base) < 0 && requestDataLength(~op & 0xFF & ~TOGGLE) >= 0) {
            return "reply to " + name(~op & 0xFF);
        }
        return switch (base) {
            case ALIVE -> "Alive";
            case GET_VALUE -> "Get value";
            case SET_MOTOR_POWER -> "Set motor power";
            case GET_VERSIONS -> "Get versions";
            case SET_MOTOR_ON_OFF -> "Set motor on/off";
            case PLAY_TONE -> "Play tone";
            case GET_BATTERY -> "Get battery";
            case SET_SENSOR_TYPE -> "Set sensor type";
            case SET_SENSOR_MODE -> "Set sensor mode";
            case STOP_ALL_TASKS -> "Stop all tasks";
            case PLAY_SOUND -> "Play sound";
            case SET_MOTOR_DIRECTION -> "Set motor direction";
            default -> String.format("opcode 0x%02X", op);
        };
    }

    /**
     * @param bytes bytes
     * @return them in hex, for messages
     */
    public static String hex(byte[] bytes) {
        StringBuilder sb = new StringBuilder();
        for (byte b : bytes) {
            if (!sb.isEmpty()) {
                sb.append(' ');
            }
            sb.append(String.format("%02X", b & 0xFF));
        }
        return sb.toString();
    }
}
