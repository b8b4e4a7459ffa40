package io.robomw.api;

import java.io.Serializable;

/**
 * A mobile agent: a serializable object that travels between agent hosts and runs on each.
 * Subclasses override the lifecycle callbacks they need; every callback is called on the
 * agent's own thread at its current host, one at a time.
 *
 * <ul>
 *   <li>{@link #onCreation(Object)}: once in the agent's life, when it is created.</li>
 *   <li>{@link #onDispatching()}: before it leaves a host.</li>
 *   <li>{@link #onArrival()}: after it has arrived at a host, before {@link #run()}.</li>
 *   <li>{@link #run()}: its work at this host.</li>
 *   <li>{@link #onDisposing()}: once, before it is disposed of.</li>
 * </ul>
 *
 * <p>Only serializable state travels; fields holding a robot, a thread or a socket must be
 * {@code transient}.
 */
public abstract class Agent implements Serializable {

    private static final long serialVersionUID = 1L;

    /**
     * Called once, when the agent is created.
     *
     * @param init the initialisation argument given at creation, or {@code null}
     */
    public void onCreation(Object init) {
    }

    /** Called before the agent leaves a host. */
    public void onDispatching() {
    }

    /** Called after the agent has arrived at a host, before {@link #run()}. */
    public void onArrival() {
    }

    /** The agent's work at its current host. */
    public abstract void run();

    /** Called once, before the agent is disposed of. */
    public void onDisposing() {
    }
}
