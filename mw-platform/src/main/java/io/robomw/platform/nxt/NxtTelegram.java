package io.robomw.platform.nxt;

import io.robomw.platform.brick.LittleEndian;
/**
 * The NXT's LCP direct-command telegrams, byte for byte (LEGO Bluetooth Developer Kit; firmware
 * {@code c_cmd.c}; shared/protocols §1). Every multi-byte field is little-endian; every offset a
 * driver reads or writes is a constant here.
 *
 * <pre>
 * serial/Bluetooth:  [len_lo][len_hi] [type][opcode][payload ...]     len = bytes after the prefix, at most 64
 * request:           [type][opcode][payload ...]          TYPE_OFFSET 0, OPCODE_OFFSET 1, PAYLOAD_OFFSET 2
 *                    type 0x00 direct, reply wanted    0x80 direct, no reply
 *                         0x01 system, reply wanted    0x81 system, no reply
 * reply:             [0x02][opcode][status][data ...]     STATUS_OFFSET 2, DATA_OFFSET 3; status 0x00 = success
 *
 * An output's state (SETOUTPUTSTATE's payload, GETOUTPUTSTATE's reply data), offsets OUT_*:
 *   +0 port u8 | +1 power s8 | +2 mode u8 | +3 regulation u8 | +4 turn_ratio s8 | +5 run_state u8 | +6 tacho_limit u32
 *   GETOUTPUTSTATE only: +10 tacho_count s32 | +14 block_tacho_count s32 | +18 rotation_count s32       (reply 25 bytes)
 * An input's values (GETINPUTVALUES's reply data), offsets IN_*:
 *   +0 port u8 | +1 valid u8 | +2 calibrated u8 | +3 type u8 | +4 mode u8 | +5 raw u16 | +7 normalized u16
 *   | +9 scaled s16 | +11 calibrated s16                                                                (reply 16 bytes)
 *
 * SETOUTPUTSTATE 0x04  an output's state (the first seven fields)
 * GETOUTPUTSTATE 0x06  port u8  -> an output's state, and its counts
 * SETINPUTMODE   0x05  port u8, sensor_type u8, sensor_mode u8
 * GETINPUTVALUES 0x07  port u8  -> an input's values
 * LSWRITE        0x0F  port u8, tx_len u8, rx_len u8, tx_data[tx_len]
 * LSGETSTATUS    0x0E  port u8  -> bytes_ready u8                                              (4 bytes)
 * LSREAD         0x10  port u8  -> bytes_read u8, data[16]                                     (20 bytes)
 * GETBATTERYLEVEL 0x0B          -> millivolts u16                                              (5 bytes)
 * KEEPALIVE      0x0D           -> sleep time limit u32, ms                                    (7 bytes)
 * RESETMOTORPOSITION 0x0A  port u8, relative bool (1: block tacho count, 0: rotation count)
 * UPDATE_RESET_COUNT 0x21  port u8   (tacho count and tacho-limit target; firmware 1.29 and later)
 * </pre>
 *
 * Stateless; the encoders return the telegram without its length prefix.
 */
public final class NxtTelegram {

    /** Longest telegram, without the length prefix. */
    public static final int MAX_LENGTH = 64;

    /** Direct command, reply wanted. */
    public static final int DIRECT = 0x00;
    /** Direct command, no reply. */
    public static final int DIRECT_NO_REPLY = 0x80;
    /** System command, reply wanted. */
    public static final int SYSTEM = 0x01;
    /** System command, no reply. */
    public static final int SYSTEM_NO_REPLY = 0x81;
    /** A reply. */
    public static final int REPLY = 0x02;

