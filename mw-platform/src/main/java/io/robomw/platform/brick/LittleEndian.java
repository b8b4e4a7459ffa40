package io.robomw.platform.brick;

/**
 * Little-endian reads and writes of the fields of brick telegrams (NXT, EV3 and TXT are all
 * little-endian). Unsigned fields are widened, so {@code 0xFFFF} reads as 65535, not −1. Stateless.
 */
public final class LittleEndian {

    private LittleEndian() {
    }

    /**
     * @param b   bytes
     * @param off offset
     * @return the unsigned 16-bit value there
     */
    public static int u16(byte[] b, int off) {
        return (b[off] & 0xFF) | (b[off + 1] & 0xFF) << 8;
    }

    /**
     * @param b   bytes
     * @param off offset
     * @return the signed 16-bit value there
     */
    public static int s16(byte[] b, int off) {
        return (short) u16(b, off);
    }

    /**
     * @param b   bytes
     * @param off offset
     * @return the signed 32-bit value there
     */
    public static int s32(byte[] b, int off) {
        return (b[off] & 0xFF) | (b[off + 1] & 0xFF) << 8 | (b[off + 2] & 0xFF) << 16 | (b[off + 3] & 0xFF) << 24;
    }

    /**
     * @param b   bytes
     * @param off offset
     * @return the unsigned 32-bit value there
     */
    public static long u32(byte[] b, int off) {
        return s32(b, off) & 0xFFFF_FFFFL;
    }

    /**
     * @param b   bytes
     * @param off offset
     * @return the IEEE-754 single-precision value there
     */
    public static float f32(byte[] b, int off) {
        return Float.intBitsToFloat(s32(b, off));
    }

    /**
     * Writes the low 16 bits of a value.
     *
     * @param b     bytes
     * @param off   offset
     * @param value the value
     */
    public static void putU16(byte[] b, int off, int value) {
        b[off] = (byte) value;
        b[off + 1] = (byte) (value >> 8);
    }

    /**
     * Writes the low 32 bits of a value (signed or unsigned).
     *
     * @param b     bytes
     * @param off   offset
     * @param value the value
     */
    public static void putU32(byte[] b, int off, long value) {
        b[off] = (byte) value;
        b[off + 1] = (byte) (value >> 8);
        b[off + 2] = (byte) (value >> 16);
        b[off + 3] = (byte) (value >> 24);
    }

    /**
     * Writes an IEEE-754 single-precision value.
     *
     * @param b     bytes
     * @param off   offset
     * @param value the value
     */
    public static void putF32(byte[] b, int off, float value) {
        putU32(b, off, Float.floatToRawIntBits(value));
    }
}
