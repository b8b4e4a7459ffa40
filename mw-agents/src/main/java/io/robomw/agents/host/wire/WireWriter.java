package io.robomw.agents.host.wire;

import io.robomw.agents.host.security.FrameTag;
import javax.crypto.spec.SecretKeySpec;
import java.io.IOException;
import java.io.OutputStream;
import java.nio.ByteBuffer;
import java.nio.channels.SocketChannel;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.CompletionException;
import java.util.concurrent.Executor;
import java.util.concurrent.RejectedExecutionException;

/**
 * Writes agent wire frames ({@link WireFrames}) to one connection, straight from the arrays that
 * hold them: on a plain connection a frame of up to {@value #ONE_WRITE} bytes of body goes in one
 * gathering write (header, the body where it lies, tag) after its tag is computed. A larger one is
 * written in pieces of that size while a tagger thread ({@link #WireWriter(Out, Executor)}) computes
 * its tag over the same bytes, and the tag follows the last piece: on two processors the tag (about
 * 0.2 ms a megabyte) no longer adds to the copies into the socket, and the peer starts reading and
 * checking the first piece at once. Without a tagger (or when it refuses the work: the host is
 * closing) each piece is put through the tag just before it is written. The bytes sent are the same
 * either way. On TLS the pieces go through the TLS socket's stream, which writes them as TLS
 * records. Not thread-safe: one writer per connection, one frame at a time; {@link #write} returns
 * only once the tagger is done with the frame, so the caller may reuse the body's array.
 */
public final class WireWriter {

    /** The largest body written in one write; larger ones go in pieces of this size. */
    public static final int ONE_WRITE = 256 * 1024;

    /** Where a writer's bytes go. */
    public interface Out {
        /** Writes every remaining byte of the buffers, in order. */
        void write(ByteBuffer... parts) throws IOException;
    }

    /** @return the gathering writes of a blocking channel */
    public static Out of(SocketChannel channel) {
        return parts -> {
            long left = 0;
            for (ByteBuffer p : parts) {
                left += p.remaining();
            }
            while (left > 0) {
                left -= channel.write(parts);
            }
        };
    }

    /** @return writes to a stream (TLS: a buffered one over the TLS socket's, so a small frame is one TLS record), then a flush */
    public static Out of(OutputStream stream) {
        return parts -> {
            for (ByteBuffer p : parts) {
                stream.write(p.array(), p.arrayOffset() + p.position(), p.remaining());
                p.position(p.limit());
            }
            stream.flush();
        };
    }

    private final Out out;
    private final FrameTag tag = new FrameTag();
    private final Executor tagger;
    /** A small frame's header, and the parts of its one gathering write: reused frame after frame (one frame at a time). */
    private final byte[] smallHeader = new byte[WireFrames.HEADER];
    private final ByteBuffer smallHeaderBuffer = ByteBuffer.wrap(smallHeader);
    private final ByteBuffer[] parts = new ByteBuffer[3];

    /** A writer that tags every frame on the writing thread. */
    public WireWriter(Out out) {
        this(out, null);
    }

    /**
     * @param out    where the bytes go
     * @param tagger computes the tag of a frame larger than {@value #ONE_WRITE} bytes of body while it is written, or {@code null}
     */
    public WireWriter(Out out, Executor tagger) {
        this.out = out;
        this.tagger = tagger;
    }

    /**
     * Writes a tagged frame.
     *
     * @param key       the session's frame key
     * @param direction {@link WireFrames#DIRECTION_REQUEST} or {@link WireFrames#DIRECTION_REPLY}
     * @param code      the operation or status
     * @param session   the session id
     * @param seq       the request's sequence number
     * @param body      holds the body
     * @param off       where it starts
     * @param len       its length
     */
    public void write(SecretKeySpec key, int direction, int code, long session, long seq, byte[] body, int off, int len) throws IOException {
        tag.start(key, direction, seq, false);
        if (len <= ONE_WRITE) {
            WireFrames.header(smallHeader, code, session, seq, len);
            tag.update(smallHeader, 0, smallHeader.length);
            tag.update(body, off, len);
            byte[] t = tag.finish();
            parts[0] = smallHeaderBuffer.clear();
            parts[1] = ByteBuffer.wrap(body, off, len);
            parts[2] = tagBuffer(t);
            try {
                out.write(parts);
            } finally {
                parts[1] = null; // the body's array is the caller's again
            }
            return;
        }
        byte[] header = WireFrames.header(code, session, seq, len);
        tag.update(header, 0, header.length);
        CompletableFuture<byte[]> sealed = null;
        if (tagger != null) {
            try {
                sealed = CompletableFuture.supplyAsync(() -> {
                    tag.update(body, off, len);
                    return tag.finish();
                }, tagger);
            } catch (RejectedExecutionException closing) {
                // tagged here, piece by piece
            }
        }
        if (sealed != null) {
            writeWhileTagged(header, body, off, len, sealed);
            return;
        }
        int end = off + len;
        for (int at = off; at < end; at += ONE_WRITE) {
            int n = Math.min(ONE_WRITE, end - at);
            tag.update(body, at, n);
            ByteBuffer piece = ByteBuffer.wrap(body, at, n);
            if (at == off) {
                out.write(ByteBuffer.wrap(header), piece);
            } else if (at + n == end) {
                out.write(piece, ByteBuffer.wrap(tag.finish()));
            } else {
                out.write(piece);
            }
        }
    }

    private ByteBuffer tagBuffer;

    /** @return a buffer over the tag's array (FrameTag's own, the same frame after frame), wrapped once */
    private ByteBuffer tagBuffer(byte[] t) {
        ByteBuffer b = tagBuffer;
        if (b == null || b.array() != t) {
            b = ByteBuffer.wrap(t);
            tagBuffer = b;
        }
        return b.clear();
    }

    /** Writes the pieces of a large frame while {@code sealed} computes its tag, then the tag; returns once the tagger is done. */
    private void writeWhileTagged(byte[] header, byte[] body, int off, int len, CompletableFuture<byte[]> sealed) throws IOException {
        boolean written = false;
        try {
            int end = off + len;
            for (int at = off; at < end; at += ONE_WRITE) {
                ByteBuffer piece = ByteBuffer.wrap(body, at, Math.min(ONE_WRITE, end - at));
                if (at == off) {
                    out.write(ByteBuffer.wrap(header), piece);
                } else {
                    out.write(piece);
                }
            }
            byte[] t;
            try {
                t = sealed.join();
            } catch (CompletionException e) {
                Throwable c = e.getCause();
                throw c instanceof RuntimeException r ? r : new IllegalStateException("the frame's tag failed: " + c, c);
            }
            out.write(ByteBuffer.wrap(t));
            written = true;
        } finally {
            if (!written) {
                // The write failed: wait until the tagger is done with the body and the cipher before both are reused.
                try {
                    sealed.join();
                } catch (RuntimeException ignored) {
                    // the frame failed anyway
                }
            }
        }
    }

    /** Writes an untagged reply (UNKNOWN_SESSION, FRAME_REFUSED): information for the peer, not proof. */
    void writeUntagged(int status, long session, long seq, byte[] body) throws IOException {
        out.write(ByteBuffer.wrap(WireFrames.header(status, session, seq, body.length)), ByteBuffer.wrap(body), ByteBuffer.wrap(new byte[WireFrames.TAG]));
    }
}
