package io.robomw.agents.messaging.io;

import io.robomw.agents.messaging.DropReason;
import io.robomw.agents.messaging.frame.FrameCodec;
import io.robomw.agents.messaging.frame.FrameException;

import java.io.IOException;
import java.io.InputStream;
import java.net.SocketTimeoutException;
import java.util.Arrays;
import java.util.concurrent.TimeUnit;

/**
 * Cuts a byte stream into frames by their declared lengths, reading in large chunks. After
 * {@link #next()} returns a length, the frame is at {@link #buffer()}[{@link #offset()}] until the
 * next call.
 *
 * <p>A stream cannot be resynchronised after garbage or an oversized length, so those end it
 * ({@link FrameException}); the caller drops the connection and keeps serving the others.
 *
 * <p>What a peer can make it hold is bounded by what the peer sent, not by what it announced: the
 * buffer starts at {@value #INITIAL} bytes and grows (doubling) only as bytes arrive: to
 * {@value #STREAMING} while reads keep filling it, beyond that only for a frame that needs it, so
 * a header announcing a 1 MiB frame costs nothing until the megabyte comes. A stream of large
 * frames (camera images) keeps the large buffer from one frame to the next, rather than growing it
 * again for each (which allocated and copied about twice the frame every time); the buffer shrinks
 * back to {@value #STREAMING} when a frame no larger than that comes (on an idle link, its next
 * keep-alive). With {@link Timeouts}, a stream that delivers
 * no whole frame within the first-frame timeout (from the start) or the idle timeout (from each
 * call of {@link #next()}) ends with {@link DropReason#TIMED_OUT}: a peer that stops in the
 * middle of a frame, or sends a byte now and then, cannot hold the connection.
 *
 * <p>Not thread-safe: one reader thread per connection.
 */
public final class FrameStreamReader {

    /** The buffer's size at first: what a connection that has sent nothing much costs. */
    public static final int INITIAL = 8 * 1024;
    /**
     * The size it grows to while bytes stream in (each read filling it), for reading in large
     * chunks; and the size it shrinks back to after a frame larger than that.
     */
    public static final int STREAMING = 64 * 1024;

    /** How a reader bounds the time a read may block: a socket's {@code SO_TIMEOUT}. */
    @FunctionalInterface
    public interface ReadTimeout {
        /**
         * @param millis the longest a read may block from now, > 0
         * @throws IOException if it cannot be set (the socket closed)
         */
        void set(int millis) throws IOException;
    }

    /**
     * The time limits of a stream.
     *
     * @param readTimeout      sets how long one read may block
     * @param firstFrameNanos  the longest wait for the first whole frame
     * @param idleNanos        the longest wait for each further whole frame
     */
    public record Timeouts(ReadTimeout readTimeout, long firstFrameNanos, long idleNanos) {
    }

    private final InputStream in;
    private final int maxFrameSize;
    private final Timeouts timeouts;
    private byte[] buf = new byte[INITIAL];
    private int start;
    private int end;
    private int pending;
    private long deadline;
    private boolean first = true;
    private int timeoutSet = -1;

    /**
     * A reader without time limits (for streams whose other end is trusted, and tests).
     *
     * @param in           the stream
     * @param maxFrameSize the largest frame accepted
     */
    public FrameStreamReader(InputStream in, int maxFrameSize) {
        this(in, maxFrameSize, null);
    }

    /**
     * @param in           the stream
     * @param maxFrameSize the largest frame accepted
     * @param timeouts     the time limits, or {@code null} for none
     */
    public FrameStreamReader(InputStream in, int maxFrameSize, Timeouts timeouts) {
        this.in = in;
        this.maxFrameSize = maxFrameSize;
        this.timeouts = timeouts;
        if (timeouts != null) {
            deadline = System.nanoTime() + timeouts.firstFrameNanos();
        }
    }

