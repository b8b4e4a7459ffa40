package io.robomw.agents.messaging.io;

import io.robomw.agents.messaging.DropReason;
import io.robomw.agents.messaging.frame.FrameCodec;
import io.robomw.agents.messaging.frame.FrameException;

import java.io.IOException;
import java.io.InputStream;

/**
 * Cuts a byte stream into frames by their declared lengths, reading in large chunks. After
 * {@link #next()} returns a length, the frame is at {@link #buffer()}[{@link #offset()}] until the
 * next call.
 *
 * <p>A stream cannot be resynchronised after garbage or an oversized length, so those end it
 * ({@link FrameException}); the caller drops the connection and keeps serving the others.
 * Not thread-safe: one reader thread per connection.
 */
public final class FrameStreamReader {

    private final InputStream in;
    private final int maxFrameSize;
    private byte[] buf = new byte[64 * 1024];
    private int start;
    private int end;
    private int pending;

    /**
     * @param in           the stream
     * @param maxFrameSize the largest frame accepted
     */
    public FrameStreamReader(InputStream in, int maxFrameSize) {
        this.in = in;
        this.maxFrameSize = maxFrameSize;
    }

    /**
     * @return the next frame's length, or -1 at a clean end of stream (between frames)
     * @throws FrameException if the stream holds garbage, a frame above the maximum, or ends inside a frame
     * @throws IOException    if reading fails
     */
    public int next() throws IOException, FrameException {
        start += pending;
        pending = 0;
        if (!fill(FrameCodec.PREFIX_LENGTH)) {
            if (end == start) {
                return -1;
            }
            throw new FrameException(DropReason.TRUNCATED, "stream ended " + (end - start) + " bytes into a frame prefix");
        }
        int length = FrameCodec.declaredLength(buf, start, maxFrameSize);
        if (!fill(length)) {
            throw new FrameException(DropReason.TRUNCATED, "stream ended after " + (end - start) + " of a frame's " + length + " bytes");
        }
        pending = length;
        return length;
    }

    /** @return the buffer holding the current frame */
    public byte[] buffer() {
        return buf;
    }

    /** @return where the current frame starts in {@link #buffer()} */
    public int offset() {
        return start;
    }

    private boolean fill(int needed) throws IOException {
        if (end - start >= needed) {
            return true;
        }
        if (buf.length - start < needed) {
            byte[] target = buf.length < needed ? new byte[Math.max(needed, buf.length * 2)] : buf;
            System.arraycopy(buf, start, target, 0, end - start);
            end -= start;
            start = 0;
            buf = target;
        }
        while (end - start < needed) {
            int n = in.read(buf, end, buf.length - end);
            if (n < 0) {
                return false;
            }
            end += n;
        }
        return true;
    }
}
