package io.robomw.platform.exec;

/**
 * What happens when a container of the same priority wants an actuator this container holds.
 */
public enum InterruptionBehavior {
    /** The newcomer wins and this container is interrupted: the paper's "most recent wins". */
    CANCEL_SELF,
    /** This container keeps its actuators and the newcomer is refused. */
    CANCEL_INCOMING
}
