package io.robomw.platform.ev3;

import io.robomw.platform.brick.LittleEndian;
import java.nio.charset.StandardCharsets;
import java.util.Objects;

/**
 * One parameter of an EV3 byte code: a constant, a string, or a reference to a local or global
 * variable (for results, a global variable is a byte offset into the reply). The static methods
 * encode the firmware's macros ({@code bytecodes.h}); {@link Ev3CodeReader} decodes them.
 *
 * <pre>
 * first byte   bit 7      bit 6      bit 5         bits 4..0 / 2..0
 * short form   0          0 const    sign          value: 6-bit two's complement   LC0(v) = v &amp; 0x3F
 *              0          1 variable 0 local/1 glob index 0..31                    LV0(i) = 0x40|i, GV0(i) = 0x60|i
 * long form    1 (0x80)   0 const    0             size: 1 = 1 byte, 2 = 2, 3 = 4, 4 = zero-terminated string
 *              1          1 variable 0 local/1 glob size as above, then the offset LE
 *
 * LC1(v) = 81 v   LC2(v) = 82 lo hi   LC4(v) = 83 b0 b1 b2 b3   LCS("x") = 84 'x' 00
 * LV1 = C1, LV2 = C2, LV4 = C3      GV1 = E1, GV2 = E2, GV4 = E3   (then the offset, little-endian)
 * </pre>
 *
 * The shortest-form encoders ({@link #lc(int)}, {@link #gv(int)}, {@link #lv(int)}) choose as
 * ev3-dc's {@code LCX}/{@code GVX} do: 31 is {@code 1F}, 32 is {@code 81 20}, -33 is
 * {@code 81 DF}.
 *
 * @param kind  what the parameter is
 * @param value the constant, or the variable's byte offset; 0 for a string
 * @param text  the string, or {@code null}
 */
public record Ev3Parameter(Kind kind, int value, String text) {

    /** What a parameter is. */
    public enum Kind {
        /** A constant number. */
        CONSTANT,
        /** A zero-terminated string constant. */
        STRING,
        /** A reference to a local variable (byte offset). */
        LOCAL,
        /** A reference to a global variable (byte offset into the reply). */
        GLOBAL
    }

    /** Long form: a size code and value bytes follow. */
    static final int PRIMPAR_LONG = 0x80;
    /** A variable rather than a constant. */
    static final int PRIMPAR_VARIABLE = 0x40;
    /** A global variable rather than a local one (with {@link #PRIMPAR_VARIABLE}). */
    static final int PRIMPAR_GLOBAL = 0x20;
    /** Sign bit of a short constant. */
    static final int PRIMPAR_CONST_SIGN = 0x20;
    /** A handle (long-form variables; not supported here). */
    static final int PRIMPAR_HANDLE = 0x10;
    /** An address (not supported here). */
    static final int PRIMPAR_ADDR = 0x08;
    /** The value bits of a short constant. */
    static final int PRIMPAR_VALUE = 0x3F;
    /** The index bits of a short variable. */
    static final int PRIMPAR_INDEX = 0x1F;
    /** The size bits of the long form. */
    static final int PRIMPAR_BYTES = 0x07;
    /** Size code: a zero-terminated string (old form). */
    static final int PRIMPAR_STRING_OLD = 0;
    /** Size code: one byte. */
    static final int PRIMPAR_1_BYTE = 1;
    /** Size code: two bytes. */
    static final int PRIMPAR_2_BYTES = 2;
    /** Size code: four bytes. */
    static final int PRIMPAR_4_BYTES = 3;
    /** Size code: a zero-terminated string. */
    static final int PRIMPAR_STRING = 4;

    /** Checks the fields. */
    public Ev3Parameter {
        Objects.requireNonNull(kind, "kind");
        if ((kind == Kind.STRING) != (text != null)) {
            throw new IllegalArgumentException("a STRING parameter, and only it, carries text; kind=" + kind + ", text=" + text);
        }
    }

