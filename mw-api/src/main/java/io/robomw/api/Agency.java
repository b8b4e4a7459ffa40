package io.robomw.api;

import java.util.List;

/**
 * Mobile agents (paper section III.A.4, after IBM Aglets): an agent is sent to an agent host,
 * runs there with that host's robot, travels along its {@link Itinerary} and sends its results
 * home. The runtime lives in {@code mw-agents}; a robot without one throws
 * {@link UnsupportedActionException} from every method.
 */
public interface Agency {

    /**
     * Sends an agent to a host: it runs {@link Agent#run()} there, then goes on with the stops
     * already in its itinerary, then its result comes home. Blocks until the host has stored
     * the agent and acknowledged it (so it cannot be lost), not until the trip ends.
     *
     * @param host  the agent host's address, for example {@code rmi://127.0.0.1:1099/nxt}
     * @param agent the agent
     * @return a handle on the travelling agent
     * @throws AgentException if the host cannot be reached, refuses this peer, or refuses the agent
     */
    AgentRef sendAgent(String host, Agent agent);

    /**
     * Starts an agent on the trip its itinerary describes (after Aglets' {@code SeqItinerary.startTrip}).
     * Blocks until the first host has stored and acknowledged it.
     *
     * @param agent an agent with at least one stop in its itinerary
     * @return a handle on the travelling agent
     * @throws AgentException if the first stop cannot be reached (after the itinerary's unreachable-stop policy) or refuses the agent
     */
    AgentRef startTrip(Agent agent);

    /**
     * Sends one clone of an agent to each host, in parallel: the paper's "one agent cloned to
     * several robots". Each clone gets its own id and an itinerary of one stop, its host, where
     * it runs {@link Agent#run()}. Blocks until every host has accepted its clone.
     *
     * @param agent the agent to clone (it is not sent itself)
     * @param hosts the hosts, one clone each
     * @return one handle per host, in the order of {@code hosts}
     * @throws PartialDispatchException if some hosts could not be reached or refused their clones:
     *         the others were sent, and the exception holds their handles ({@link PartialDispatchException#sent()})
     *         and why each of the rest was not sent
     * @throws AgentException if no clone could be sent
     */
    List<AgentRef> dispatchClones(Agent agent, String... hosts);
}
