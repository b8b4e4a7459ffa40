package io.robomw.platform.ft.txt;

import io.robomw.platform.brick.LittleEndian;
import java.nio.charset.StandardCharsets;
import java.util.Arrays;
import java.util.Objects;

/**
 * The fischertechnik TXT controller's online protocol on TCP port 65000, byte for byte, as the
 * client {@code ftrobopy} (v2.0.2, {@code ftrobopy.py}) and the server {@code ftrobopy_server}
 * ({@code src/ftrobopy_server.cpp}) implement it. Every message starts with a u32 message id; the
 * structs behind it are packed, and every multi-byte field is <b>little-endian</b>. Each request
 * has exactly one reply, of a fixed size.
 *
 * <pre>
 * request             id        bytes   reply                 id        bytes
 * queryStatus         DC21219A      4   status                BAC9723E     24
 * startOnline         163FF61D     68   startOnline ack       CA689F75      4
 * updateConfig        060EF27E     96   updateConfig ack      9689A68C      4
 * exchange (simple)   CC3597BA     60   exchange reply        4EEFAC41     80
 * stopOnline          9BE5082C      4   stopOnline ack        FBF600D2      4
 *
 * status        0 id u32 | 4 device name char[16], NUL padded | 20 firmware version u32 (0x04060600 = 4.6.6)
 * startOnline   0 id u32 | 4 name char[64], zeros
 * updateConfig  0 id u32 | 4 config_id s16 | 6 extension_id s16 (0 = the TXT itself) | 8 pgm_state_req u8
 *               9 old_FtTransfer u8 | 10 pad[2]
 *              12 motor u8[4]: 1 = M1..M4 drive a motor, 0 = O1..O8 are single outputs
 *              16 uni[8], 4 bytes each: mode u8 (0 voltage, 1 resistance or switch, 3 ultrasonic), digital u8, pad[2]
 *              48 cnt[4], 4 bytes each: mode u8, pad[3]
 *              64 motor_config s16[16]
 * exchange      0 id u32 | 4 pwm s16[8], 0..512: motor Mi forward = pwm[2i], reverse = pwm[2i+1]
 *              20 motor_sync s16[4] (0 = none, j = in step with Mj) | 28 motor_dist s16[4] (counter pulses, 0 = no limit)
 *              36 motor_cmd_id s16[4] (a changed id starts the distance command)
 *              44 counter_cmd_id s16[4] (a changed id resets counter Ci to 0)
 *              52 sound u16 | 54 sound_index u16 | 56 sound_repeat u16 | 58 pad[2]
 * reply         0 id u32 | 4 input s16[8], I1..I8 in the configured mode's unit (switch 0/1, mV, ohm, cm)
 *              20 counter_level s16[4] | 28 counter_value s16[4], pulses since the counter's last reset
 *              36 counter_cmd_id s16[4], the last reset done | 44 motor_cmd_id s16[4], the last distance command finished
 *              52 sound_cmd_id u16 | 54 ir[25]: 5 remotes x (4 s8 axes, u8 buttons) | 79 pad
 * </pre>
 *
 * Command ids count modulo 8 ({@link #CMD_ID_MASK}), as ftrobopy counts them. The compressed
 * exchange ({@code FBC56F98}), the camera (port 65001) and I²C (port 65002) messages are not used.
 *
 * <p>Stateless. Decoders throw {@link IllegalArgumentException} naming the length or id that is
 * wrong; a driver checks the reply id itself first, since a wrong id means the stream lost its
 * framing.
 */
public final class TxtProtocol {

    /** The TXT's command port. */
    public static final int TCP_PORT = 65000;
    /** The port ftrobopy's startOnline also connects to (I²C); not used by the driver. */
    public static final int I2C_TCP_PORT = 65002;

    /** queryStatus request id. */
    public static final long QUERY_STATUS = 0xDC21219AL;
    /** Its reply id. */
    public static final long QUERY_STATUS_REPLY = 0xBAC9723EL;
    /** startOnline request id. */
    public static final long START_ONLINE = 0x163FF61DL;
    /** Its reply id. */
    public static final long START_ONLINE_REPLY = 0xCA689F75L;
    /** updateConfig request id. */
    public static final long UPDATE_CONFIG = 0x060EF27EL;
    /** Its reply id. */
    public static final long UPDATE_CONFIG_REPLY = 0x9689A68CL;
    /** exchange (simple) request id. */
    public static final long EXCHANGE = 0xCC3597BAL;
    /** Its reply id. */
    public static final long EXCHANGE_REPLY = 0x4EEFAC41L;
    /** stopOnline request id. */
    public static final long STOP_ONLINE = 0x9BE5082CL;
    /** Its reply id. */
    public static final long STOP_ONLINE_REPLY = 0xFBF600D2L;

