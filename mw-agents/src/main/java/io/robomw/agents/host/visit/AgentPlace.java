package io.robomw.agents.host.visit;

import io.robomw.api.Agency;
import io.robomw.api.AgentRef;
import io.robomw.api.Itinerary;
import io.robomw.api.Messaging;
import io.robomw.api.Robot;

import java.io.Serializable;

/**
 * What a host gives the agents at it through their {@link HostContext}: who it is, its robot (one
 * stop at a time), its messaging, clones and reports sent home, and its agency. The host's facade
 * implements it; the parts that run agents see this, not the facade.
 */
public interface AgentPlace {

    /** @return the host's name */
    String name();

    /** @return the host's address, {@code rmi://host:port/name} */
    String address();

    /** @return the robot for the agent's stop (waiting for the agent that has it), or {@code null} if the host has none */
    Robot claimRobot(HostedAgent h);

    /** @return an agent's view of the host's messaging node */
    Messaging messagingFor(HostedAgent h);

    /** @return the agent host address of a host an agent here names (its address, or its name as messages use it) */
    String hostAddressOf(String nameOrAddress, HostedAgent h);

    /** @return a clone of an agent here, sent with its own plan; this host is its home */
    AgentRef cloneOf(HostedAgent parent, Itinerary plan);

    /** Sends a value an agent here reports to its home. */
    void report(HostedAgent h, Serializable value);

    /** @return this host as a home */
    Agency agency();
}
