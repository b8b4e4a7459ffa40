package io.robomw.platform.ev3;

import io.robomw.platform.link.Link;

import java.io.IOException;
import java.time.Duration;
import java.util.ArrayDeque;
import java.util.ArrayList;
import java.util.Arrays;
import java.util.Deque;
import java.util.List;
import java.util.function.Function;

/**
 * A hand-written fake brick link: each frame written is kept, and a responder turns it into the
 * pieces later reads return (one piece, or part of it, per read; no piece left reads as a timeout).
 */
final class FakeEv3Link implements Link {

    private final Function<byte[], List<byte[]>> responder;
    private final Deque<byte[]> pieces = new ArrayDeque<>();
    private final List<byte[]> written = new ArrayList<>();
    private boolean open;

    /**
     * @param responder from a written frame to the pieces of what the brick sends back
     */
    FakeEv3Link(Function<byte[], List<byte[]>> responder) {
        this.responder = responder;
    }

    /** @return every frame written, in order */
    List<byte[]> written() {
        return written;
    }

    @Override
    public void open() {
        open = true;
    }

    @Override
    public boolean isOpen() {
        return open;
    }

    @Override
    public void write(byte[] data, int off, int len) throws IOException {
        if (!open) {
            throw new IOException("fake link closed");
        }
        byte[] frame = Arrays.copyOfRange(data, off, off + len);
        written.add(frame);
        pieces.addAll(responder.apply(frame));
    }

    @Override
    public int read(byte[] buf, int off, int len, Duration timeout) throws IOException {
        if (!open) {
            throw new IOException("fake link closed");
        }
        byte[] piece = pieces.poll();
        if (piece == null) {
            return 0;
        }
        int n = Math.min(len, piece.length);
        System.arraycopy(piece, 0, buf, off, n);
        if (n < piece.length) {
            pieces.addFirst(Arrays.copyOfRange(piece, n, piece.length));
        }
        return n;
    }

    @Override
    public String describe() {
        return "fake ev3 link";
    }

    @Override
    public void close() {
        open = false;
    }

    /**
     * @param frame a command frame
     * @param globals its reply's globals
     * @return a DIRECT_REPLY echoing its counter
     */
    static byte[] okReply(byte[] frame, byte[] globals) {
        return Ev3Reply.ok(Ev3Frame.counter(frame), globals).encode();
    }

    /**
     * @param bytes bytes
     * @return them as single-byte pieces
     */
    static List<byte[]> oneByteAtATime(byte[] bytes) {
        List<byte[]> out = new ArrayList<>();
        for (byte b : bytes) {
            out.add(new byte[]{b});
        }
        return out;
    }
}