    /** Bytes of the message id that starts every message. */
    public static final int ID_LENGTH = 4;
    /** queryStatus request length. */
    public static final int QUERY_STATUS_LENGTH = ID_LENGTH;
    /** status reply length: id, name[16], version. */
    public static final int QUERY_STATUS_REPLY_LENGTH = 24;
    /** startOnline request length: id, name[64]. */
    public static final int START_ONLINE_LENGTH = 68;
    /** updateConfig request length. */
    public static final int UPDATE_CONFIG_LENGTH = 96;
    /** exchange request length. */
    public static final int EXCHANGE_LENGTH = 60;
    /** exchange reply length. */
    public static final int EXCHANGE_REPLY_LENGTH = 80;
    /** stopOnline request length. */
    public static final int STOP_ONLINE_LENGTH = ID_LENGTH;
    /** Length of the replies that carry only their id (startOnline, updateConfig, stopOnline). */
    public static final int ACK_LENGTH = ID_LENGTH;

    /** Motor outputs M1..M4. */
    public static final int MOTORS = 4;
    /** Single outputs O1..O8, two per motor output. */
    public static final int OUTPUTS = 8;
    /** Universal inputs I1..I8. */
    public static final int INPUTS = 8;
    /** Fast counters C1..C4. */
    public static final int COUNTERS = 4;
    /** The most a PWM value can be: full power. */
    public static final int PWM_MAX = 512;
    /** Command ids count modulo 8. */
    public static final int CMD_ID_MASK = 0x07;
    /** Bytes of the device name in the status reply. */
    public static final int DEVICE_NAME_LENGTH = 16;
    /** Bytes of infra-red remote state in the exchange reply. */
    public static final int IR_LENGTH = 25;

    /** status: device name offset. */
    public static final int STATUS_NAME_OFFSET = 4;
    /** status: firmware version offset. */
    public static final int STATUS_VERSION_OFFSET = 20;

    /** updateConfig: config_id offset (s16). */
    public static final int CONFIG_ID_OFFSET = 4;
    /** updateConfig: extension_id offset (s16). */
    public static final int CONFIG_EXTENSION_OFFSET = 6;
    /** updateConfig: pgm_state_req offset (u8). */
    public static final int CONFIG_PGM_STATE_OFFSET = 8;
    /** updateConfig: old_FtTransfer offset (u8). */
    public static final int CONFIG_OLD_TRANSFER_OFFSET = 9;
    /** updateConfig: motor[4] offset (u8 each). */
    public static final int CONFIG_MOTOR_OFFSET = 12;
    /** updateConfig: uni[8] offset, {@link #CONFIG_UNI_STRIDE} bytes each. */
    public static final int CONFIG_UNI_OFFSET = 16;
    /** updateConfig: bytes per universal input: mode, digital, pad[2]. */
    public static final int CONFIG_UNI_STRIDE = 4;
    /** updateConfig: cnt[4] offset, {@link #CONFIG_CNT_STRIDE} bytes each. */
    public static final int CONFIG_CNT_OFFSET = 48;
    /** updateConfig: bytes per counter: mode, pad[3]. */
    public static final int CONFIG_CNT_STRIDE = 4;
    /** updateConfig: motor_config[16] offset (s16 each). */
    public static final int CONFIG_MOTOR_CONFIG_OFFSET = 64;
    /** updateConfig: motor_config entries. */
    public static final int CONFIG_MOTOR_CONFIG_COUNT = 16;

    /** Universal input mode: voltage, mV (analog) or above 600 mV (digital). */
    public static final int MODE_VOLTAGE = 0;
    /** Universal input mode: resistance, ohm (analog) or a switch, 1 closed (digital). */
    public static final int MODE_RESISTANCE = 1;
    /** Universal input mode: the ultrasonic distance sensor, cm. */
    public static final int MODE_ULTRASONIC = 3;

