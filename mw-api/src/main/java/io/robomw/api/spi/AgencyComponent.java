package io.robomw.api.spi;

import io.robomw.api.Agency;

import java.util.Optional;

/**
 * A robot's agency, as an {@link AgencyProvider} opens it: sending mobile agents, with an
 * in-process home where their results arrive. The robot closes it when it closes.
 */
public interface AgencyComponent extends Agency, AutoCloseable {

    /** @return the address of its home, once it has started */
    Optional<String> homeAddress();

    /** Closes its home; agents still travelling can no longer report to it. Idempotent. */
    @Override
    void close();
}
