package io.robomw.platform.link;

import java.io.ByteArrayOutputStream;
import java.io.IOException;
import java.time.Duration;
import java.util.ArrayDeque;
import java.util.Deque;

/**
 * A hand-written fake link: each read returns the next scripted piece (or throws a scripted loss),
 * written bytes are kept.
 */
final class ScriptedLink implements Link {

    /** Marks a scripted loss in the queue; compared by identity. */
    private static final byte[] LOSS = new byte[0];

    private final Deque<byte[]> pieces = new ArrayDeque<>();
    private final ByteArrayOutputStream written = new ByteArrayOutputStream();
    private boolean open;
    private int reads;

    /** Queues one piece; a read returns at most one piece, or part of it if asked for fewer bytes. */
    ScriptedLink deliver(byte[] piece) {
        pieces.add(piece);
        return this;
    }

    /** Queues a read that throws {@link LinkLostException}. */
    ScriptedLink deliverLoss() {
        pieces.add(LOSS);
        return this;
    }

    int reads() {
        return reads;
    }

    byte[] written() {
        return written.toByteArray();
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
        requireOpen();
        written.write(data, off, len);
    }

    @Override
    public int read(byte[] buf, int off, int len, Duration timeout) throws IOException {
        requireOpen();
        reads++;
        byte[] piece = pieces.poll();
        if (piece == null) {
            return 0;
        }
        if (piece == LOSS) {
            throw new LinkLostException(describe(), "scripted loss");
        }
        int n = Math.min(len, piece.length);
        System.arraycopy(piece, 0, buf, off, n);
        if (n < piece.length) {
            byte[] rest = new byte[piece.length - n];
            System.arraycopy(piece, n, rest, 0, rest.length);
            pieces.addFirst(rest);
        }
        return n;
    }

    private void requireOpen() throws IOException {
        if (!open) {
            throw new IOException(describe() + " is closed");
        }
    }

    @Override
    public String describe() {
        return "scripted";
    }

    @Override
    public void close() {
        open = false;
    }
}
