package io.robomw.agents.messaging.frame;

/** What a frame is for. The code is the frame's {@code kind} byte. */
public enum FrameKind {
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
    UNSUBSCRIBE(6);

    private final int code;

    FrameKind(int code) {
        this.code = code;
    }

    /** @return the wire code */
    public int code() {
        return code;
    }

    /**
     * @param code a wire code
     * @return its kind, or {@code null} if it is none
     */
    public static FrameKind of(int code) {
        for (FrameKind k : values()) {
            if (k.code == code) {
                return k;
            }
        }
        return null;
    }
}
