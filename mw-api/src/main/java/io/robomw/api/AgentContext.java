package io.robomw.api;

import java.io.Serializable;
import java.util.List;
import java.util.UUID;

/**
 * What an agent sees at the host it is on (after Aglets' {@code AgletContext}): the host's robot,
 * its messaging, the agent's itinerary, and the ways to move on, clone itself, finish and send
 * results home. Valid only while the agent is at this host, and only on the agent's own thread
 * (except {@link #report}, which any thread may call).
 *
 * <p>It is also an {@link Agency}: an agent may send other agents from here; their home is
 * this host. Those calls go to the host's agency ({@link #agency()}), as a {@link Robot}'s go to
 * its own, so an implementation gives the component rather than forwarding each call.
 */
public interface AgentContext extends Agency {

    /** @return this agent's id, the same at every host and for the whole trip */
    UUID agentId();

    /** @return the name of the host the agent is at */
    String hostName();

    /** @return the address of the host the agent is at, for example {@code rmi://127.0.0.1:1099/nxt} */
    String hostAddress();

    /** @return the address of the agent's home, where its results go */
    String homeAddress();

    /**
     * The host's robot, to this agent alone until the current stop's work returns: the first call
     * in a stop waits while another agent's stop at this host has the robot, so two agents' moves
     * never pre-empt each other. Call it on the agent's own thread.
     *
     * @return the host's robot
     * @throws UnsupportedActionException if this host has no robot
     */
    Robot robot();

    /**
     * @return the host's messaging (the paper's sendMessage, publishMessage, ...)
     * @throws UnsupportedActionException if this host has no messaging node
     */
    Messaging messaging();

    /**
     * @return the host's agency, where the {@link Agency} calls of this context go: agents sent
     *         with it have this host as their home
     */
    Agency agency();

    /** @return the agent's itinerary (the same object as {@link Agent#itinerary()}) */
    Itinerary itinerary();

    /**
     * Goes to {@code host} next: inserts a stop there (its work is {@link Agent#run()}) before the
     * rest of the itinerary. The agent leaves when the current callback returns; this method does
     * not block (it may ask the agent's home or the hosts known here where a host of that name is).
     *
     * @param host the host's address ({@code rmi://host:port/name}), or its name as messages use it
     *             (a host this one knows: its agents' homes and stops, the hosts those know, the hosts
     *             announced at a broker it is at)
     * @throws IllegalArgumentException if it is neither an address nor the name of a host known here
     *                                  or at the agent's home (the message lists the hosts known)
     */
    void dispatch(String host);

    /**
     * Makes a copy of this agent, with a new id and the same home, that travels {@code itinerary}
     * on its own. Its result goes home like this agent's.
     *
     * @param itinerary the clone's stops
     * @return a handle on the clone
     */
    AgentRef cloneAgent(Itinerary itinerary);

    /**
     * Ends the trip here when the current callback returns: {@link Agent#onDisposing()} runs and
     * the result goes home, whatever stops remain.
     */
    void dispose();

    /**
     * Whether an operator asked this agent to leave (a retract or a dispose): its callback's thread
     * has been interrupted, and the request takes effect when the callback returns. An agent that
     * works in a loop without blocking calls polls this (or {@link Thread#interrupted()}) and
     * returns soon; the host waits for it (Java cannot end a thread that ignores its interrupt) and
     * says so after 5 s.
     *
     * @return whether it should return from its callback now
     */
    default boolean leaving() {
        return Thread.currentThread().isInterrupted();
    }

    /**
     * Sets the result the agent brings home at the end of its trip; the last value set wins.
     *
     * @param result the result (serializable, of the agent's own classes or allow-listed JDK types)
     */
    void setResult(Serializable result);

    /**
     * Sends a value home now, while the trip goes on: its {@link AgentRef}'s report listeners get
     * it. Returns at once; reports from one agent arrive in order.
     *
     * @param value the value
     */
    void report(Serializable value);

    @Override
    default AgentRef sendAgent(String host, Agent agent) {
        return agency().sendAgent(host, agent);
    }

    @Override
    default AgentRef startTrip(Agent agent) {
        return agency().startTrip(agent);
    }

    @Override
    default List<AgentRef> dispatchClones(Agent agent, String... hosts) {
        return agency().dispatchClones(agent, hosts);
    }
}
