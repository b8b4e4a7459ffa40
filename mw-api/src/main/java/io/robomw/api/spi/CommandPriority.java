package io.robomw.api.spi;

/**
 * How a command ranks when it needs an actuator another command holds. Within one priority the
 * most recent command wins; a command never takes an actuator from a higher-priority one.
 */
public enum CommandPriority {
    /** Ordinary motion: interrupted by any newer command on the same actuators. */
    NORMAL,
    /** Stops and safety actions: never interrupted by a normal command. */
    SAFETY
}
