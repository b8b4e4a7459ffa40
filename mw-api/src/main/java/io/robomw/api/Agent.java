package io.robomw.api;

import java.io.Serializable;

/**
 * A mobile agent (paper section III.A.4, after IBM Aglets' {@code Aglet}): a serializable object
 * that travels between agent hosts along its {@link Itinerary} and runs at each stop with that
 * host's robot. Subclasses override the lifecycle callbacks they need.
 *
 * <p>Lifecycle, in the order a host calls it; every callback runs on the agent's own named thread
 * at its current host, one at a time:
 * <ul>
 *   <li>{@link #onCreation(Object)}: once, at home, when the agent is sent (for clones: once, before cloning).</li>
 *   <li>{@link #onArrival()}: after it has arrived at a host, before the stop's work.</li>
 *   <li>{@link #run()}: the work of a stop that names no {@link Itinerary.Task} of its own.</li>
 *   <li>{@link #onDispatching()}: before it leaves a host for the next stop.</li>
 *   <li>{@link #onDisposing()}: once, at the host where its trip ends, before it is disposed of.</li>
 * </ul>
 * {@link #handleMessage(AgentMessage)} is called on the host's message thread and may run while
 * a callback runs: synchronise the state the two share.
 *
 * <p>What travels: the agent's serializable fields (its itinerary among them) and the classes of
 * its code, which go in an archive identified by its SHA-256 (see the {@code mw-agents} docs).
 * Fields holding a robot, a thread, a socket or a stream must be {@code transient}; a host
 * refuses state with classes that are neither in the agent's archive nor on its allow-list.
 */
public abstract class Agent implements Serializable {

    private static final long serialVersionUID = 1L;

    private final Itinerary itinerary = new Itinerary();
    private transient AgentContext context;

    /**
     * Called once, at home, when the agent is sent; {@link #context()} is not valid yet.
     *
     * @param init the initialisation argument given when it was sent, or {@code null}
     */
    public void onCreation(Object init) {
    }

    /** Called after the agent has arrived at a host, before the stop's work. */
    public void onArrival() {
    }

    /** The agent's work at a stop that names no task of its own. */
    public abstract void run();

    /** Called before the agent leaves a host for its next stop. */
    public void onDispatching() {
    }

    /** Called once, at the host where the trip ends, before the agent is disposed of. */
    public void onDisposing() {
    }

    /**
     * Handles a message sent to this agent through its {@link AgentRef}. Reply with
     * {@link AgentMessage#sendReply}. Called on the host's message thread.
     *
     * @param message the message
     * @return whether the message was handled; {@code false} makes the sender's call fail with
     *         {@link NotHandledException}
     */
    public boolean handleMessage(AgentMessage message) {
        return false;
    }

    /**
     * @return the stops this agent will visit; it may change them while it travels
     */
    public final Itinerary itinerary() {
        return itinerary;
    }

    /**
     * @return the host the agent is at: its robot, messaging, itinerary and the ways to leave
     * @throws IllegalStateException if the agent is not at a host (it has not been sent, or this is a copy)
     */
    public final AgentContext context() {
        AgentContext c = context;
        if (c == null) {
            throw new IllegalStateException("agent " + getClass().getName() + " is not at an agent host: context() is only valid inside its callbacks at a host");
        }
        return c;
    }

    /**
     * Gives the agent its context at a host. Called by the agent runtime when the agent arrives;
     * agents do not call it.
     *
     * @param context the host's context for this agent, or {@code null} when it leaves
     */
    public final void attach(AgentContext context) {
        this.context = context;
    }
}
