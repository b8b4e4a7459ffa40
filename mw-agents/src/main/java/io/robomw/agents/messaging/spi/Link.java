package io.robomw.agents.messaging.spi;

import io.robomw.agents.messaging.Address;

/** A channel this node opened to an address, for sending messages and subscriptions there. */
public interface Link extends Channel, AutoCloseable {

    /** @return the address it was opened to */
    Address address();

    /** Closes it. Idempotent. */
    @Override
    void close();
}
