package io.robomw.agents.messaging.spi;

import io.robomw.agents.messaging.Address;

import java.io.IOException;

/**
 * One node's use of one kind of address. Hands every frame it receives to
 * {@link TransportContext#onFrame}, with the {@link Channel} that answers go back on.
 *
 * <p>Thread-safe. Owned by one node, which closes it.
 */
public interface Transport extends AutoCloseable {

    /**
     * Starts receiving at an address: listens (TCP, RMI), binds a socket (UDP) or joins a group
     * (multicast).
     *
     * @param address where; port 0 picks a free port
     * @return the endpoint, whose address has the real port
     * @throws IOException if the address cannot be used; the message names it
     */
    Endpoint bind(io.robomw.agents.messaging.Address address) throws IOException;

    /**
     * Opens a link for sending to an address (and receiving what comes back on it).
     *
     * @param address where to
     * @return the link
     * @throws IOException if the peer cannot be reached within the connect timeout
     */
    Link connect(Address address) throws IOException;

    /**
     * The node now answers to another receiver name as well ({@code MessagingNode.answerTo}): a
     * transport that must ask for a receiver's messages (a broker subscription) does it now; the
     * names known when it starts are in {@link TransportContext#receiverNames()}.
     *
     * @param receiverName the new name
     */
    default void answerTo(String receiverName) {
    }

    /** Closes every endpoint and link of this transport. Idempotent. */
    @Override
    void close();
}
