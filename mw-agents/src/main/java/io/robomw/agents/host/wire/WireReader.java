package io.robomw.agents.host.wire;

import io.robomw.agents.host.security.FrameTag;
import java.io.IOException;
import java.io.InputStream;
import java.net.Socket;
import java.net.SocketTimeoutException;

/**
 * Reads agent wire frames ({@link WireFrames}) from one connection: a header, then the whole frame
 * into one array (header, body, tag: the body is used where it lies), feeding the frame's tag as
 * the bytes arrive. The array is the connection's own and is reused by the next frame when it is
 * large enough and at most {@link #KEEP_MAX} bytes, so a connection that carries large agents
 * allocates (and G1 zeroes) their megabytes once rather than at every hop; a frame is used only
 * up to its length, and the array is grown only after the frame's header has passed the caller's
 * checks. Reads up to {@link #AHEAD} bytes at once, so a small frame comes in one read with its
 * header. Optionally each frame must arrive by a deadline (the socket's read timeout is set to what
 * is left before each read). Not thread-safe: one reader per connection, and a frame's array is
 * valid only until the next {@link #frame} call.
 */
public final class WireReader {

    /** How much a read asks the socket for while no frame's body is being read. */
    static final int AHEAD = 64 * 1024;
    /** The largest frame array a connection keeps for the next frame; a larger frame gets an array of its own, dropped after it. */
    public static final int KEEP_MAX = 4 * 1024 * 1024;

    /** Which frames' arrays a reader reuses for the next frame. */
    public enum Reuse {
        /** Only a frame of more than {@link #AHEAD} bytes: a smaller one gets an array of its own, which whoever serves it may keep. */
        LARGE_FRAMES,
        /** Every frame of up to {@link #KEEP_MAX} bytes: for a reader whose caller copies out what it keeps (a peer reading replies). */
        EVERY_FRAME
    }

    private final InputStream in;
    private final Socket socket;
    private final Reuse reuse;
    private final byte[] ahead = new byte[AHEAD];
    /** The array the last frame was read into, reused by the next one that fits; {@code null} until a frame of more than {@link #AHEAD} bytes. */
    private byte[] kept;
    private int pos;
    private int limit;
    private long deadline;
    private String deadlineWhat;

    /**
     * @param in     the connection's input
     * @param socket the socket whose read timeout enforces deadlines, or {@code null} for none (a byte array in a test)
     */
    public WireReader(InputStream in, Socket socket) {
        this(in, socket, Reuse.LARGE_FRAMES);
    }

    /**
     * @param in     the connection's input
     * @param socket the socket whose read timeout enforces deadlines, or {@code null} for none
     * @param reuse  which frames' arrays are reused
     */
    public WireReader(InputStream in, Socket socket, Reuse reuse) {
        this.in = in;
        this.socket = socket;
        this.reuse = reuse;
    }

    /**
     * @param nanoTime when the frames read from now must be complete (System.nanoTime), 0 for no deadline
     * @param what     what the deadline is, for the error
     */
    void deadline(long nanoTime, String what) {
        this.deadline = nanoTime;
        this.deadlineWhat = what;
    }

    /** @return whether bytes of a next frame have been read already */
    boolean buffered() {
        return limit > pos;
    }

    /**
     * @return the next frame's header, or {@code null} if the stream ended cleanly before it
     * @throws WireFrames.FrameRefused if the stream ends within a header
     * @throws IOException             if the connection fails or the deadline passes
     */
    public WireFrames.Header header() throws IOException {
        if (pos > 0 && limit - pos < WireFrames.HEADER) {
            System.arraycopy(ahead, pos, ahead, 0, limit - pos);
            limit -= pos;
            pos = 0;
        }
        while (limit - pos < WireFrames.HEADER) {
            int n = read(ahead, limit, ahead.length - limit);
            if (n < 0) {
                if (limit == pos) {
                    return null;
                }
                throw new WireFrames.FrameRefused("the connection ended within a frame's header, after " + (limit - pos) + " of its "
                        + WireFrames.HEADER + " bytes");
            }
            limit += n;
        }
        return WireFrames.Header.read(ahead, pos);
    }

    /**
     * Reads the frame whose header {@link #header()} just returned, into one array: the
     * connection's own (reused, possibly longer than the frame) or, for a frame of more than
     * {@link #KEEP_MAX} bytes, one of its own. Only the first {@link WireFrames.Header#frameLength()}
     * bytes are the frame; the array holds it until the next call.
     *
     * @param h   its header (its length checked against the limits by the caller)
     * @param tag where the header and body go as they arrive (started by the caller), or {@code null}
     * @return the array holding the frame (header, body, tag) from index 0
     * @throws WireFrames.FrameRefused if the stream ends within the frame
     * @throws IOException             if the connection fails or the deadline passes
     */
    public byte[] frame(WireFrames.Header h, FrameTag tag) throws IOException {
        int total = Math.toIntExact(h.frameLength());
        int signed = total - WireFrames.TAG;
        byte[] f = arrayFor(total);
        int at = Math.min(limit - pos, total);
        System.arraycopy(ahead, pos, f, 0, at);
        pos += at;
        int fed = 0;
        if (tag != null) {
            fed = Math.min(at, signed);
            tag.update(f, 0, fed);
        }
        while (at < total) {
            int n = read(f, at, total - at);
            if (n < 0) {
                throw new WireFrames.FrameRefused("the connection ended within a frame, after " + at + " of its " + total + " bytes");
            }
            at += n;
            if (tag != null && fed < signed) {
                int upto = Math.min(at, signed);
                tag.update(f, fed, upto - fed);
                fed = upto;
            }
        }
        return f;
    }

    /** @return an array of at least {@code total} bytes: the kept one if it is long enough, else a new one (kept if not too large) */
    private byte[] arrayFor(int total) {
        if (kept != null && kept.length >= total) {
            return kept;
        }
        byte[] f = new byte[total];
        if (total <= KEEP_MAX && (total > AHEAD || reuse == Reuse.EVERY_FRAME)) {
            kept = f;
        }
        return f;
    }

    private int read(byte[] b, int off, int len) throws IOException {
        if (deadline != 0 && socket != null) {
            long left = deadline - System.nanoTime();
            if (left <= 0) {
                throw new SocketTimeoutException(deadlineWhat);
            }
            socket.setSoTimeout((int) Math.max(1, Math.min(Integer.MAX_VALUE, left / 1_000_000)));
        }
        try {
            return in.read(b, off, len);
        } catch (SocketTimeoutException e) {
            throw deadline != 0 ? new SocketTimeoutException(deadlineWhat) : e;
        }
    }
}
