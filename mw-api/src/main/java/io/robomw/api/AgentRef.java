package io.robomw.api;

import java.io.Serializable;
import java.util.UUID;
import java.util.concurrent.CompletableFuture;

/**
 * A handle on a travelling agent, kept by whoever sent it (after Aglets' {@code AgletProxy}).
 */
public interface AgentRef {

    /** @return the agent's id, the same on every host it visits */
    UUID id();

    /** @return the address of the host the agent was last known to be at */
    String location();

    /** @return the agent's last known status */
    AgentStatus status();

    /** @return completes with the result the agent sends home when its trip ends */
    CompletableFuture<Serializable> result();

    /** Brings the agent back to its home host from wherever it is. */
    void retract();

    /** Disposes of the agent wherever it is. */
    void dispose();
}
