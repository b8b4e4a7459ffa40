package io.robomw.platform.ev3;

import io.robomw.platform.brick.LittleEndian;
/**
 * The frame of an EV3 direct command and of its reply, byte for byte (firmware
 * {@code lms2012/c_com/source/c_com.h} and {@code c_com.c}), with a name for every offset. The same
 * frame travels over Bluetooth SPP, USB and TCP; there is no extra layer on Bluetooth. Every
 * multi-byte field is <b>little-endian</b>; the helpers below say so in their names and never rely
 * on a buffer's default order.
 *
 * <pre>
 * Direct command:
 *   0         2              4        5            7
 *  +---------+--------------+--------+------------+------------------------------+
 *  | length  | msg counter  |  type  |    vars    | byte codes ...               |
 *  | u16 LE  |    u16 LE    |   u8   |   u16 LE   | opcode, parameters, opcode...|
 *  +---------+--------------+--------+------------+------------------------------+
 *  length = bytes after the length field (frame length - 2)
 *  type   = 0x00 direct command, reply wanted; 0x80 direct command, no reply
 *           (0x01 / 0x81 are system commands)
 *  vars   = locals &lt;&lt; 10 | globals   globals 0..1021 bytes (the reply space), locals 0..63 bytes
 *
 * Reply:
 *   0         2              4        5
 *  +---------+--------------+--------+---------------------------------+
 *  | length  | msg counter  |  type  | global variables ...            |
 *  | u16 LE  |  (echoed)    |   u8   | exactly `globals` bytes         |
 *  +---------+--------------+--------+---------------------------------+
 *  type   = 0x02 DIRECT_REPLY, 0x04 DIRECT_REPLY_ERROR
 *  A malformed header (or globals over 1021) gets the bare error reply 03 00 cc cc 04, without
 *  globals; a failure while running the byte codes gets type 0x04 with the globals appended.
 * </pre>
 *
 * Stateless.
 */
public final class Ev3Frame {

    /** Offset of the u16 length field: bytes that follow it. */
    public static final int LENGTH_FIELD_OFFSET = 0;
    /** Size of the length field. */
    public static final int LENGTH_FIELD_SIZE = 2;
    /** Offset of the u16 message counter, in commands and replies. */
    public static final int COUNTER_FIELD_OFFSET = 2;
    /** Offset of the type byte, in commands and replies. */
    public static final int TYPE_FIELD_OFFSET = 4;
    /** Offset of the u16 vars field (locals and globals) of a command. */
    public static final int VARS_FIELD_OFFSET = 5;
    /** Offset of a command's first byte code. */
    public static final int CODE_OFFSET = 7;
    /** Length of a command's header, up to its byte codes. */
    public static final int COMMAND_HEADER_LENGTH = CODE_OFFSET;
    /** Offset of a reply's global variables. */
    public static final int GLOBALS_OFFSET = 5;
    /** Length of a reply's header, up to its global variables. */
    public static final int REPLY_HEADER_LENGTH = GLOBALS_OFFSET;

    /** Type: direct command, reply wanted. */
    public static final int DIRECT_COMMAND_REPLY = 0x00;
    /** Type: direct command, no reply. */
    public static final int DIRECT_COMMAND_NO_REPLY = 0x80;
    /** Type: system command, reply wanted. */
    public static final int SYSTEM_COMMAND_REPLY = 0x01;
    /** Type: system command, no reply. */
    public static final int SYSTEM_COMMAND_NO_REPLY = 0x81;
    /** Reply type: the direct command ran. */
    public static final int DIRECT_REPLY = 0x02;
    /** Reply type: a system command ran. */
    public static final int SYSTEM_REPLY = 0x03;
    /** Reply type: the direct command was malformed or failed while running. */
    public static final int DIRECT_REPLY_ERROR = 0x04;
    /** Reply type: a system command failed. */
    public static final int SYSTEM_REPLY_ERROR = 0x05;

