package io.robomw.agents.messaging.spi;

import io.robomw.agents.messaging.DropReason;
import io.robomw.agents.messaging.MessagingSettings;

import java.util.concurrent.ThreadFactory;

/** What a transport gets from its node: settings, and where received frames and events go. */
public interface TransportContext {

    /** @return the node's name, for thread names and logs */
    String nodeName();

    /** @return every receiver name the node answers to: its own and those added with {@code MessagingNode.answerTo} */
    java.util.Set<String> receiverNames();

    /** @return what the node announces about itself, for transports that can announce it (a broker) */
    io.robomw.agents.messaging.Presence presence();

    /** @return the node's settings */
    MessagingSettings settings();

    /**
     * Takes one received frame (exactly one, as framed by the transport). Called on the
     * transport's receiving thread, which runs listeners; never throws.
     *
     * @param buf    bytes holding the frame
     * @param offset where it starts
     * @param length its length
     * @param from   the channel it came on
     */
    void onFrame(byte[] buf, int offset, int length, Channel from);

    /**
     * Takes one received {@link io.robomw.agents.messaging.frame.FrameKind#PUBLISH_SHARED} frame with
     * the payload it refers to, which the transport took out of the peer's shared memory: the node
     * handles it as the {@code PUBLISH} it stands for. Called on the transport's receiving thread;
     * never throws.
     *
     * @param buf     bytes holding the reference frame
     * @param offset  where it starts
     * @param length  its length
     * @param payload the publication's payload
     * @param from    the channel it came on
     */
    void onFrame(byte[] buf, int offset, int length, byte[] payload, Channel from);

    /**
     * Counts and logs input the transport could not even frame (garbage on a stream, a datagram
     * too short, a declared length above the maximum).
     *
     * @param reason why
     * @param where  the peer or socket
     * @param detail what was wrong
     */
    void dropped(DropReason reason, String where, String detail);

    /**
     * @param why why the node refuses a connection (it serves its maximum already)
     * @return an encoded frame saying so (an ERROR with correlation id zero), to write before closing it
     */
    byte[] refusal(String why);

    /**
     * A connection (accepted or opened) is ready: the node sends it its subscriptions.
     *
     * @param channel the connection
     */
    void opened(Channel channel);

    /**
     * A connection closed: the node forgets its subscriptions and fails replies expected on it.
     *
     * @param channel the connection
     */
    void closed(Channel channel);

    /**
     * @return where what a transport's threads catch goes: a failure of one unit of their work (a
     *         frame, a connection) as survived, what ends a thread as its death
     */
    io.robomw.api.spi.FailurePolicy failures();

    /**
     * @param role what the threads do, for example {@code tcp-read-127.0.0.1:7000}
     * @return a factory of daemon threads named after the node and the role, which report whatever
     *         ends them to {@link #failures()}
     */
    ThreadFactory threads(String role);
}