    /**
     * @param value a number
     * @return the constant
     */
    public static Ev3Parameter constant(int value) {
        return new Ev3Parameter(Kind.CONSTANT, value, null);
    }

    /**
     * @param offset a byte offset
     * @return a reference to that global variable
     */
    public static Ev3Parameter global(int offset) {
        return new Ev3Parameter(Kind.GLOBAL, offset, null);
    }

    /**
     * @param offset a byte offset
     * @return a reference to that local variable
     */
    public static Ev3Parameter local(int offset) {
        return new Ev3Parameter(Kind.LOCAL, offset, null);
    }

    /**
     * @param text a string
     * @return the string constant
     */
    public static Ev3Parameter string(String text) {
        return new Ev3Parameter(Kind.STRING, 0, text);
    }

    /** @return whether it refers to a variable (and can take a result) */
    public boolean isVariable() {
        return kind == Kind.LOCAL || kind == Kind.GLOBAL;
    }

    /** @return it encoded in its shortest form */
    public byte[] encode() {
        return switch (kind) {
            case CONSTANT -> lc(value);
            case STRING -> lcs(text);
            case LOCAL -> lv(value);
            case GLOBAL -> gv(value);
        };
    }

    @Override
    public String toString() {
        return switch (kind) {
            case CONSTANT -> Integer.toString(value);
            case STRING -> '"' + text + '"';
            case LOCAL -> "LV(" + value + ")";
            case GLOBAL -> "GV(" + value + ")";
        };
    }

    // ---- constants ----

    /**
     * @param v a constant
     * @return it in the shortest form: LC0 for -32..31, LC1 for a byte, LC2 for a short, else LC4
     */
    public static byte[] lc(int v) {
        if (v >= -32 && v <= 31) {
            return lc0(v);
        }
        if (v >= Byte.MIN_VALUE && v <= Byte.MAX_VALUE) {
            return lc1(v);
        }
        if (v >= Short.MIN_VALUE && v <= Short.MAX_VALUE) {
            return lc2(v);
        }
        return lc4(v);
    }

    /**
     * @param v -32..31
     * @return LC0(v): one byte, the value's low 6 bits
     */
    public static byte[] lc0(int v) {
        requireRange("LC0", v, -32, 31);
        return new byte[]{(byte) (v & PRIMPAR_VALUE)};
    }

    /**
     * @param v -128..127
     * @return LC1(v): {@code 81 v}
     */
    public static byte[] lc1(int v) {
        requireRange("LC1", v, Byte.MIN_VALUE, Byte.MAX_VALUE);
        return new byte[]{(byte) (PRIMPAR_LONG | PRIMPAR_1_BYTE), (byte) v};
    }

    /**
     * @param v -32768..32767
     * @return LC2(v): {@code 82 lo hi}
     */
    public static byte[] lc2(int v) {
        requireRange("LC2", v, Short.MIN_VALUE, Short.MAX_VALUE);
        return new byte[]{(byte) (PRIMPAR_LONG | PRIMPAR_2_BYTES), (byte) v, (byte) (v >> 8)};
    }

    /**
     * @param v any int
     * @return LC4(v): {@code 83} and the value little-endian
     */
    public static byte[] lc4(int v) {
        byte[] b = new byte[5];
        b[0] = (byte) (PRIMPAR_LONG | PRIMPAR_4_BYTES);
        LittleEndian.putU32(b, 1, v);
        return b;
    }

    /**
     * @param text ASCII text without NUL
     * @return LCS(text): {@code 84}, the text, {@code 00}
     */
    public static byte[] lcs(String text) {
        byte[] chars = text.getBytes(StandardCharsets.US_ASCII);
        for (byte c : chars) {
            if (c == 0) {
                throw new IllegalArgumentException("an EV3 string constant ends at its first NUL; text must not contain one: " + text);
            }
        }
        byte[] b = new byte[chars.length + 2];
        b[0] = (byte) (PRIMPAR_LONG | PRIMPAR_STRING);
        System.arraycopy(chars, 0, b, 1, chars.length);
        return b;
    }