    /** Most global-variable bytes a direct command may ask for ({@code MAX_COMMAND_GLOBALS}). */
    public static final int MAX_GLOBALS = 1021;
    /** Most local-variable bytes the 6-bit field can carry ({@code MAX_COMMAND_LOCALS} is 64). */
    public static final int MAX_LOCALS = 63;
    /** The firmware's receive buffer (1024 bytes) less the length field: the longest length field of a command. */
    public static final int MAX_COMMAND_LENGTH = 1022;
    /** Longest length field of a reply: counter, type and {@link #MAX_GLOBALS} bytes. */
    public static final int MAX_REPLY_LENGTH = REPLY_HEADER_LENGTH - LENGTH_FIELD_SIZE + MAX_GLOBALS;
    /** Shortest length field of a reply: counter and type. */
    public static final int MIN_REPLY_LENGTH = REPLY_HEADER_LENGTH - LENGTH_FIELD_SIZE;

    private static final int GLOBALS_MASK = 0x3FF;
    private static final int LOCALS_SHIFT = 10;
    private static final int LOCALS_MASK = 0x3F;

    private Ev3Frame() {
    }

    /**
     * @param locals  local-variable bytes, 0..{@value #MAX_LOCALS}
     * @param globals global-variable bytes, 0..{@value #MAX_GLOBALS}
     * @return the vars field
     * @throws IllegalArgumentException if either is out of range
     */
    public static int vars(int locals, int globals) {
        if (globals < 0 || globals > MAX_GLOBALS) {
            throw new IllegalArgumentException("globals must be 0.." + MAX_GLOBALS + " bytes, globals=" + globals);
        }
        if (locals < 0 || locals > MAX_LOCALS) {
            throw new IllegalArgumentException("locals must be 0.." + MAX_LOCALS + " bytes, locals=" + locals);
        }
        return locals << LOCALS_SHIFT | globals;
    }

    /**
     * @param vars a vars field
     * @return its global-variable bytes (0..1023; above {@value #MAX_GLOBALS} the firmware refuses the command)
     */
    public static int globalsOf(int vars) {
        return vars & GLOBALS_MASK;
    }

    /**
     * @param vars a vars field
     * @return its local-variable bytes
     */
    public static int localsOf(int vars) {
        return vars >> LOCALS_SHIFT & LOCALS_MASK;
    }

    /**
     * @param frame a command or reply frame, from its length field
     * @return the length field: bytes after it
     */
    public static int length(byte[] frame) {
        return LittleEndian.u16(frame, LENGTH_FIELD_OFFSET);
    }

    /**
     * @param frame a command or reply frame
     * @return its message counter
     */
    public static int counter(byte[] frame) {
        return LittleEndian.u16(frame, COUNTER_FIELD_OFFSET);
    }

    /**
     * @param frame a command or reply frame
     * @return its type byte
     */
    public static int type(byte[] frame) {
        return frame[TYPE_FIELD_OFFSET] & 0xFF;
    }

    /**
     * @param body a frame without its length field, as a length-driven reader returns it
     * @return the whole frame, with its length field in front
     */
    public static byte[] withLength(byte[] body) {
        byte[] frame = new byte[LENGTH_FIELD_SIZE + body.length];
        LittleEndian.putU16(frame, LENGTH_FIELD_OFFSET, body.length);
        System.arraycopy(body, 0, frame, LENGTH_FIELD_SIZE, body.length);
        return frame;
    }

    /**
     * @param type a command or reply type byte
     * @return its name, for messages
     */
    public static String typeName(int type) {
        return switch (type) {
            case DIRECT_COMMAND_REPLY -> "DIRECT_COMMAND_REPLY";
            case DIRECT_COMMAND_NO_REPLY -> "DIRECT_COMMAND_NO_REPLY";
            case SYSTEM_COMMAND_REPLY -> "SYSTEM_COMMAND_REPLY";
            case SYSTEM_COMMAND_NO_REPLY -> "SYSTEM_COMMAND_NO_REPLY";
            case DIRECT_REPLY -> "DIRECT_REPLY";
            case SYSTEM_REPLY -> "SYSTEM_REPLY";
            case DIRECT_REPLY_ERROR -> "DIRECT_REPLY_ERROR";
            case SYSTEM_REPLY_ERROR -> "SYSTEM_REPLY_ERROR";
            default -> String.format("type 0x%02X", type);
        };
    }

    // ---- little-endian fields ----







}