    /** exchange: pwm[8] offset. */
    public static final int PWM_OFFSET = 4;
    /** exchange: motor_sync[4] offset. */
    public static final int MOTOR_SYNC_OFFSET = 20;
    /** exchange: motor_dist[4] offset. */
    public static final int MOTOR_DIST_OFFSET = 28;
    /** exchange: motor_cmd_id[4] offset. */
    public static final int MOTOR_CMD_ID_OFFSET = 36;
    /** exchange: counter_cmd_id[4] offset. */
    public static final int COUNTER_CMD_ID_OFFSET = 44;
    /** exchange: sound offset (u16). */
    public static final int SOUND_OFFSET = 52;
    /** exchange: sound_index offset (u16). */
    public static final int SOUND_INDEX_OFFSET = 54;
    /** exchange: sound_repeat offset (u16). */
    public static final int SOUND_REPEAT_OFFSET = 56;

    /** exchange reply: input[8] offset. */
    public static final int REPLY_INPUT_OFFSET = 4;
    /** exchange reply: counter_level[4] offset. */
    public static final int REPLY_COUNTER_LEVEL_OFFSET = 20;
    /** exchange reply: counter_value[4] offset. */
    public static final int REPLY_COUNTER_VALUE_OFFSET = 28;
    /** exchange reply: counter_cmd_id[4] offset. */
    public static final int REPLY_COUNTER_CMD_ID_OFFSET = 36;
    /** exchange reply: motor_cmd_id[4] offset. */
    public static final int REPLY_MOTOR_CMD_ID_OFFSET = 44;
    /** exchange reply: sound_cmd_id offset (u16). */
    public static final int REPLY_SOUND_CMD_ID_OFFSET = 52;
    /** exchange reply: ir[25] offset. */
    public static final int REPLY_IR_OFFSET = 54;

    private TxtProtocol() {
    }

    // ---- the message table ----

    /**
     * @param requestId a message id
     * @return the length of that request, id included, or -1 if it is not a request of the table
     */
    public static int requestLength(long requestId) {
        if (requestId == QUERY_STATUS) {
            return QUERY_STATUS_LENGTH;
        } else if (requestId == START_ONLINE) {
            return START_ONLINE_LENGTH;
        } else if (requestId == UPDATE_CONFIG) {
            return UPDATE_CONFIG_LENGTH;
        } else if (requestId == EXCHANGE) {
            return EXCHANGE_LENGTH;
        } else if (requestId == STOP_ONLINE) {
            return STOP_ONLINE_LENGTH;
        }
        return -1;
    }

    /**
     * @param requestId a request id of the table
     * @return the id of its reply
     * @throws IllegalArgumentException if the id is not a request of the table
     */
    public static long replyId(long requestId) {
        if (requestId == QUERY_STATUS) {
            return QUERY_STATUS_REPLY;
        } else if (requestId == START_ONLINE) {
            return START_ONLINE_REPLY;
        } else if (requestId == UPDATE_CONFIG) {
            return UPDATE_CONFIG_REPLY;
        } else if (requestId == EXCHANGE) {
            return EXCHANGE_REPLY;
        } else if (requestId == STOP_ONLINE) {
            return STOP_ONLINE_REPLY;
        }
        throw new IllegalArgumentException(String.format("message id 0x%08X is not a TXT request of the table", requestId));
    }

    /**
     * @param requestId a request id of the table
     * @return the length of its reply, id included
     * @throws IllegalArgumentException if the id is not a request of the table
     */
    public static int replyLength(long requestId) {
        if (requestId == QUERY_STATUS) {
            return QUERY_STATUS_REPLY_LENGTH;
        } else if (requestId == EXCHANGE) {
            return EXCHANGE_REPLY_LENGTH;
        } else if (requestId == START_ONLINE || requestId == UPDATE_CONFIG || requestId == STOP_ONLINE) {
            return ACK_LENGTH;
        }
        throw new IllegalArgumentException(String.format("message id 0x%08X is not a TXT request of the table", requestId));
    }

