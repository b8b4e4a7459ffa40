package io.robomw.console.mcap;

import java.nio.charset.StandardCharsets;
import java.util.Arrays;
import java.util.Map;

/** A growable little-endian byte buffer for building MCAP records. Not thread-safe. */
final class LeWriter {

    private byte[] bytes;
    private int length;

    LeWriter(int capacity) {
        bytes = new byte[Math.max(16, capacity)];
    }

    int length() {
        return length;
    }

    byte[] array() {
        return bytes;
    }

    byte[] toByteArray() {
        return Arrays.copyOf(bytes, length);
    }

    void reset() {
        length = 0;
    }

    private void ensure(int more) {
        if (length + more > bytes.length) {
            long wanted = Math.max((long) bytes.length * 2, (long) length + more);
            if (wanted > Integer.MAX_VALUE - 16) {
                throw new IllegalStateException("an MCAP record buffer cannot grow past 2 GiB (" + length + " + " + more + " bytes)");
            }
            bytes = Arrays.copyOf(bytes, (int) wanted);
        }
    }

    LeWriter u8(int v) {
        ensure(1);
        bytes[length++] = (byte) v;
        return this;
    }

    LeWriter u16(int v) {
        ensure(2);
        bytes[length++] = (byte) v;
        bytes[length++] = (byte) (v >>> 8);
        return this;
    }

    LeWriter u32(long v) {
        ensure(4);
        for (int i = 0; i < 4; i++) {
            bytes[length++] = (byte) (v >>> (8 * i));
        }
        return this;
    }

    LeWriter u64(long v) {
        ensure(8);
        for (int i = 0; i < 8; i++) {
            bytes[length++] = (byte) (v >>> (8 * i));
        }
        return this;
    }

    /** Writes a u64 at an earlier position (a length known only afterwards). */
    void u64At(int position, long v) {
        for (int i = 0; i < 8; i++) {
            bytes[position + i] = (byte) (v >>> (8 * i));
        }
    }

    /** Writes a u32 at an earlier position. */
    void u32At(int position, long v) {
        for (int i = 0; i < 4; i++) {
            bytes[position + i] = (byte) (v >>> (8 * i));
        }
    }

    LeWriter raw(byte[] b) {
        return raw(b, 0, b.length);
    }

    LeWriter raw(byte[] b, int offset, int len) {
        ensure(len);
        System.arraycopy(b, offset, bytes, length, len);
        length += len;
        return this;
    }

    LeWriter string(String s) {
        byte[] b = s.getBytes(StandardCharsets.UTF_8);
        return u32(b.length).raw(b);
    }

    LeWriter bytes32(byte[] b) {
        return u32(b.length).raw(b);
    }

    LeWriter stringMap(Map<String, String> map) {
        int start = length;
        u32(0);
        for (Map.Entry<String, String> e : map.entrySet()) {
            string(e.getKey()).string(e.getValue());
        }
        u32At(start, length - start - 4L);
        return this;
    }

    LeWriter u16u64Map(Map<Integer, Long> map) {
        u32(map.size() * 10L);
        for (Map.Entry<Integer, Long> e : map.entrySet()) {
            u16(e.getKey()).u64(e.getValue());
        }
        return this;
    }
}
