package io.robomw.api;

import java.util.List;

/**
 * Mobile agents (paper section III.A.4, after IBM Aglets): an agent is sent to an agent host,
 * runs there with that host's robot, travels along its itinerary and sends its results home.
 * The runtime lives in {@code mw-agents}; a robot without one throws
 * {@link UnsupportedActionException} from every method.
 */
public interface Agency {

    /**
     * Sends an agent to a host. Returns once the host has accepted it.
     *
     * @param host  the agent host's address, for example {@code rmi://127.0.0.1:1099/nxt}
     * @param agent the agent
     * @return a handle on the travelling agent
     */
    AgentRef sendAgent(String host, Agent agent);

    /**
     * Sends one clone of an agent to each host, in parallel: the paper's "one agent cloned to
     * several robots". Returns once every host has accepted its clone.
     *
     * @param agent the agent to clone
     * @param hosts the hosts, one clone each
     * @return one handle per host, in the order of {@code hosts}
     */
    List<AgentRef> dispatchClones(Agent agent, String... hosts);
}
