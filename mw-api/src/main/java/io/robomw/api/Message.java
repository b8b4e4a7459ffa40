package io.robomw.api;

import java.io.Serializable;
import java.time.Instant;
import java.util.Objects;
import java.util.UUID;

/**
 * One message, as delivered to a {@link MessageListener} or returned by
 * {@link Messaging#waitForReply}.
 *
 * @param sender        the sender's name
 * @param topic         the topic
 * @param function      what the receiver is asked to do with the payload
 * @param payload       the payload, or {@code null}
 * @param correlationId the id that ties a reply to its request
 * @param timestamp     when the sender created it
 */
public record Message(String sender, String topic, String function, Serializable payload,
                      UUID correlationId, Instant timestamp) implements Serializable {

    /** Checks that every field but the payload is present. */
    public Message {
        Objects.requireNonNull(sender, "sender");
        Objects.requireNonNull(topic, "topic");
        Objects.requireNonNull(function, "function");
        Objects.requireNonNull(correlationId, "correlationId");
        Objects.requireNonNull(timestamp, "timestamp");
    }
}
