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
 */
public record AgentInfo(UUID id, String className, AgentStatus status, long hop, String home) {
}
