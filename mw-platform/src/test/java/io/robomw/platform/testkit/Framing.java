package io.robomw.platform.testkit;

/**
 * How the far end of a {@link ScriptedLink} cuts what is written into frames, so that its
 * responder answers each frame, however the driver batches or splits its writes (a brick reads
 * frames off its input buffer, not writes). Bytes that do not make a whole frame yet wait for the
 * next write.
 */
@FunctionalInterface
public interface Framing {

    /**
     * @param bytes     what has been written and not yet framed
     * @param from      where the next frame starts
     * @param available how many bytes there are from {@code from}
     * @return the length of the frame that starts at {@code from}, header included (it may be
     *         more than {@code available}: the rest is still to come), or 0 if more bytes must
     *         come to tell
     */
    int frameLength(byte[] bytes, int from, int available);

    /**
     * @param length every frame's length
     * @return frames of {@code length} bytes (the Intelligent Interface's two-byte commands)
     */
    static Framing fixed(int length) {
        if (length < 1) {
            throw new IllegalArgumentException("a frame has at least one byte, length=" + length);
        }
        return (bytes, from, available) -> length;
    }

    /**
     * @return frames behind a two-byte little-endian length that counts the bytes after it (the
     *         NXT's Bluetooth telegrams, the EV3's direct commands); the frame handed on includes
     *         the length
     */
    static Framing lengthPrefixed16LittleEndian() {
        return (bytes, from, available) -> available < 2 ? 0 : 2 + ((bytes[from] & 0xFF) | (bytes[from + 1] & 0xFF) << 8);
    }
}
