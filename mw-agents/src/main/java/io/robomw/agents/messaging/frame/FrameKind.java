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
    KEEPALIVE(7);

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