    /** Direct-command opcodes. */
    public static final int PLAYTONE = 0x03;
    /** Sets a motor's output. */
    public static final int SETOUTPUTSTATE = 0x04;
    /** Sets an input port's sensor type and mode. */
    public static final int SETINPUTMODE = 0x05;
    /** Reads a motor's state and counters. */
    public static final int GETOUTPUTSTATE = 0x06;
    /** Reads an input port. */
    public static final int GETINPUTVALUES = 0x07;
    /** Resets an input's scaled value. */
    public static final int RESETINPUTSCALEDVALUE = 0x08;
    /** Writes to a mailbox. */
    public static final int MESSAGEWRITE = 0x09;
    /** Resets a motor's counters. */
    public static final int RESETMOTORPOSITION = 0x0A;
    /** Reads the battery voltage. */
    public static final int GETBATTERYLEVEL = 0x0B;
    /** Stops sound. */
    public static final int STOPSOUNDPLAYBACK = 0x0C;
    /** Keeps the brick awake. */
    public static final int KEEPALIVE = 0x0D;
    /** Polls an I²C transaction. */
    public static final int LSGETSTATUS = 0x0E;
    /** Starts an I²C transaction. */
    public static final int LSWRITE = 0x0F;
    /** Reads an I²C transaction's answer. */
    public static final int LSREAD = 0x10;
    /** Reads the running program's name. */
    public static final int GETCURRENTPROGRAMNAME = 0x11;
    /**
     * Zeroes a motor's tacho count and the target its tacho limits add up to ({@code c_cmd.c}
     * RC_UPDATE_RESET_COUNT, flag UPDATE_RESET_COUNT; LEGO firmware 1.29 and later: earlier
     * firmware answers 0xBE).
     */
    public static final int UPDATE_RESET_COUNT = 0x21;

    /** SETOUTPUTSTATE's port for all three outputs at once. */
    public static final int ALL_OUTPUTS = 0xFF;

    /** Reply lengths (without the prefix), by opcode. */
    public static final int GETOUTPUTSTATE_REPLY = 25;
    /** Length of a GETINPUTVALUES reply. */
    public static final int GETINPUTVALUES_REPLY = 16;
    /** Length of an LSGETSTATUS reply. */
    public static final int LSGETSTATUS_REPLY = 4;
    /** Length of an LSREAD reply. */
    public static final int LSREAD_REPLY = 20;
    /** Length of a GETBATTERYLEVEL reply. */
    public static final int GETBATTERYLEVEL_REPLY = 5;
    /** Length of a KEEPALIVE reply. */
    public static final int KEEPALIVE_REPLY = 7;
    /** Length of a reply that carries only a status. */
    public static final int STATUS_REPLY = 3;

    /** Offset of the type byte in a telegram or reply. */
    public static final int TYPE_OFFSET = 0;
    /** Offset of the opcode in a telegram or reply. */
    public static final int OPCODE_OFFSET = 1;
    /** Offset of a request's payload. */
    public static final int PAYLOAD_OFFSET = 2;
    /** Offset of the status byte in a reply. */
    public static final int STATUS_OFFSET = 2;
    /** Offset of a reply's data, after its status. */
    public static final int DATA_OFFSET = 3;

    /** An output's state, from SETOUTPUTSTATE's payload or GETOUTPUTSTATE's reply data: the port. */
    public static final int OUT_PORT = 0;
    /** ...the power, s8. */
    public static final int OUT_POWER = 1;
    /** ...the mode bits. */
    public static final int OUT_MODE = 2;
    /** ...the regulation mode. */
    public static final int OUT_REGULATION = 3;
    /** ...the turn ratio, s8. */
    public static final int OUT_TURN_RATIO = 4;
    /** ...the run state. */
    public static final int OUT_RUN_STATE = 5;
    /** ...the tacho limit, u32. */
    public static final int OUT_TACHO_LIMIT = 6;
    /** GETOUTPUTSTATE only: the tacho count, s32 (since the last UPDATE_RESET_COUNT). */
    public static final int OUT_TACHO_COUNT = 10;
    /** GETOUTPUTSTATE only: the block tacho count, s32 (the synchronised pair's). */
    public static final int OUT_BLOCK_TACHO_COUNT = 14;
    /** GETOUTPUTSTATE only: the rotation count, s32 (the encoder, since RESETMOTORPOSITION absolute). */
    public static final int OUT_ROTATION_COUNT = 18;

    /** An input's values, in GETINPUTVALUES's reply data: the port. */
    public static final int IN_PORT = 0;
    /** ...whether the values are valid (0 until the firmware has set the sensor up after SETINPUTMODE). */
    public static final int IN_VALID = 1;
    /** ...the sensor type the port is set up for ({@link #TYPE_NO_SENSOR} on a brick that has just started). */
    public static final int IN_TYPE = 3;
    /** ...the sensor mode the port is set up for. */
    public static final int IN_MODE = 4;
    /** ...the raw A/D value, u16. */
    public static final int IN_RAW = 5;
    /** ...the normalized value 0..1023, u16. */
    public static final int IN_NORMALIZED = 7;
    /** ...the scaled value (by the sensor mode), s16. */
    public static final int IN_SCALED = 9;

