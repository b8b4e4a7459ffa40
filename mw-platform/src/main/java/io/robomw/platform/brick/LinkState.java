package io.robomw.platform.brick;

/**
 * The state of a brick's link, kept in one place: its {@link LinkAgent}. Each change is one line
 * in the log.
 */
public enum LinkState {
    /** Exchanges go to the brick. */
    UP,
    /**
     * An exchange failed: every command was stopped, new ones are refused, exchanges fail at once,
     * and the agent reopens the link every {@link BrickChannel#REOPEN_INTERVAL}.
     */
    DOWN,
    /** The agent is reopening the link (and trying it); it is up or down again after. */
    REOPENING
}
