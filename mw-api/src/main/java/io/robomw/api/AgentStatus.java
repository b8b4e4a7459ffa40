package io.robomw.api;

/** Where an agent is in its life, as its {@link AgentRef} last heard. */
public enum AgentStatus {
    /** Created, not yet accepted by a host. */
    CREATED,
    /** Accepted by a host and running there. */
    ACTIVE,
    /** Between two hosts. */
    IN_TRANSIT,
    /** Finished its itinerary; its result is home. */
    COMPLETED,
    /** Disposed of before finishing. */
    DISPOSED,
    /** Brought home by {@link AgentRef#retract()}. */
    RETRACTED,
    /** Failed; its result future holds the cause. */
    FAILED
}
