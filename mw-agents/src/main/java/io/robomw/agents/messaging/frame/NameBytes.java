package io.robomw.agents.messaging.frame;

import java.nio.charset.StandardCharsets;

/**
 * The UTF-8 bytes of the names a node sends (its own, topics, functions, receivers): the same
 * few, over and over, usually the very same {@code String} objects. Looked up by identity in a
 * small direct-mapped table, so a publication's four names cost four array reads instead of four
 * hash-map lookups (a hash-map lookup hashes and compares the text). Thread-safe: entries are
 * immutable, and a racing writer can only replace one entry by another.
 */
public final class NameBytes {

    private static final int SIZE = 128;

    /** A name and its bytes. */
    private record Entry(String name, byte[] bytes) {
    }

    private final Entry[] entries = new Entry[SIZE];

    /**
     * @param what  what the name is, for the error
     * @param value the name
     * @return its UTF-8 bytes (shared: do not change them)
     * @throws IllegalArgumentException if it is longer than {@link FrameCodec#MAX_NAME_BYTES} bytes
     */
    public byte[] of(String what, String value) {
        int slot = System.identityHashCode(value) & (SIZE - 1);
        Entry e = entries[slot];
        if (e != null && e.name() == value) {
            return e.bytes();
        }
        byte[] bytes = value.getBytes(StandardCharsets.UTF_8);
        if (bytes.length > FrameCodec.MAX_NAME_BYTES) {
            throw new IllegalArgumentException(what + " is " + bytes.length + " bytes in UTF-8; the limit is " + FrameCodec.MAX_NAME_BYTES);
        }
        entries[slot] = new Entry(value, bytes);
        return bytes;
    }
}