    /** LSGETSTATUS's reply data: the bytes ready, u8. */
    public static final int LS_BYTES_READY = 0;
    /** LSREAD's reply data: the bytes read, u8, then the 16 data bytes. */
    public static final int LS_BYTES_READ = 0;
    /** LSREAD's reply data: the first data byte. */
    public static final int LS_DATA = 1;
    /** GETBATTERYLEVEL's reply data: millivolts, u16. */
    public static final int BATTERY_MILLIVOLTS = 0;
    /** KEEPALIVE's reply data: the sleep time limit, ms, u32. */
    public static final int SLEEP_LIMIT_MILLIS = 0;

    /** Motor mode bits. */
    public static final int MODE_MOTORON = 0x01;
    /** Brake when power is 0. */
    public static final int MODE_BRAKE = 0x02;
    /** Use the regulation mode. */
    public static final int MODE_REGULATED = 0x04;
    /** Regulation: none. */
    public static final int REGULATION_IDLE = 0;
    /** Regulation: constant speed. */
    public static final int REGULATION_SPEED = 1;
    /** Regulation: two motors in step. */
    public static final int REGULATION_SYNC = 2;
    /** Run state: idle. */
    public static final int RUN_IDLE = 0x00;
    /** Run state: running. */
    public static final int RUN_RUNNING = 0x20;

    /** Sensor types. */
    public static final int TYPE_NO_SENSOR = 0x00;
    /** A switch (touch sensor). */
    public static final int TYPE_SWITCH = 0x01;
    /** Light sensor with its lamp on. */
    public static final int TYPE_LIGHT_ACTIVE = 0x05;
    /** Light sensor with its lamp off. */
    public static final int TYPE_LIGHT_INACTIVE = 0x06;
    /** Sound sensor, dB. */
    public static final int TYPE_SOUND_DB = 0x07;
    /** I²C, 9 V (ultrasonic sensor). */
    public static final int TYPE_LOWSPEED_9V = 0x0B;
    /** Colour sensor, full colour. */
    public static final int TYPE_COLORFULL = 0x0D;
    /** Sensor mode: raw. */
    public static final int MODE_RAW = 0x00;
    /** Sensor mode: boolean. */
    public static final int MODE_BOOLEAN = 0x20;
    /** Sensor mode: percent of full scale. */
    public static final int MODE_PCTFULLSCALE = 0x80;

    /** The ultrasonic sensor's I²C address. */
    public static final int ULTRASONIC_ADDRESS = 0x02;
    /** Its first measurement register (centimetres). */
    public static final int ULTRASONIC_DISTANCE = 0x42;

    /** Motor speed at power 100, regulated, degrees per second: shared by driver and emulator. */
    public static final double DEGREES_PER_SECOND_AT_FULL_POWER = 900;

    private NxtTelegram() {
    }

    /**
     * @param reply whether a reply is wanted
     * @param state the output's new state
     * @return SETOUTPUTSTATE
     */
    public static byte[] setOutputState(boolean reply, OutputState state) {
        byte[] t = header(reply, SETOUTPUTSTATE, 10);
        t[PAYLOAD_OFFSET + OUT_PORT] = (byte) state.port();
        t[PAYLOAD_OFFSET + OUT_POWER] = (byte) state.power();
        t[PAYLOAD_OFFSET + OUT_MODE] = (byte) state.modeBits();
        t[PAYLOAD_OFFSET + OUT_REGULATION] = (byte) state.regulation().code();
        t[PAYLOAD_OFFSET + OUT_TURN_RATIO] = (byte) state.turnRatio();
        t[PAYLOAD_OFFSET + OUT_RUN_STATE] = (byte) state.runState().code();
        LittleEndian.putU32(t, PAYLOAD_OFFSET + OUT_TACHO_LIMIT, state.tachoLimit());
        return t;
    }