    /**
     * @param id a message id
     * @return its name, for messages
     */
    public static String name(long id) {
        if (id == QUERY_STATUS) {
            return "queryStatus";
        } else if (id == QUERY_STATUS_REPLY) {
            return "queryStatus reply";
        } else if (id == START_ONLINE) {
            return "startOnline";
        } else if (id == START_ONLINE_REPLY) {
            return "startOnline reply";
        } else if (id == UPDATE_CONFIG) {
            return "updateConfig";
        } else if (id == UPDATE_CONFIG_REPLY) {
            return "updateConfig reply";
        } else if (id == EXCHANGE) {
            return "exchange";
        } else if (id == EXCHANGE_REPLY) {
            return "exchange reply";
        } else if (id == STOP_ONLINE) {
            return "stopOnline";
        } else if (id == STOP_ONLINE_REPLY) {
            return "stopOnline reply";
        }
        return String.format("message 0x%08X", id);
    }

    /**
     * @param message a message, at least {@link #ID_LENGTH} bytes
     * @return its id, the unsigned little-endian u32 it starts with
     */
    public static long messageId(byte[] message) {
        if (message.length < ID_LENGTH) {
            throw new IllegalArgumentException("a TXT message starts with a 4-byte id, got " + message.length + " byte(s)");
        }
        return LittleEndian.u32(message, 0);
    }

    // ---- messages without fields ----

    /** @return queryStatus, 4 bytes */
    public static byte[] queryStatus() {
        return message(QUERY_STATUS, QUERY_STATUS_LENGTH);
    }

    /** @return startOnline, 68 bytes: the id and an empty name */
    public static byte[] startOnline() {
        return message(START_ONLINE, START_ONLINE_LENGTH);
    }

    /** @return stopOnline, 4 bytes */
    public static byte[] stopOnline() {
        return message(STOP_ONLINE, STOP_ONLINE_LENGTH);
    }

    /**
     * @param replyId {@link #START_ONLINE_REPLY}, {@link #UPDATE_CONFIG_REPLY} or {@link #STOP_ONLINE_REPLY}
     * @return the 4-byte reply that carries only its id
     */
    public static byte[] ack(long replyId) {
        if (replyId != START_ONLINE_REPLY && replyId != UPDATE_CONFIG_REPLY && replyId != STOP_ONLINE_REPLY) {
            throw new IllegalArgumentException(String.format("0x%08X is not the id of a TXT reply without fields", replyId));
        }
        return message(replyId, ACK_LENGTH);
    }

    private static byte[] message(long id, int length) {
        byte[] m = new byte[length];
        LittleEndian.putU32(m, 0, id);
        return m;
    }

    private static void check(byte[] message, long id, int length) {
        Objects.requireNonNull(message, "message");
        if (message.length != length) {
            throw new IllegalArgumentException(name(id) + " is " + length + " bytes, got " + message.length);
        }
        long got = LittleEndian.u32(message, 0);
        if (got != id) {
            throw new IllegalArgumentException(String.format("expected %s (id 0x%08X), got id 0x%08X", name(id), id, got));
        }
    }

    // ---- messages with fields ----

    /**
     * The queryStatus reply.
     *
     * @param deviceName the controller's name, at most 16 bytes of UTF-8
     * @param version    the firmware version, e.g. {@code 0x04060600} for 4.6.6
     */
    public record Status(String deviceName, long version) {

        /** Checks the name's length and the version's range. */
        public Status {
            Objects.requireNonNull(deviceName, "deviceName");
            if (deviceName.getBytes(StandardCharsets.UTF_8).length > DEVICE_NAME_LENGTH) {
                throw new IllegalArgumentException("the device name has room for " + DEVICE_NAME_LENGTH + " bytes, got '" + deviceName + "'");
            }
            if (version < 0 || version > 0xFFFF_FFFFL) {
                throw new IllegalArgumentException("the version is a u32, got " + version);
            }
        }

        /** @return the version as text, e.g. {@code 4.6.6} */
        public String versionText() {
            return String.format("%x.%x.%x", version >> 24, (version >> 16) & 0xFF, (version >> 8) & 0xFF);
        }

        /** @return the 24-byte reply */
        public byte[] encode() {
            byte[] m = message(QUERY_STATUS_REPLY, QUERY_STATUS_REPLY_LENGTH);
            byte[] name = deviceName.getBytes(StandardCharsets.UTF_8);
            System.arraycopy(name, 0, m, STATUS_NAME_OFFSET, name.length);
            LittleEndian.putU32(m, STATUS_VERSION_OFFSET, version);
            return m;
        }

