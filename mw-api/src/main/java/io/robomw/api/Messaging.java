package io.robomw.api;

import java.io.Serializable;
import java.time.Duration;

/**
 * The paper's communication component: point-to-point messages with replies, and
 * publish/subscribe on topics, optionally protected by a password.
 *
 * <p>Hosts are addresses whose scheme chooses the transport: {@code tcp://host:port},
 * {@code udp://host:port}, {@code multicast://group:port}, {@code rmi://host:port/name}.
 * A topic with a password delivers only messages carrying a valid HMAC made from it, and only to
 * listeners registered with it.
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
     * @throws RobotException if no reply arrives within the default timeout
     */
    Message waitForReply(String topic, String host);

    /**
     * Waits for the next reply on a topic from a host, for at most {@code timeout}.
     *
     * @param topic   the topic
     * @param host    the replying host's address
     * @param timeout how long to wait
     * @return the reply
     * @throws RobotException if no reply arrives in time
     */
    Message waitForReply(String topic, String host, Duration timeout);

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
     * only with the right password.
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