    /**
     * A GETOUTPUTSTATE reply: the output's state and its three counts.
     *
     * @param state           the state, as SETOUTPUTSTATE would set it
     * @param tachoCount      degrees since the last UPDATE_RESET_COUNT
     * @param blockTachoCount degrees since the last RESETMOTORPOSITION relative
     * @param rotationCount   degrees since the last RESETMOTORPOSITION absolute: the encoder
     */
    public record OutputReading(OutputState state, int tachoCount, int blockTachoCount, int rotationCount) {
    }

    /**
     * @param reply a successful GETOUTPUTSTATE reply ({@value #GETOUTPUTSTATE_REPLY} bytes, without the prefix)
     * @return what it reports
     * @throws IllegalArgumentException naming the field if the reply is too short or carries a code
     *                                  the firmware does not have
     */
    public static OutputReading outputReading(byte[] reply) {
        if (reply.length < GETOUTPUTSTATE_REPLY) {
            throw new IllegalArgumentException("a GETOUTPUTSTATE reply is " + GETOUTPUTSTATE_REPLY + " bytes, got " + reply.length);
        }
        int d = DATA_OFFSET;
        OutputState state = new OutputState(reply[d + OUT_PORT] & 0xFF, reply[d + OUT_POWER],
                OutputState.Mode.fromBits(reply[d + OUT_MODE] & 0xFF), OutputState.Regulation.fromCode(reply[d + OUT_REGULATION] & 0xFF),
                reply[d + OUT_TURN_RATIO], OutputState.RunState.fromCode(reply[d + OUT_RUN_STATE] & 0xFF), LittleEndian.u32(reply, d + OUT_TACHO_LIMIT));
        return new OutputReading(state, LittleEndian.s32(reply, d + OUT_TACHO_COUNT), LittleEndian.s32(reply, d + OUT_BLOCK_TACHO_COUNT),
                LittleEndian.s32(reply, d + OUT_ROTATION_COUNT));
    }

    /**
     * @param telegramOrReply a telegram or a reply, without its length prefix
     * @return its opcode
     */
    public static int opcode(byte[] telegramOrReply) {
        return telegramOrReply[OPCODE_OFFSET] & 0xFF;
    }

    /**
     * @param reply a reply, without its length prefix
     * @return its status byte ({@link NxtStatus})
     */
    public static int status(byte[] reply) {
        return reply[STATUS_OFFSET] & 0xFF;
    }

    /**
     * @param port the motor port
     * @return GETOUTPUTSTATE
     */
    public static byte[] getOutputState(int port) {
        byte[] t = header(true, GETOUTPUTSTATE, 1);
        t[PAYLOAD_OFFSET] = (byte) port;
        return t;
    }

    /**
     * @param reply    whether a reply is wanted
     * @param port     the motor port
     * @param relative true resets the block tacho count, false the rotation count
     * @return RESETMOTORPOSITION
     */
    public static byte[] resetMotorPosition(boolean reply, int port, boolean relative) {
        byte[] t = header(reply, RESETMOTORPOSITION, 2);
        t[PAYLOAD_OFFSET] = (byte) port;
        t[PAYLOAD_OFFSET + 1] = (byte) (relative ? 1 : 0);
        return t;
    }

    /**
     * @param reply whether a reply is wanted
     * @param port  the input port 0..3
     * @param type  the sensor type
     * @param mode  the sensor mode
     * @return SETINPUTMODE
     */
    public static byte[] setInputMode(boolean reply, int port, int type, int mode) {
        byte[] t = header(reply, SETINPUTMODE, 3);
        t[PAYLOAD_OFFSET] = (byte) port;
        t[PAYLOAD_OFFSET + 1] = (byte) type;
        t[PAYLOAD_OFFSET + 2] = (byte) mode;
        return t;
    }

    /**
     * @param port the input port
     * @return GETINPUTVALUES
     */
    public static byte[] getInputValues(int port) {
        byte[] t = header(true, GETINPUTVALUES, 1);
        t[PAYLOAD_OFFSET] = (byte) port;
        return t;
    }

    /**
     * @param reply whether a reply is wanted
     * @param port  the motor port
     * @return UPDATE_RESET_COUNT
     */
    public static byte[] updateResetCount(boolean reply, int port) {
        byte[] t = header(reply, UPDATE_RESET_COUNT, 1);
        t[PAYLOAD_OFFSET] = (byte) port;
        return t;
    }

