package io.robomw.agents.messaging.spi;

import java.io.IOException;

/**
 * A way to send frames to one peer: a connection, a session, or a datagram socket and an address.
 * Replies and publications for a peer go through the channel its frames came on.
 */
public interface Channel {

    /** @return the peer, for logs and for matching replies, for example {@code tcp://127.0.0.1:41234} */
    String peer();

    /**
     * Sends one encoded frame. The channel copies it and writes its own stream sequence number
     * into the copy, so the same array may be sent on many channels. Keeps the order of sends.
     *
     * @param frame an encoded frame
     * @throws IOException if the channel is closed, or the peer did not take frames within the send timeout
     */
    void send(byte[] frame) throws IOException;

    /**
     * Sends one publication: by default its whole frame ({@link #send}). A transport that carries a
     * payload apart from its frame (an MQTT broker: the PUBLISH's payload) sends the
     * {@link Publication#head() head} and the {@link Publication#payload() payload} of one that
     * {@link Publication#travelsApart() travels apart}, without copying the payload into a frame.
     *
     * @param publication the publication
     * @throws IOException as {@link #send}
     */
    default void sendPublication(Publication publication) throws IOException {
        send(publication.frame());
    }

    /** @return the largest frame this channel can carry (one datagram for UDP and multicast) */
    default int maxFrameBytes() {
        return Integer.MAX_VALUE;
    }

    /** @return whether frames can still be sent */
    boolean isOpen();

    /**
     * @return {@code true} for a connection that reports when it closes (TCP, RMI): subscriptions
     *         made on it last until then; {@code false} for datagrams, whose subscriptions must be refreshed
     */
    boolean isConnection();

    /**
     * @param thread a thread
     * @return whether frames from this channel are delivered on that thread (waiting on it for a
     *         reply from this channel would block the reply)
     */
    boolean deliversOn(Thread thread);

    /**
     * @param nowNanos   now, from {@link System#nanoTime()}
     * @param limitNanos the send timeout
     * @return whether a write to the peer has been blocked longer than the limit (the node then closes the channel)
     */
    default boolean stuck(long nowNanos, long limitNanos) {
        return false;
    }

    /**
     * Sends a keep-alive frame if the channel has sent nothing for {@code silentNanos} and nothing
     * waits to be sent; never blocks (the node calls it from its housekeeping thread). Channels
     * whose peer does not time out idle links (datagrams, RMI sessions, brokers) ignore it.
     *
     * @param frame       an encoded {@code KEEPALIVE} frame
     * @param nowNanos    now, from {@link System#nanoTime()}
     * @param silentNanos how long the channel must have been silent
     * @return whether it was queued
     */
    default boolean keepAlive(byte[] frame, long nowNanos, long silentNanos) {
        return false;
    }

    /**
     * @return whether frames from it were sent to a group (multicast): a message there reaches
     *         every member, so one not meant for this node is ignored quietly rather than refused
     */
    default boolean isGroup() {
        return false;
    }

    /**
     * @return whether this channel leads to a broker that routes frames by their topic and receiver
     *         (MQTT): the node then hands it every publication and request itself, instead of waiting
     *         for the peer to subscribe
     */
    default boolean isBroker() {
        return false;
    }

    /** Closes the channel (for a datagram peer: forgets it). Idempotent. */
    void close();
}
