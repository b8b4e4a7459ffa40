package io.robomw.agents.messaging.frame;

import java.nio.charset.StandardCharsets;
import java.util.Arrays;
import java.util.function.UnaryOperator;

/**
 * Remembers the last few names (senders, topics, functions) a reading thread decoded, so the
 * same bytes give the same {@code String} without decoding and allocating it again: a stream of
 * publications repeats the same three or four names in every frame. Direct-mapped, 64 entries,
 * of names up to {@value #MAX_CACHED_BYTES} bytes. It also remembers the last frame's four names
 * as one block ({@link #lastBlock}): a stream from one sender on one topic then costs one
 * comparison per frame instead of three lookups. A name decoded for the first time can be
 * replaced by an equal {@code String} the node already holds (its topic's), so that map lookups
 * by it find the very same object.
 * Not thread-safe: one per reading thread.
 */
public final class NameCache {

    /** The longest name block remembered whole. */
    static final int MAX_BLOCK_BYTES = 256;

    private static final int SIZE = 64;
    /** Longer names are decoded each time, not kept (at most 64 × 2 × 256 bytes per reading thread). */
    static final int MAX_CACHED_BYTES = 256;

    private final byte[][] keys = new byte[SIZE][];
    private final String[] values = new String[SIZE];
    private final UnaryOperator<String> canonical;
    private final byte[] block = new byte[MAX_BLOCK_BYTES];
    private long blockLengths = -1;
    private final String[] blockNames = new String[4];

    /** A cache that keeps the {@code String}s it decodes. */
    public NameCache() {
        this(UnaryOperator.identity());
    }

    /**
     * @param canonical given a newly decoded name, returns an equal {@code String} to keep instead
     *                  (or the name itself)
     */
    public NameCache(UnaryOperator<String> canonical) {
        this.canonical = canonical;
    }

    /**
     * The last frame's names, if this frame's four names are the same bytes.
     *
     * @param buf     bytes
     * @param at      where the names start (sender, receiver, topic, function, back to back)
     * @param lengths the four lengths, 16 bits each (sender highest)
     * @param length  their sum
     * @return the four names, or {@code null} if they differ (then {@link #rememberBlock} them); do not change the array
     */
    public String[] lastBlock(byte[] buf, int at, long lengths, int length) {
        if (length <= MAX_BLOCK_BYTES && lengths == blockLengths && Arrays.equals(block, 0, length, buf, at, at + length)) {
            return blockNames;
        }
        return null;
    }

    /**
     * Remembers a frame's names as the last block (if they are short enough).
     *
     * @param buf     bytes
     * @param at      where the names start
     * @param lengths the four lengths, 16 bits each (sender highest)
     * @param length  their sum
     * @param names   the four names decoded
     */
    public void rememberBlock(byte[] buf, int at, long lengths, int length, String... names) {
        if (length > MAX_BLOCK_BYTES) {
            blockLengths = -1;
            return;
        }
        System.arraycopy(buf, at, block, 0, length);
        System.arraycopy(names, 0, blockNames, 0, 4);
        blockLengths = lengths;
    }

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
        String s = canonical.apply(new String(buf, offset, length, StandardCharsets.UTF_8));
        keys[slot] = Arrays.copyOfRange(buf, offset, offset + length);
        values[slot] = s;
        return s;
    }
}