    // ---- variables ----

    /**
     * @param offset a global-variable byte offset, 0 or more
     * @return a reference to it in the shortest form: GV0 up to 31, GV1 up to 255, GV2 up to 65535, else GV4
     */
    public static byte[] gv(int offset) {
        return variable(PRIMPAR_GLOBAL, "GV", offset);
    }

    /**
     * @param offset 0..31
     * @return GV0(offset): {@code 0x60 | offset}
     */
    public static byte[] gv0(int offset) {
        return variable0(PRIMPAR_GLOBAL, "GV0", offset);
    }

    /**
     * @param offset 0..255
     * @return GV1(offset): {@code E1 offset}
     */
    public static byte[] gv1(int offset) {
        return variable1(PRIMPAR_GLOBAL, "GV1", offset);
    }

    /**
     * @param offset 0..65535
     * @return GV2(offset): {@code E2 lo hi}
     */
    public static byte[] gv2(int offset) {
        return variable2(PRIMPAR_GLOBAL, "GV2", offset);
    }

    /**
     * @param offset 0 or more
     * @return GV4(offset): {@code E3} and the offset little-endian
     */
    public static byte[] gv4(int offset) {
        return variable4(PRIMPAR_GLOBAL, "GV4", offset);
    }

    /**
     * @param offset a local-variable byte offset, 0 or more
     * @return a reference to it in the shortest form: LV0, LV1, LV2 or LV4
     */
    public static byte[] lv(int offset) {
        return variable(0, "LV", offset);
    }

    /**
     * @param offset 0..31
     * @return LV0(offset): {@code 0x40 | offset}
     */
    public static byte[] lv0(int offset) {
        return variable0(0, "LV0", offset);
    }

    private static byte[] variable(int scope, String name, int offset) {
        requireRange(name, offset, 0, Integer.MAX_VALUE);
        if (offset <= PRIMPAR_INDEX) {
            return variable0(scope, name + "0", offset);
        }
        if (offset <= 0xFF) {
            return variable1(scope, name + "1", offset);
        }
        if (offset <= 0xFFFF) {
            return variable2(scope, name + "2", offset);
        }
        return variable4(scope, name + "4", offset);
    }

    private static byte[] variable0(int scope, String name, int offset) {
        requireRange(name, offset, 0, PRIMPAR_INDEX);
        return new byte[]{(byte) (PRIMPAR_VARIABLE | scope | offset)};
    }

    private static byte[] variable1(int scope, String name, int offset) {
        requireRange(name, offset, 0, 0xFF);
        return new byte[]{(byte) (PRIMPAR_LONG | PRIMPAR_VARIABLE | scope | PRIMPAR_1_BYTE), (byte) offset};
    }

    private static byte[] variable2(int scope, String name, int offset) {
        requireRange(name, offset, 0, 0xFFFF);
        return new byte[]{(byte) (PRIMPAR_LONG | PRIMPAR_VARIABLE | scope | PRIMPAR_2_BYTES), (byte) offset, (byte) (offset >> 8)};
    }

    private static byte[] variable4(int scope, String name, int offset) {
        requireRange(name, offset, 0, Integer.MAX_VALUE);
        byte[] b = new byte[5];
        b[0] = (byte) (PRIMPAR_LONG | PRIMPAR_VARIABLE | scope | PRIMPAR_4_BYTES);
        LittleEndian.putU32(b, 1, offset);
        return b;
    }

    private static void requireRange(String form, int v, int min, int max) {
        if (v < min || v > max) {
            throw new IllegalArgumentException(form + " holds " + min + ".." + max + ", got " + v);
        }
    }
}
