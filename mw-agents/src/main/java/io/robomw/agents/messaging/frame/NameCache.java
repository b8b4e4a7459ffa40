package io.robomw.agents.messaging.frame;

import java.nio.charset.StandardCharsets;
import java.util.Arrays;

/**
 * Remembers the last few names (senders, topics, functions) a reading thread decoded, so the
 * same bytes give the same {@code String} without decoding and allocating it again: a stream of
 * publications repeats the same three or four names in every frame. Direct-mapped, 64 entries,
 * of names up to {@value #MAX_CACHED_BYTES} bytes.
 * Not thread-safe: one per reading thread.
 */
public final class NameCache {

    private static final int SIZE = 64;
    /** Longer names are decoded each time, not kept (at most 64 × 2 × 256 bytes per reading thread). */
    static final int MAX_CACHED_BYTES = 256;

    private final byte[][] keys = new byte[SIZE][];
    private final String[] values = new String[SIZE];

    /**
     * @param buf    bytes
     * @param offset where the name starts
     * @param length its length in bytes
     * @return the name
     */
    public String decode(byte[] buf, int offset, int length) {
        if (length == 0) {
            return "";
        }
        if (length > MAX_CACHED_BYTES) {
            // not kept: a peer sending long names must not make each reading thread hold 64 of them
            return new String(buf, offset, length, StandardCharsets.UTF_8);
        }
        int slot = (length * 31 + buf[offset] * 7 + buf[offset + length - 1]) & (SIZE - 1);
        byte[] key = keys[slot];
        if (key != null && key.length == length && Arrays.equals(key, 0, length, buf, offset, offset + length)) {
            return values[slot];
        }
        String s = new String(buf, offset, length, StandardCharsets.UTF_8);
        keys[slot] = Arrays.copyOfRange(buf, offset, offset + length);
        values[slot] = s;
        return s;
    }
}
