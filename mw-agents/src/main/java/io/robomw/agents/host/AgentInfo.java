package io.robomw.agents.host;

import io.robomw.api.AgentStatus;

import java.util.UUID;

/**
 * One agent at a host, as {@code mw agents} lists it.
 *
 * @param id        the agent
 * @param className its class
 * @param status    what it is doing
 * @param hop       the hop that brought it here
 * @param home      where its results go
 * @param pending   an operator's request that takes effect when its callback returns
 */
public record AgentInfo(UUID id, String className, AgentStatus status, long hop, String home, Pending pending) {

    /**
     * An operator's retract or dispose asked of an agent whose callback ran: the callback was
     * interrupted and the request takes effect when it returns.
     */
    public enum Pending {
        /** None. */
        NONE,
        /** Retract pending: the agent goes home once its callback returns. */
        RETRACT,
        /** Dispose pending: the agent's trip ends once its callback returns. */
        DISPOSE
    }

    /** An agent with no request pending. */
    public AgentInfo(UUID id, String className, AgentStatus status, long hop, String home) {
        this(id, className, status, hop, home, Pending.NONE);
    }

    /** @return its status as {@code mw agents} shows it: {@code ACTIVE}, or {@code ACTIVE (retract pending)} */
    public String state() {
        return pending == Pending.NONE ? status.toString() : status + " (" + pending.name().toLowerCase(java.util.Locale.ROOT) + " pending)";
    }
}