        /**
         * @param reply a 24-byte status reply
         * @return its fields; the name ends at its first NUL, and a name that is not UTF-8 is read
         *         byte by byte, printable ASCII as it is and any other byte as '?' (so it keeps its 16
         *         bytes: replacement characters would not fit)
         */
        public static Status decode(byte[] reply) {
            check(reply, QUERY_STATUS_REPLY, QUERY_STATUS_REPLY_LENGTH);
            int end = STATUS_NAME_OFFSET;
            while (end < STATUS_NAME_OFFSET + DEVICE_NAME_LENGTH && reply[end] != 0) {
                end++;
            }
            int length = end - STATUS_NAME_OFFSET;
            String name;
            try {
                name = StandardCharsets.UTF_8.newDecoder().decode(java.nio.ByteBuffer.wrap(reply, STATUS_NAME_OFFSET, length)).toString();
            } catch (java.nio.charset.CharacterCodingException notUtf8) {
                StringBuilder b = new StringBuilder(length);
                for (int i = STATUS_NAME_OFFSET; i < end; i++) {
                    b.append(reply[i] >= 0x20 && reply[i] < 0x7F ? (char) reply[i] : '?');
                }
                name = b.toString();
            }
            return new Status(name, LittleEndian.u32(reply, STATUS_VERSION_OFFSET));
        }
    }

    /**
     * The updateConfig request (pgm_state_req and old_FtTransfer are 0, as ftrobopy sends them).
     *
     * @param configId     incremented by the client with every configuration
     * @param extensionId  0 for the TXT itself, 1..8 for extensions
     * @param motor        per motor output: 1 = motor, 0 = two single outputs ({@link #MOTORS} entries)
     * @param inputMode    per universal input: {@link #MODE_VOLTAGE}, {@link #MODE_RESISTANCE} or
     *                     {@link #MODE_ULTRASONIC} ({@link #INPUTS} entries)
     * @param inputDigital per universal input: 1 digital, 0 analog ({@link #INPUTS} entries)
     * @param counterMode  per counter ({@link #COUNTERS} entries; ftrobopy sends 1)
     * @param motorConfig  {@link #CONFIG_MOTOR_CONFIG_COUNT} entries (ftrobopy sends 0)
     */
    public record Config(int configId, int extensionId, int[] motor, int[] inputMode, int[] inputDigital, int[] counterMode,
                         int[] motorConfig) {

        /** Checks the array lengths and copies them. */
        public Config {
            motor = copy("motor", motor, MOTORS);
            inputMode = copy("inputMode", inputMode, INPUTS);
            inputDigital = copy("inputDigital", inputDigital, INPUTS);
            counterMode = copy("counterMode", counterMode, COUNTERS);
            motorConfig = copy("motorConfig", motorConfig, CONFIG_MOTOR_CONFIG_COUNT);
        }

        /** @return the 96-byte request */
        public byte[] encode() {
            byte[] m = message(UPDATE_CONFIG, UPDATE_CONFIG_LENGTH);
            LittleEndian.putU16(m, CONFIG_ID_OFFSET, configId);
            LittleEndian.putU16(m, CONFIG_EXTENSION_OFFSET, extensionId);
            for (int i = 0; i < MOTORS; i++) {
                m[CONFIG_MOTOR_OFFSET + i] = (byte) motor[i];
            }
            for (int i = 0; i < INPUTS; i++) {
                m[CONFIG_UNI_OFFSET + i * CONFIG_UNI_STRIDE] = (byte) inputMode[i];
                m[CONFIG_UNI_OFFSET + i * CONFIG_UNI_STRIDE + 1] = (byte) inputDigital[i];
            }
            for (int i = 0; i < COUNTERS; i++) {
                m[CONFIG_CNT_OFFSET + i * CONFIG_CNT_STRIDE] = (byte) counterMode[i];
            }
            putS16ArrayLe(m, CONFIG_MOTOR_CONFIG_OFFSET, motorConfig);
            return m;
        }

        /**
         * @param request a 96-byte updateConfig request
         * @return its fields
         */
        public static Config decode(byte[] request) {
            check(request, UPDATE_CONFIG, UPDATE_CONFIG_LENGTH);
            int[] motor = new int[MOTORS];
            for (int i = 0; i < MOTORS; i++) {
                motor[i] = request[CONFIG_MOTOR_OFFSET + i] & 0xFF;
            }
            int[] mode = new int[INPUTS];
            int[] digital = new int[INPUTS];
            for (int i = 0; i < INPUTS; i++) {
                mode[i] = request[CONFIG_UNI_OFFSET + i * CONFIG_UNI_STRIDE] & 0xFF;
                digital[i] = request[CONFIG_UNI_OFFSET + i * CONFIG_UNI_STRIDE + 1] & 0xFF;
            }
            int[] counter = new int[COUNTERS];
            for (int i = 0; i < COUNTERS; i++) {
                counter[i] = request[CONFIG_CNT_OFFSET + i * CONFIG_CNT_STRIDE] & 0xFF;
            }
            return new Config(LittleEndian.s16(request, CONFIG_ID_OFFSET), LittleEndian.s16(request, CONFIG_EXTENSION_OFFSET), motor, mode, digital, counter,
                    s16ArrayLe(request, CONFIG_MOTOR_CONFIG_OFFSET, CONFIG_MOTOR_CONFIG_COUNT));
        }

        @Override
        public int[] motor() {
            return motor.clone();
        }

        @Override
        public int[] inputMode() {
            return inputMode.clone();
        }

        @Override
        public int[] inputDigital() {
            return inputDigital.clone();
        }

        @Override
        public int[] counterMode() {
            return counterMode.clone();
        }

        @Override
        public int[] motorConfig() {
            return motorConfig.clone();
        }

        @Override
        public boolean equals(Object o) {
            return o instanceof Config c && configId == c.configId && extensionId == c.extensionId && Arrays.equals(motor, c.motor)
                    && Arrays.equals(inputMode, c.inputMode) && Arrays.equals(inputDigital, c.inputDigital)
                    && Arrays.equals(counterMode, c.counterMode) && Arrays.equals(motorConfig, c.motorConfig);
        }

        @Override
        public int hashCode() {
            return Objects.hash(configId, extensionId, Arrays.hashCode(motor), Arrays.hashCode(inputMode), Arrays.hashCode(inputDigital),
                    Arrays.hashCode(counterMode), Arrays.hashCode(motorConfig));
        }

        @Override
        public String toString() {
            return "Config[configId=" + configId + ", extensionId=" + extensionId + ", motor=" + Arrays.toString(motor) + ", inputMode="
                    + Arrays.toString(inputMode) + ", inputDigital=" + Arrays.toString(inputDigital) + ", counterMode="
                    + Arrays.toString(counterMode) + ", motorConfig=" + Arrays.toString(motorConfig) + "]";
        }
    }

