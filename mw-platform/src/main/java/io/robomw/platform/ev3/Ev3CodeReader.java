package io.robomw.platform.ev3;

import io.robomw.platform.brick.LittleEndian;
import java.nio.charset.StandardCharsets;

/**
 * Reads the byte codes of a direct command: opcode and sub-code bytes, and parameters in every
 * encoding of {@link Ev3Parameter} (the brick emulator runs them; tests decode the documented
 * examples with it). Byte codes that end inside a parameter, and the encodings the firmware uses
 * only inside programs (labels, handles, addresses), are refused with an
 * {@link IllegalArgumentException} naming the offset.
 *
 * <p>Not thread-safe: one reader per command.
 */
public final class Ev3CodeReader {

    private final byte[] bytes;
    private final int end;
    private int position;

    /**
     * @param bytes the bytes holding the byte codes
     * @param from  offset of the first byte code
     * @param to    offset just past the last one
     */
    public Ev3CodeReader(byte[] bytes, int from, int to) {
        if (from < 0 || to > bytes.length || from > to) {
            throw new IllegalArgumentException("byte codes must lie within the " + bytes.length + " bytes given, from=" + from + ", to=" + to);
        }
        this.bytes = bytes;
        this.position = from;
        this.end = to;
    }

    /**
     * @param frame a whole direct-command frame, from its length field
     * @return a reader of its byte codes
     */
    public static Ev3CodeReader ofCommand(byte[] frame) {
        return new Ev3CodeReader(frame, Ev3Frame.CODE_OFFSET, frame.length);
    }

    /** @return whether byte codes are left */
    public boolean hasMore() {
        return position < end;
    }

    /** @return offset of the next byte */
    public int position() {
        return position;
    }

    /**
     * @return the next byte, unsigned: an opcode or a sub-code
     * @throws IllegalArgumentException if none is left
     */
    public int nextByte() {
        require(1, "an opcode");
        return bytes[position++] & 0xFF;
    }

    /**
     * @return the next parameter
     * @throws IllegalArgumentException if the byte codes end inside it, or it uses an encoding
     *                                  direct commands do not
     */
    public Ev3Parameter nextParameter() {
        int at = position;
        int b = nextByte();
        if ((b & Ev3Parameter.PRIMPAR_LONG) == 0) {
            if ((b & Ev3Parameter.PRIMPAR_VARIABLE) == 0) {
                int v = b & Ev3Parameter.PRIMPAR_VALUE;
                return Ev3Parameter.constant((v & Ev3Parameter.PRIMPAR_CONST_SIGN) != 0 ? v - 64 : v);
            }
            int index = b & Ev3Parameter.PRIMPAR_INDEX;
            return (b & Ev3Parameter.PRIMPAR_GLOBAL) != 0 ? Ev3Parameter.global(index) : Ev3Parameter.local(index);
        }
        if ((b & Ev3Parameter.PRIMPAR_ADDR) != 0 || (b & Ev3Parameter.PRIMPAR_HANDLE) != 0) {
            throw unsupported(b, at, "handles and addresses");
        }
        int size = b & Ev3Parameter.PRIMPAR_BYTES;
        if ((b & Ev3Parameter.PRIMPAR_VARIABLE) == 0) {
            if ((b & Ev3Parameter.PRIMPAR_GLOBAL) != 0) {
                throw unsupported(b, at, "labels");
            }
            return switch (size) {
                case Ev3Parameter.PRIMPAR_STRING_OLD, Ev3Parameter.PRIMPAR_STRING -> Ev3Parameter.string(readString(at));
                case Ev3Parameter.PRIMPAR_1_BYTE -> Ev3Parameter.constant(readSigned(1, at));
                case Ev3Parameter.PRIMPAR_2_BYTES -> Ev3Parameter.constant(readSigned(2, at));
                case Ev3Parameter.PRIMPAR_4_BYTES -> Ev3Parameter.constant(readSigned(4, at));
                default -> throw unsupported(b, at, "size code " + size);
            };
        }
        int offset = switch (size) {
            case Ev3Parameter.PRIMPAR_1_BYTE -> readSigned(1, at) & 0xFF;
            case Ev3Parameter.PRIMPAR_2_BYTES -> readSigned(2, at) & 0xFFFF;
            case Ev3Parameter.PRIMPAR_4_BYTES -> readSigned(4, at);
            default -> throw unsupported(b, at, "size code " + size + " for a variable");
        };
        if (offset < 0) {
            throw new IllegalArgumentException("variable offset at byte " + at + " is negative: " + offset);
        }
        return (b & Ev3Parameter.PRIMPAR_GLOBAL) != 0 ? Ev3Parameter.global(offset) : Ev3Parameter.local(offset);
    }

    private int readSigned(int n, int at) {
        require(n, "the value of the parameter at byte " + at);
        int v = switch (n) {
            case 1 -> bytes[position];
            case 2 -> LittleEndian.s16(bytes, position);
            default -> LittleEndian.s32(bytes, position);
        };
        position += n;
        return v;
    }

    private String readString(int at) {
        int start = position;
        while (position < end && bytes[position] != 0) {
            position++;
        }
        if (position >= end) {
            throw new IllegalArgumentException("the string parameter at byte " + at + " has no terminating NUL before the end of the byte codes");
        }
        String s = new String(bytes, start, position - start, StandardCharsets.US_ASCII);
        position++;
        return s;
    }

    private void require(int n, String what) {
        if (end - position < n) {
            throw new IllegalArgumentException("the byte codes end at byte " + end + " inside " + what
                    + " (" + n + " byte(s) needed, " + (end - position) + " left)");
        }
    }

    private static IllegalArgumentException unsupported(int b, int at, String what) {
        return new IllegalArgumentException(String.format("parameter byte 0x%02X at byte %d uses %s, which direct commands do not support", b, at, what));
    }
}
