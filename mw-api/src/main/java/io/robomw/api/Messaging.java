package io.robomw.api;

import java.io.Serializable;
import java.time.Duration;
import java.util.UUID;

/**
 * The paper's communication component: point-to-point messages with replies, and
 * publish/subscribe on topics, optionally protected by a password.
 *
 * <p>Hosts are addresses whose scheme chooses the transport: {@code tcp://host:port},
 * {@code udp://host:port}, {@code multicast://group:port}, {@code rmi://host:port/name}.
 * A topic with a password delivers only messages carrying a valid HMAC made from it, and only to
 * listeners registered with it.
 *
 * <p>Requests and replies: {@link #sendMessage} returns the message's correlation id; the
 * receiver's listener answers with {@link #replyMessage}, and the sender collects the answer with
 * {@link #waitForReply(UUID, Duration)} (the reply to that request, safe when many threads send
 * at once) or the paper's {@link #waitForReply(String, String)} (the next reply on a topic from a
 * host). Every wait is bounded; a reply that does not come in time raises
 * {@link MessagingException}.
 *
 * <p>This interface is the contract of the Instruction Layer; the transports live in
 * {@code mw-agents}. A robot without a messaging component throws
 * {@link UnsupportedActionException} from every method.
 */
public interface Messaging {

    /**
     * Sends one message to one receiver and returns once it has been handed to the transport.
     *
     * @param name     the receiver's name at that host (a robot or an agent)
     * @param host     the receiver's address, for example {@code tcp://127.0.0.1:7000}
     * @param pass     the topic's password, or {@code null} for an open topic
     * @param topic    the topic
     * @param object   the payload; its class must be allowed by the receiver's deserialization filter
     * @param function what the receiver is asked to do with it
     * @return the correlation id of the message, which a reply carries
     */
    java.util.UUID sendMessage(String name, String host, String pass, String topic, Serializable object, String function);

    /**
     * Waits for the next reply on a topic from a host, for at most the configured default timeout
     * (never forever).
     *
     * @param topic the topic
     * @param host  the replying host's address
     * @return the reply
     * @throws MessagingException if no reply arrives within the default timeout
     */
    Message waitForReply(String topic, String host);

    /**
     * Waits for the next reply on a topic from a host, for at most {@code timeout}.
     *
     * @param topic   the topic
     * @param host    the replying host's address
     * @param timeout how long to wait
     * @return the reply
     * @throws MessagingException if no reply arrives in time
     */
    Message waitForReply(String topic, String host, Duration timeout);

    /**
     * Waits for the reply to one request, for at most {@code timeout}. Unlike
     * {@link #waitForReply(String, String, Duration)} this cannot take another thread's reply,
     * so it is the form to use when several requests are in flight on the same topic.
     *
     * @param correlationId what {@link #sendMessage} returned for the request
     * @param timeout       how long to wait
     * @return the reply
     * @throws MessagingException if no reply arrives in time
     */
    default Message waitForReply(UUID correlationId, Duration timeout) {
        throw new MessagingException("waitForReply(correlationId, timeout) is not supported by " + getClass().getName());
    }

    /**
     * Answers a message received through {@link #sendMessage}: the reply goes back to its
     * sender, carries the request's correlation id and, on a password-protected topic, an HMAC
     * made with the topic's password. Returns once the reply has been handed to the transport.
     *
     * @param request  the message being answered, as delivered to a {@link MessageListener}
     * @param object   the reply's payload, or {@code null}
     * @param function what the sender is told about it (for example {@code "ok"})
     * @throws MessagingException if the request's sender can no longer be reached
     */
    default void replyMessage(Message request, Serializable object, String function) {
        throw new MessagingException("replyMessage is not supported by " + getClass().getName());
    }

    /**
     * Publishes a message to every subscriber of a topic.
     *
     * @param topic    the topic
     * @param object   the payload
     * @param function what subscribers are asked to do with it
     * @param password the topic's password, or {@code null} for an open topic
     */
    void publishMessage(String topic, Serializable object, String function, String password);

    /**
     * Subscribes to a topic; its messages go to the listeners registered with
     * {@link #addMessageListener}.
     *
     * @param topic    the topic
     * @param password the topic's password, or {@code null} for an open topic
     */
    void subscribeMessage(String topic, String password);

    /**
     * Registers a listener for a topic. On a password-protected topic a listener is registered
     * only with the right password; a wrong one raises {@link MessagingException}.
     *
     * @param topic    the topic
     * @param password the topic's password, or {@code null}
     * @param listener called for each message, on a messaging thread
     */
    void addMessageListener(String topic, String password, MessageListener listener);

    /**
     * Unregisters a listener.
     *
     * @param topic    the topic
     * @param listener the listener
     */
    void removeMessageListener(String topic, MessageListener listener);
}