    /**
     * The simple exchange request: the outputs and commands the client wants now.
     *
     * @param pwm          {@link #OUTPUTS} values 0..512; motor Mi forward = pwm[2i], reverse = pwm[2i+1]
     * @param motorSync    per motor: 0, or j to keep it in step with Mj
     * @param motorDist    per motor: counter pulses to turn after its command id changes, 0 = no limit
     * @param motorCmdId   per motor: a changed value starts a distance command
     * @param counterCmdId per counter: a changed value resets the counter to 0
     * @param sound        sound command id
     * @param soundIndex   sound to play, 0 = none
     * @param soundRepeat  how often, 0 = forever
     */
    public record Exchange(int[] pwm, int[] motorSync, int[] motorDist, int[] motorCmdId, int[] counterCmdId, int sound, int soundIndex,
                           int soundRepeat) {

        /** Checks the array lengths and copies them. */
        public Exchange {
            pwm = copy("pwm", pwm, OUTPUTS);
            motorSync = copy("motorSync", motorSync, MOTORS);
            motorDist = copy("motorDist", motorDist, MOTORS);
            motorCmdId = copy("motorCmdId", motorCmdId, MOTORS);
            counterCmdId = copy("counterCmdId", counterCmdId, COUNTERS);
        }

        /** @return the 60-byte request */
        public byte[] encode() {
            byte[] m = message(EXCHANGE, EXCHANGE_LENGTH);
            putS16ArrayLe(m, PWM_OFFSET, pwm);
            putS16ArrayLe(m, MOTOR_SYNC_OFFSET, motorSync);
            putS16ArrayLe(m, MOTOR_DIST_OFFSET, motorDist);
            putS16ArrayLe(m, MOTOR_CMD_ID_OFFSET, motorCmdId);
            putS16ArrayLe(m, COUNTER_CMD_ID_OFFSET, counterCmdId);
            LittleEndian.putU16(m, SOUND_OFFSET, sound);
            LittleEndian.putU16(m, SOUND_INDEX_OFFSET, soundIndex);
            LittleEndian.putU16(m, SOUND_REPEAT_OFFSET, soundRepeat);
            return m;
        }

        /**
         * @param request a 60-byte exchange request
         * @return its fields
         */
        public static Exchange decode(byte[] request) {
            check(request, EXCHANGE, EXCHANGE_LENGTH);
            return new Exchange(s16ArrayLe(request, PWM_OFFSET, OUTPUTS), s16ArrayLe(request, MOTOR_SYNC_OFFSET, MOTORS),
                    s16ArrayLe(request, MOTOR_DIST_OFFSET, MOTORS), s16ArrayLe(request, MOTOR_CMD_ID_OFFSET, MOTORS),
                    s16ArrayLe(request, COUNTER_CMD_ID_OFFSET, COUNTERS), LittleEndian.u16(request, SOUND_OFFSET), LittleEndian.u16(request, SOUND_INDEX_OFFSET),
                    LittleEndian.u16(request, SOUND_REPEAT_OFFSET));
        }

        @Override
        public int[] pwm() {
            return pwm.clone();
        }

        @Override
        public int[] motorSync() {
            return motorSync.clone();
        }

        @Override
        public int[] motorDist() {
            return motorDist.clone();
        }

        @Override
        public int[] motorCmdId() {
            return motorCmdId.clone();
        }

        @Override
        public int[] counterCmdId() {
            return counterCmdId.clone();
        }

        @Override
        public boolean equals(Object o) {
            return o instanceof Exchange x && Arrays.equals(pwm, x.pwm) && Arrays.equals(motorSync, x.motorSync)
                    && Arrays.equals(motorDist, x.motorDist) && Arrays.equals(motorCmdId, x.motorCmdId)
                    && Arrays.equals(counterCmdId, x.counterCmdId) && sound == x.sound && soundIndex == x.soundIndex
                    && soundRepeat == x.soundRepeat;
        }

        @Override
        public int hashCode() {
            return Objects.hash(Arrays.hashCode(pwm), Arrays.hashCode(motorSync), Arrays.hashCode(motorDist), Arrays.hashCode(motorCmdId),
                    Arrays.hashCode(counterCmdId), sound, soundIndex, soundRepeat);
        }

        @Override
        public String toString() {
            return "Exchange[pwm=" + Arrays.toString(pwm) + ", motorSync=" + Arrays.toString(motorSync) + ", motorDist="
                    + Arrays.toString(motorDist) + ", motorCmdId=" + Arrays.toString(motorCmdId) + ", counterCmdId="
                    + Arrays.toString(counterCmdId) + ", sound=" + sound + ", soundIndex=" + soundIndex + ", soundRepeat=" + soundRepeat + "]";
        }
    }

