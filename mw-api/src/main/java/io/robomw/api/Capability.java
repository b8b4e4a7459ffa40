package io.robomw.api;

/** What kind of motion a robot is built for, as listed in its description. */
public enum Capability {
    /** Drives or walks on the ground. */
    GROUND,
    /** Flies: can change altitude. */
    AIR,
    /** Swims. */
    WATER
}
