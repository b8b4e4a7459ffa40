package io.robomw.agents.host.home;

import io.robomw.agents.host.core.HostState;
import io.robomw.agents.host.protocol.Bodies;
import io.robomw.agents.host.protocol.Op;
import io.robomw.agents.host.protocol.Reply;
import io.robomw.agents.host.rmi.PeerException;
import io.robomw.agents.host.rmi.Peers;
import io.robomw.agents.host.code.StateCodec;
import io.robomw.agents.host.code.StateRejectedException;
import io.robomw.api.AgentException;
import io.robomw.api.NotHandledException;

import java.io.IOException;
import java.io.Serializable;
import java.util.concurrent.CompletableFuture;

/**
 * The home's calls to its agents wherever they are (through their {@link AgentHandle}s):
 * messages, and retract and dispose requests. A call goes to where the agent was last heard of
 * and follows it when that host answers that it moved on; the calls made through one handle go
 * out one after the other, in the order they were made, on the host's request threads.
 */
public final class AgentRequests {

    /** How many moves a call follows before it gives up on an agent that keeps moving. */
    private static final int MAX_ROUTE_HOPS = 16;

    private final HostState host;
    private final Peers peers;

    public AgentRequests(HostState host, Peers peers) {
        this.host = host;
        this.peers = peers;
    }

    /**
     * @param handle  the agent
     * @param content the message
     * @param oneway  whether nobody waits for the answer
     * @return the agent's answer; fails with {@link NotHandledException} if it did not handle the message
     */
    CompletableFuture<Serializable> messageAgent(AgentHandle handle, Serializable content, boolean oneway) {
        byte[] bytes;
        try {
            bytes = StateCodec.write(content);
        } catch (IOException e) {
            return CompletableFuture.failedFuture(new AgentException("message to agent " + handle.id() + " is not serializable: " + e.getMessage(), e));
        }
        byte[] body = Bodies.message(handle.id(), oneway, bytes);
        return handle.inOrder(() -> {
            Reply r = agentCall(handle, Op.MESSAGE, body);
            return switch (r.status()) {
                case OK -> {
                    if (r.body().length == 0) {
                        yield null;
                    }
                    try {
                        yield host.codec.read(r.body(), handle.loader, Serializable.class);
                    } catch (StateRejectedException e) {
                        throw new AgentException("reply of agent " + handle.id() + " refused: " + e.getMessage(), e);
                    }
                }
                case NOT_HANDLED -> throw new NotHandledException(r.text());
                default -> throw failure(handle, r);
            };
        }, host.requests);
    }

    /**
     * @param handle the agent
     * @param op     {@link Op#RETRACT} or {@link Op#DISPOSE}
     * @return completes once the agent's host has taken the request (it takes effect when the agent's current callback returns)
     */
    CompletableFuture<Void> requestOfAgent(AgentHandle handle, Op op) {
        byte[] body = Bodies.agentRequest(handle.id());
        return handle.inOrder(() -> {
            Reply r = agentCall(handle, op, body);
            if (r.status() != Reply.Status.OK) {
                throw failure(handle, r);
            }
            return null;
        }, host.requests).thenApply(x -> null);
    }

    private Reply agentCall(AgentHandle handle, Op op, byte[] body) {
        if (handle.ended()) {
            throw new AgentException("agent " + handle.id() + " has ended its trip (" + handle.status() + " at " + handle.location() + ")");
        }
        try {
            return routeToAgent(handle, op, body);
        } catch (PeerException e) {
            throw new AgentException(op + " to agent " + handle.id() + " failed: " + e.getMessage(), e);
        }
    }

    private Reply routeToAgent(AgentHandle handle, Op op, byte[] body) throws PeerException {
        String location = handle.location();
        for (int i = 0; i < MAX_ROUTE_HOPS; i++) {
            if (i > 0 && handle.ended()) {
                // it came home (retracted, disposed, done) while the call chased it
                return Reply.of(Reply.Status.GONE, "agent " + handle.id() + " has ended its trip");
            }
            Reply r = peers.call(location, op, body);
            if (r.status() != Reply.Status.MOVED) {
                return r;
            }
            location = r.text();
            handle.location(location);
        }
        throw new PeerException("agent " + handle.id() + " moved more than " + MAX_ROUTE_HOPS + " times while a call chased it", false, null);
    }

    private static AgentException failure(AgentHandle handle, Reply r) {
        if (r.status() == Reply.Status.GONE && handle.ended()) {
            return new AgentException("agent " + handle.id() + " has ended its trip");
        }
        return new AgentException(r.status() + ": " + r.text());
    }
}