    /**
     * The simple exchange reply: the controller's inputs and counters now.
     *
     * @param input        {@link #INPUTS} values of I1..I8, in the unit of each input's mode
     * @param counterLevel per counter: its input's level, 0/1
     * @param counterValue per counter: pulses since its last reset (s16, wraps)
     * @param counterCmdId per counter: the id of the last reset done
     * @param motorCmdId   per motor: the id of the last distance command finished
     * @param soundCmdId   the id of the last sound command finished
     * @param ir           {@link #IR_LENGTH} bytes of infra-red remote state
     */
    public record ExchangeReply(int[] input, int[] counterLevel, int[] counterValue, int[] counterCmdId, int[] motorCmdId, int soundCmdId,
                                byte[] ir) {

        /** Checks the array lengths and copies them. */
        public ExchangeReply {
            input = copy("input", input, INPUTS);
            counterLevel = copy("counterLevel", counterLevel, COUNTERS);
            counterValue = copy("counterValue", counterValue, COUNTERS);
            counterCmdId = copy("counterCmdId", counterCmdId, COUNTERS);
            motorCmdId = copy("motorCmdId", motorCmdId, MOTORS);
            Objects.requireNonNull(ir, "ir");
            if (ir.length != IR_LENGTH) {
                throw new IllegalArgumentException("ir has " + IR_LENGTH + " bytes, got " + ir.length);
            }
            ir = ir.clone();
        }

        /** @return the 80-byte reply */
        public byte[] encode() {
            byte[] m = message(EXCHANGE_REPLY, EXCHANGE_REPLY_LENGTH);
            putS16ArrayLe(m, REPLY_INPUT_OFFSET, input);
            putS16ArrayLe(m, REPLY_COUNTER_LEVEL_OFFSET, counterLevel);
            putS16ArrayLe(m, REPLY_COUNTER_VALUE_OFFSET, counterValue);
            putS16ArrayLe(m, REPLY_COUNTER_CMD_ID_OFFSET, counterCmdId);
            putS16ArrayLe(m, REPLY_MOTOR_CMD_ID_OFFSET, motorCmdId);
            LittleEndian.putU16(m, REPLY_SOUND_CMD_ID_OFFSET, soundCmdId);
            System.arraycopy(ir, 0, m, REPLY_IR_OFFSET, IR_LENGTH);
            return m;
        }

        /**
         * @param reply an 80-byte exchange reply
         * @return its fields
         */
        public static ExchangeReply decode(byte[] reply) {
            check(reply, EXCHANGE_REPLY, EXCHANGE_REPLY_LENGTH);
            return new ExchangeReply(s16ArrayLe(reply, REPLY_INPUT_OFFSET, INPUTS), s16ArrayLe(reply, REPLY_COUNTER_LEVEL_OFFSET, COUNTERS),
                    s16ArrayLe(reply, REPLY_COUNTER_VALUE_OFFSET, COUNTERS), s16ArrayLe(reply, REPLY_COUNTER_CMD_ID_OFFSET, COUNTERS),
                    s16ArrayLe(reply, REPLY_MOTOR_CMD_ID_OFFSET, MOTORS), LittleEndian.u16(reply, REPLY_SOUND_CMD_ID_OFFSET),
                    Arrays.copyOfRange(reply, REPLY_IR_OFFSET, REPLY_IR_OFFSET + IR_LENGTH));
        }

        /**
         * @param i 0 for I1 ... 7 for I8
         * @return that input's value
         */
        public int input(int i) {
            return input[i];
        }

        @Override
        public int[] input() {
            return input.clone();
        }

        @Override
        public int[] counterLevel() {
            return counterLevel.clone();
        }

        @Override
        public int[] counterValue() {
            return counterValue.clone();
        }

        @Override
        public int[] counterCmdId() {
            return counterCmdId.clone();
        }

        @Override
        public int[] motorCmdId() {
            return motorCmdId.clone();
        }

        @Override
        public byte[] ir() {
            return ir.clone();
        }

        @Override
        public boolean equals(Object o) {
            return o instanceof ExchangeReply r && Arrays.equals(input, r.input) && Arrays.equals(counterLevel, r.counterLevel)
                    && Arrays.equals(counterValue, r.counterValue) && Arrays.equals(counterCmdId, r.counterCmdId)
                    && Arrays.equals(motorCmdId, r.motorCmdId) && soundCmdId == r.soundCmdId && Arrays.equals(ir, r.ir);
        }

        @Override
        public int hashCode() {
            return Objects.hash(Arrays.hashCode(input), Arrays.hashCode(counterLevel), Arrays.hashCode(counterValue),
                    Arrays.hashCode(counterCmdId), Arrays.hashCode(motorCmdId), soundCmdId, Arrays.hashCode(ir));
        }

        @Override
        public String toString() {
            return "ExchangeReply[input=" + Arrays.toString(input) + ", counterLevel=" + Arrays.toString(counterLevel) + ", counterValue="
                    + Arrays.toString(counterValue) + ", counterCmdId=" + Arrays.toString(counterCmdId) + ", motorCmdId="
                    + Arrays.toString(motorCmdId) + ", soundCmdId=" + soundCmdId + ", ir=" + Arrays.toString(ir) + "]";
        }
    }

    private static int[] copy(String field, int[] values, int length) {
        Objects.requireNonNull(values, field);
        if (values.length != length) {
            throw new IllegalArgumentException(field + " has " + length + " entries, got " + values.length);
        }
        return values.clone();
    }

    // ---- little-endian fields ----






    private static void putS16ArrayLe(byte[] b, int off, int[] values) {
        for (int i = 0; i < values.length; i++) {
            LittleEndian.putU16(b, off + 2 * i, values[i]);
        }
    }

    private static int[] s16ArrayLe(byte[] b, int off, int count) {
        int[] values = new int[count];
        for (int i = 0; i < count; i++) {
            values[i] = LittleEndian.s16(b, off + 2 * i);
        }
        return values;
    }
}
