package io.robomw.api;

/**
 * What a sensor's converted reading measures, in its SI base unit. A {@link SensorType} has one;
 * the {@link ReturnType}s a reading can be asked in follow from it.
 */
public enum Quantity {
    /** Metres. */
    DISTANCE,
    /** Radians. */
    ANGLE,
    /** Radians per second. */
    ANGULAR_RATE,
    /** Metres per second squared. */
    ACCELERATION,
    /** A fraction of full scale, 0 to 1 (reflected or ambient light). */
    RATIO,
    /** True or false (pressed, detected), as 1 or 0. */
    PRESENCE,
    /** Sound level in decibels. */
    SOUND_LEVEL,
    /** A colour number as the sensor reports it. */
    COLOR_ID
}
