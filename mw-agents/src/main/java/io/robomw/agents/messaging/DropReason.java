package io.robomw.agents.messaging;

/**
 * Why an incoming frame (or a whole connection) was dropped. Each reason has its own counter in
 * {@link MessagingStats}.
 */
public enum DropReason {
    /** The frame ended before its declared length (a datagram cut short, a connection closed mid-frame). */
    TRUNCATED,
    /** The frame declared a length above the maximum frame size. */
    OVERSIZED,
    /** Not a RoboMW frame: wrong magic or version, or lengths that do not add up. */
    MALFORMED,
    /** A password-protected topic, and the frame carried no HMAC. */
    MISSING_MAC,
    /** The HMAC did not verify: the sender used another password, or the frame was changed. */
    BAD_MAC,
    /**
     * An authenticated frame that was already received (same source and message number), also before
     * the node restarted ({@link io.robomw.agents.messaging.security.ReplayStore}).
     */
    REPLAYED,
    /** An authenticated frame whose timestamp is further from this host's clock than allowed. */
    STALE,
    /** The payload's class is not on the deserialization allow-list, or broke its limits. */
    REJECTED_CLASS,
    /** A message for a receiver name this node does not answer to. */
    UNKNOWN_RECEIVER,
    /** A message or publication on a topic nobody here listens to. */
    NO_LISTENER,
    /** A reply to no request this node sent (or one forgotten long ago). */
    UNSOLICITED_REPLY,
    /**
     * A peer passed one of the node's {@link PeerLimits}: a connection beyond the maximum (refused),
     * a subscription beyond the per-peer or total maximum, or to a topic longer than allowed.
     */
    LIMIT,
    /**
     * A connection delivered no whole frame within the first-frame or idle timeout (it stopped in the
     * middle of a frame, trickled bytes, or never spoke); it was closed.
     */
    TIMED_OUT,
    /**
     * A frame whose payload is sealed (encrypted under a topic's password) on a topic this node
     * registered without a password: it cannot be read here.
     */
    ENCRYPTED
}
