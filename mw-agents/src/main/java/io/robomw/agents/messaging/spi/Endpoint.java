package io.robomw.agents.messaging.spi;

import io.robomw.agents.messaging.Address;

/** Where a node receives: a listening socket, a bound datagram socket, a joined group, an RMI name. */
public interface Endpoint extends AutoCloseable {

    /** @return its address, with the port actually bound */
    Address address();

    /**
     * Sends a frame to everyone at this endpoint, for transports where that means something
     * (a multicast group); others do nothing.
     *
     * @param frame an encoded frame
     * @return whether the endpoint sent it
     * @throws java.io.IOException if sending failed
     */
    default boolean broadcast(byte[] frame) throws java.io.IOException {
        return false;
    }

    /**
     * @return whether {@link #broadcast} sends anything here; the node hands publications only to
     *         endpoints that say so (it publishes millions a second: a call per endpoint and
     *         publication is measurable)
     */
    default boolean broadcasts() {
        return false;
    }

    /** Stops receiving there. Idempotent. */
    @Override
    void close();
}
