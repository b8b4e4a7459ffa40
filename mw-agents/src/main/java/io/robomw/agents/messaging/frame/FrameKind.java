package io.robomw.agents.messaging.frame;

import io.robomw.agents.net.WireCode;
import io.robomw.agents.net.WireCodes;

import io.robomw.agents.messaging.DropReason;

/**
 * What a frame is for. Each kind travels as its {@link #code()} in the frame's {@code KIND} byte
 * (the table is in {@link FrameCodec}), never as its position here.
 */
public enum FrameKind implements WireCode {
    /** A point-to-point message ({@code sendMessage}); may be answered. */
    MESSAGE(1),
    /** The answer to a {@link #MESSAGE}, carrying its correlation id. */
    REPLY(2),
    /** A receiver could not handle a {@link #MESSAGE}; the payload is the reason as text. */
    ERROR(3),
    /** A publication on a topic ({@code publishMessage}). */
    PUBLISH(4),
    /** The sending peer wants the publications of the frame's topic. */
    SUBSCRIBE(5),
    /** The sending peer no longer wants the publications of the frame's topic. */
    UNSUBSCRIBE(6),
    /**
     * Nothing but "this link is alive": sent on a connection that has been silent for a third of
     * the idle timeout, so the peer does not close a quiet healthy link. Empty names and payload.
     */
    KEEPALIVE(7),
    /**
     * "Publications may reach me through shared memory": sent once by a node at the start of a
     * plain TCP connection to a peer on the loopback interface, when shared memory is on; the
     * payload says which host it runs on ({@link io.robomw.agents.messaging.shm.Handshake}). A node
     * that does not know this kind counts one dropped frame and goes on over TCP.
     */
    SHM_ASK(8),
    /**
     * The answer to {@link #SHM_ASK} from a node on the same host, before its first large
     * publication to the asker: which segment file to map and which consumed-sequence cell is
     * the asker's. Sent only to a peer that asked.
     */
    SHM_OFFER(9),
    /** The asker mapped the offered segment and checked it: large publications may come as {@link #PUBLISH_SHARED} now. */
    SHM_ACCEPT(10),
    /**
     * A publication whose payload is in the sender's shared-memory segment: the frame is the
     * {@link #PUBLISH} it stands for, but its PAYLOAD is a 16-byte reference (sequence, offset,
     * length: {@link io.robomw.agents.messaging.shm.SharedReference}). Sent only on a connection
     * whose peer accepted an offer, and never for a frame with an HMAC.
     */
    PUBLISH_SHARED(11);

    private static final WireCodes<FrameKind> CODES = WireCodes.of(FrameKind.class, "frame kind");

    private final int code;

    FrameKind(int code) {
        this.code = code;
    }

    /** @return the wire code */
    @Override
    public int code() {
        return code;
    }

    /**
     * @param code a {@code KIND} byte as received (unsigned)
     * @return its kind
     * @throws FrameException ({@link DropReason#MALFORMED}) naming the code if no kind has it
     */
    public static FrameKind fromCode(int code) throws FrameException {
        return CODES.find(code).orElseThrow(() -> new FrameException(DropReason.MALFORMED, CODES.unknown(code)));
    }
}
