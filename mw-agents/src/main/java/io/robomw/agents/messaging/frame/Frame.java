package io.robomw.agents.messaging.frame;

import java.util.UUID;

/**
 * One decoded frame (see {@link FrameCodec} for the layout). The payload is still encoded: it is
 * deserialized only after the frame has been authenticated.
 *
 * @param kind            what the frame is for
 * @param streamSequence  position in the sending link's stream (not authenticated; for loss detection)
 * @param source          random id of the sending node instance
 * @param messageNumber   per-source number, increasing; with {@code source} it identifies the frame for replay detection
 * @param correlationId   the request's id (for a request: its own id)
 * @param timestampMicros when the sender made it, microseconds since the epoch
 * @param sender          the sender's name
 * @param receiver        the receiver's name, or empty
 * @param topic           the topic
 * @param function        what the receiver is asked to do
 * @param payloadType     how the payload is encoded ({@link io.robomw.agents.messaging.security.PayloadCodec})
 * @param payload         the encoded payload
 * @param authenticated   whether the frame carries an HMAC (not yet verified)
 */
public record Frame(FrameKind kind, long streamSequence, long source, long messageNumber, UUID correlationId,
                    long timestampMicros, String sender, String receiver, String topic, String function,
                    int payloadType, byte[] payload, boolean authenticated) {
}
