package io.robomw.platform.mavlink.wire;

/**
 * MAVLink's checksum: CRC-16/MCRF4XX (the X.25 CRC of the MAVLink C library's
 * {@code crc_accumulate}: polynomial 0x1021 reflected, initial value 0xFFFF, no final XOR). A frame's
 * checksum covers the bytes after the start byte up to the end of the payload, then the message's
 * CRC_EXTRA byte; it is sent low byte first. Stateless.
 */
public final class Crc {

    /** The checksum's initial value. */
    public static final int INITIAL = 0xFFFF;

    private Crc() {
    }

    /**
     * @param crc  the checksum so far
     * @param data one byte (its low 8 bits)
     * @return the checksum with that byte
     */
    public static int accumulate(int crc, int data) {
        int tmp = (data ^ crc) & 0xFF;
        tmp = (tmp ^ (tmp << 4)) & 0xFF;
        return ((crc >>> 8) ^ (tmp << 8) ^ (tmp << 3) ^ (tmp >>> 4)) & 0xFFFF;
    }

    /**
     * @param crc  the checksum so far
     * @param data bytes
     * @return the checksum with them
     */
    public static int accumulate(int crc, byte[] data) {
        return accumulate(crc, data, 0, data.length);
    }

    /**
     * @param crc    the checksum so far
     * @param data   bytes
     * @param offset the first
     * @param length how many
     * @return the checksum with them
     */
    public static int accumulate(int crc, byte[] data, int offset, int length) {
        int c = crc;
        for (int i = offset; i < offset + length; i++) {
            c = accumulate(c, data[i]);
        }
        return c;
    }
}
