package io.robomw.agents.messaging.shm;

import io.robomw.agents.messaging.DropReason;
import io.robomw.agents.messaging.frame.Frame;
import io.robomw.agents.messaging.frame.FrameCodec;
import io.robomw.agents.messaging.frame.FrameException;
import io.robomw.agents.messaging.frame.FrameKind;
import io.robomw.agents.messaging.security.PayloadCodec;

import java.io.IOException;
import java.nio.BufferUnderflowException;
import java.nio.ByteBuffer;
import java.nio.ByteOrder;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.InvalidPathException;
import java.nio.file.Path;
import java.util.Optional;
import java.util.UUID;

/**
 * The shared-memory handshake on a TCP connection: the frames' payloads, big-endian.
 *
 * <pre>
 * SHM_ASK     VERSION u8 = 1 | HOST ID (UTF-8, the rest: the Linux boot id, /proc/sys/kernel/random/boot_id)
 * SHM_OFFER   VERSION u8 = 1 | CELL u32 | NONCE u64 | FILE (UTF-8, the rest: the segment's absolute path)
 * SHM_ACCEPT  VERSION u8 = 1 | CELL u32 | NONCE u64
 * </pre>
 *
 * <p>A node asks at the start of a plain TCP connection whose peer is on the loopback interface.
 * The peer offers before its first large publication on that connection, if the asker's host id is
 * its own. The asker maps the file, checks it ({@link SegmentView#open}) and accepts; from then on
 * the peer may send {@link FrameKind#PUBLISH_SHARED}. A version other than 1 is not answered (the
 * connection goes on over TCP); a payload that is not of this form is a {@link DropReason#MALFORMED}
 * frame. The frames carry no names, source or HMAC: the transport answers them itself.
 *
 * <p>Stateless.
 */
public final class Handshake {

    /** The version of the handshake's payloads. */
    public static final int VERSION = 1;
    /** The longest host id or file name accepted, in bytes. */
    public static final int MAX_TEXT_BYTES = 1024;
    private static final Path BOOT_ID = Path.of("/proc/sys/kernel/random/boot_id");

    /** @param hostId the asker's host id */
    public record Ask(String hostId) {
    }

    /** @param cell the asker's cell @param nonce the segment's nonce @param file the segment file */
    public record Offer(int cell, long nonce, Path file) {
    }

    /** @param cell the cell offered @param nonce the nonce offered */
    public record Accept(int cell, long nonce) {
    }

    private Handshake() {
    }

    /**
     * @return this host's identity for the handshake: the Linux boot id; empty where there is none
     *         (no {@code /proc}, or no {@code /dev/shm}: no shared memory there)
     */
    public static Optional<String> hostId() {
        try {
            if (!Files.isDirectory(SharedSegment.DIRECTORY)) {
                return Optional.empty();
            }
            String id = Files.readString(BOOT_ID, StandardCharsets.US_ASCII).trim();
            return id.isEmpty() ? Optional.empty() : Optional.of(id);
        } catch (IOException | SecurityException e) {
            return Optional.empty();
        }
    }

    /** @param ask what to ask with @return the SHM_ASK frame */
    public static byte[] ask(Ask ask) {
        byte[] id = ask.hostId().getBytes(StandardCharsets.UTF_8);
        return frame(FrameKind.SHM_ASK, ByteBuffer.allocate(1 + id.length).put((byte) VERSION).put(id).array());
    }

    /** @param offer the offer @return the SHM_OFFER frame */
    public static byte[] offer(Offer offer) {
        byte[] file = offer.file().toString().getBytes(StandardCharsets.UTF_8);
        return frame(FrameKind.SHM_OFFER, ByteBuffer.allocate(13 + file.length).put((byte) VERSION).putInt(offer.cell()).putLong(offer.nonce()).put(file).array());
    }

    /** @param accept the acceptance @return the SHM_ACCEPT frame */
    public static byte[] accept(Accept accept) {
        return frame(FrameKind.SHM_ACCEPT, ByteBuffer.allocate(13).put((byte) VERSION).putInt(accept.cell()).putLong(accept.nonce()).array());
    }

    /**
     * @param frame a decoded SHM_ASK
     * @return the ask, or empty for a version this node does not speak
     * @throws FrameException if the payload is not an ask
     */
    public static Optional<Ask> readAsk(Frame frame) throws FrameException {
        ByteBuffer in = payload(frame, FrameKind.SHM_ASK, 1);
        if (version(in) != VERSION) {
            return Optional.empty();
        }
        return Optional.of(new Ask(text(in, frame)));
    }

    /**
     * @param frame a decoded SHM_OFFER
     * @return the offer, or empty for a version this node does not speak
     * @throws FrameException if the payload is not an offer
     */
    public static Optional<Offer> readOffer(Frame frame) throws FrameException {
        ByteBuffer in = payload(frame, FrameKind.SHM_OFFER, 1);
        if (version(in) != VERSION) {
            return Optional.empty();
        }
        try {
            int cell = in.getInt();
            long nonce = in.getLong();
            String file = text(in, frame);
            return Optional.of(new Offer(cell, nonce, Path.of(file)));
        } catch (BufferUnderflowException | InvalidPathException e) {
            throw new FrameException(DropReason.MALFORMED, "SHM_OFFER of " + frame.payload().length + " bytes is not an offer: " + e);
        }
    }

    /**
     * @param frame a decoded SHM_ACCEPT
     * @return the acceptance, or empty for a version this node does not speak
     * @throws FrameException if the payload is not an acceptance
     */
    public static Optional<Accept> readAccept(Frame frame) throws FrameException {
        ByteBuffer in = payload(frame, FrameKind.SHM_ACCEPT, 1);
        if (version(in) != VERSION) {
            return Optional.empty();
        }
        if (in.remaining() != 12) {
            throw new FrameException(DropReason.MALFORMED, "SHM_ACCEPT of " + frame.payload().length + " bytes; version 1 has 13");
        }
        return Optional.of(new Accept(in.getInt(), in.getLong()));
    }

    private static int version(ByteBuffer in) {
        return in.get() & 0xFF;
    }

    private static ByteBuffer payload(Frame frame, FrameKind kind, int atLeast) throws FrameException {
        if (frame.kind() != kind) {
            throw new IllegalArgumentException("expected a " + kind + " frame, got " + frame.kind());
        }
        if (frame.payload().length < atLeast || frame.payload().length > MAX_TEXT_BYTES + 13) {
            throw new FrameException(DropReason.MALFORMED, kind + " with a payload of " + frame.payload().length + " bytes (1 to "
                    + (MAX_TEXT_BYTES + 13) + ")");
        }
        return ByteBuffer.wrap(frame.payload()).order(ByteOrder.BIG_ENDIAN);
    }

    private static String text(ByteBuffer in, Frame frame) throws FrameException {
        byte[] b = new byte[in.remaining()];
        in.get(b);
        if (b.length == 0 || b.length > MAX_TEXT_BYTES) {
            throw new FrameException(DropReason.MALFORMED, frame.kind() + " names " + b.length + " bytes of text (1 to " + MAX_TEXT_BYTES + ")");
        }
        return new String(b, StandardCharsets.UTF_8);
    }

    private static byte[] frame(FrameKind kind, byte[] payload) {
        return FrameCodec.encode(new Frame(kind, 0, 0, 0, new UUID(0, 0), 0, "", "", "", "", PayloadCodec.BYTES, payload, false), false);
    }
}
