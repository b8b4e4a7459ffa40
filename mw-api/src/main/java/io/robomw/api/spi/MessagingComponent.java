package io.robomw.api.spi;

import io.robomw.api.Messaging;

import java.util.List;

/**
 * A robot's communication component, as a {@link MessagingProvider} opens it: the paper's
 * messaging operations, plus where it receives. The robot closes it when it closes.
 */
public interface MessagingComponent extends Messaging, AutoCloseable {

    /** @return the addresses it receives at, with real ports; empty until it has started */
    List<String> addresses();

    /** Closes its sockets and threads. Idempotent. */
    @Override
    void close();
}