    /**
     * @return the next frame's length, or -1 at a clean end of stream (between frames)
     * @throws FrameException if the stream holds garbage, a frame above the maximum, ends inside a
     *                        frame, or a time limit passed
     * @throws IOException    if reading fails
     */
    public int next() throws IOException, FrameException {
        start += pending;
        pending = 0;
        if (timeouts != null && !first) {
            // counted from when the caller is done with the last frame (a listener may take long)
            deadline = System.nanoTime() + timeouts.idleNanos();
        }
        if (!fill(FrameCodec.PREFIX_LENGTH)) {
            if (end == start) {
                return -1;
            }
            throw new FrameException(DropReason.TRUNCATED, "stream ended " + (end - start) + " bytes into a frame prefix");
        }
        int length = FrameCodec.declaredLength(buf, start, maxFrameSize);
        if (buf.length > STREAMING && length <= STREAMING && end - start <= STREAMING) {
            // the large frames are done: give their memory back
            byte[] small = new byte[STREAMING];
            System.arraycopy(buf, start, small, 0, end - start);
            end -= start;
            start = 0;
            buf = small;
        }
        if (!fill(length)) {
            throw new FrameException(DropReason.TRUNCATED, "stream ended after " + (end - start) + " of a frame's " + length + " bytes");
        }
        pending = length;
        first = false;
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

    /** @return how many bytes after the current frame are buffered */
    public int buffered() {
        return end - start - pending;
    }

    /**
     * @return whether the frame after the current one is already whole in the buffer (or its
     *         prefix is bad), so that {@link #next()} returns without reading the stream
     */
    public boolean hasWholeFrame() {
        int at = start + pending;
        int have = end - at;
        if (have < FrameCodec.PREFIX_LENGTH) {
            return false;
        }
        try {
            return have >= FrameCodec.declaredLength(buf, at, maxFrameSize);
        } catch (FrameException e) {
            return true;
        }
    }

    /** @return the buffer's size now: what the stream holds of this connection's memory */
    public int capacity() {
        return buf.length;
    }

    private boolean fill(int needed) throws IOException, FrameException {
        if (end - start >= needed) {
            return true;
        }
        if (buf.length - start < needed && start > 0) {
            System.arraycopy(buf, start, buf, 0, end - start);
            end -= start;
            start = 0;
        }
        while (end - start < needed) {
            if (end == buf.length) {
                // full and the frame goes on: grow with what arrives, never beyond the frame
                buf = Arrays.copyOf(buf, (int) Math.min(needed, 2L * buf.length));
            }
            int space = buf.length - end;
            int n = read(needed);
            if (n < 0) {
                return false;
            }
            end += n;
            if (n == space && buf.length < STREAMING) {
                // the peer sends faster than one buffer a read: read in larger chunks
                buf = Arrays.copyOf(buf, buf.length * 2);
            }
        }
        return true;
    }

    private int read(int needed) throws IOException, FrameException {
        if (timeouts == null) {
            return in.read(buf, end, buf.length - end);
        }
        long left = deadline - System.nanoTime();
        if (left <= 0) {
            throw timedOut(needed);
        }
        int millis = (int) Math.max(1, Math.min(Integer.MAX_VALUE, TimeUnit.NANOSECONDS.toMillis(left) + 1));
        if (timeoutSet < 0 || Math.abs(millis - timeoutSet) > 20) {
            timeouts.readTimeout().set(millis);
            timeoutSet = millis;
        }
        try {
            return in.read(buf, end, buf.length - end);
        } catch (SocketTimeoutException e) {
            throw timedOut(needed);
        }
    }

    private FrameException timedOut(int needed) {
        long limit = TimeUnit.NANOSECONDS.toMillis(first ? timeouts.firstFrameNanos() : timeouts.idleNanos());
        String since = first ? "since it opened" : "since its last whole frame";
        return new FrameException(DropReason.TIMED_OUT, "no whole frame within " + limit + " ms " + since + " (" + arrived(needed) + ")");
    }

    /**
     * For a timeout enforced from outside (a timer that closes the connection): what arrived of
     * the frame the reader was waiting for. Call it on the reading thread, after a read failed.
     *
     * @return for example "nothing of a frame arrived" or "40 bytes arrived of a frame's 300"
     */
    public String arrived() {
        int needed = end - start >= FrameCodec.PREFIX_LENGTH ? safeLength() : FrameCodec.PREFIX_LENGTH;
        return arrived(needed);
    }

    /** @return whether no whole frame has been returned yet */
    public boolean beforeFirstFrame() {
        return first;
    }

    private int safeLength() {
        try {
            return FrameCodec.declaredLength(buf, start, maxFrameSize);
        } catch (FrameException e) {
            return FrameCodec.PREFIX_LENGTH;
        }
    }

    private String arrived(int needed) {
        return end == start ? "nothing of a frame arrived"
                : (end - start) + " bytes arrived" + (needed > FrameCodec.PREFIX_LENGTH ? " of a frame's " + needed : " of a frame prefix");
    }
}