    /**
     * @param reply  whether a reply is wanted
     * @param port   the input port
     * @param rxLength bytes to read back
     * @param tx     bytes to write, at most 16
     * @return LSWRITE
     */
    public static byte[] lsWrite(boolean reply, int port, int rxLength, byte... tx) {
        if (tx.length > 16 || rxLength > 16) {
            throw new IllegalArgumentException("an I²C transaction moves at most 16 bytes each way, got tx=" + tx.length + " rx=" + rxLength);
        }
        byte[] t = header(reply, LSWRITE, 3 + tx.length);
        t[PAYLOAD_OFFSET] = (byte) port;
        t[PAYLOAD_OFFSET + 1] = (byte) tx.length;
        t[PAYLOAD_OFFSET + 2] = (byte) rxLength;
        System.arraycopy(tx, 0, t, PAYLOAD_OFFSET + 3, tx.length);
        return t;
    }

    /**
     * @param port the input port
     * @return LSGETSTATUS
     */
    public static byte[] lsGetStatus(int port) {
        byte[] t = header(true, LSGETSTATUS, 1);
        t[PAYLOAD_OFFSET] = (byte) port;
        return t;
    }

    /**
     * @param port the input port
     * @return LSREAD
     */
    public static byte[] lsRead(int port) {
        byte[] t = header(true, LSREAD, 1);
        t[PAYLOAD_OFFSET] = (byte) port;
        return t;
    }

    /** @return GETBATTERYLEVEL */
    public static byte[] getBatteryLevel() {
        return header(true, GETBATTERYLEVEL, 0);
    }

    /** @return KEEPALIVE */
    public static byte[] keepAlive() {
        return header(true, KEEPALIVE, 0);
    }

    /**
     * @param reply      whether a reply is wanted
     * @param hertz      frequency
     * @param millis     duration
     * @return PLAYTONE
     */
    public static byte[] playTone(boolean reply, int hertz, int millis) {
        byte[] t = header(reply, PLAYTONE, 4);
        LittleEndian.putU16(t, PAYLOAD_OFFSET, hertz);
        LittleEndian.putU16(t, PAYLOAD_OFFSET + 2, millis);
        return t;
    }

    private static byte[] header(boolean reply, int opcode, int payload) {
        byte[] t = new byte[PAYLOAD_OFFSET + payload];
        t[TYPE_OFFSET] = (byte) (reply ? DIRECT : DIRECT_NO_REPLY);
        t[OPCODE_OFFSET] = (byte) opcode;
        return t;
    }

    /**
     * @param telegram a telegram
     * @return it with its 2-byte little-endian length prefix
     */
    public static byte[] withLengthPrefix(byte[] telegram) {
        byte[] out = new byte[telegram.length + 2];
        out[0] = (byte) telegram.length;
        out[1] = (byte) (telegram.length >> 8);
        System.arraycopy(telegram, 0, out, 2, telegram.length);
        return out;
    }

    /**
     * @param opcode an opcode
     * @return its name, for messages
     */
    public static String name(int opcode) {
        return switch (opcode) {
            case PLAYTONE -> "PLAYTONE";
            case SETOUTPUTSTATE -> "SETOUTPUTSTATE";
            case SETINPUTMODE -> "SETINPUTMODE";
            case GETOUTPUTSTATE -> "GETOUTPUTSTATE";
            case GETINPUTVALUES -> "GETINPUTVALUES";
            case RESETINPUTSCALEDVALUE -> "RESETINPUTSCALEDVALUE";
            case MESSAGEWRITE -> "MESSAGEWRITE";
            case RESETMOTORPOSITION -> "RESETMOTORPOSITION";
            case GETBATTERYLEVEL -> "GETBATTERYLEVEL";
            case STOPSOUNDPLAYBACK -> "STOPSOUNDPLAYBACK";
            case KEEPALIVE -> "KEEPALIVE";
            case LSGETSTATUS -> "LSGETSTATUS";
            case LSWRITE -> "LSWRITE";
            case LSREAD -> "LSREAD";
            case GETCURRENTPROGRAMNAME -> "GETCURRENTPROGRAMNAME";
            case UPDATE_RESET_COUNT -> "UPDATE_RESET_COUNT";
            default -> String.format("opcode 0x%02X", opcode);
        };
    }
}
