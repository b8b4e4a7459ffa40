package io.robomw.api;

import java.util.Set;

/**
 * The unit a reading is wanted in. Each return type fits some {@link Quantity}s; asking for one
 * that does not fit the sensor raises {@link UnsupportedActionException}.
 */
public enum ReturnType {
    /** The brick's raw value, unconverted. Fits every sensor. */
    RAW(Set.of(Quantity.values())),
    /** Percent of full scale, 0 to 100. */
    PERCENT(Set.of(Quantity.RATIO)),
    /** Metres. */
    METERS(Set.of(Quantity.DISTANCE)),
    /** Centimetres. */
    CENTIMETERS(Set.of(Quantity.DISTANCE)),
    /** Millimetres. */
    MILLIMETERS(Set.of(Quantity.DISTANCE)),
    /** Radians. */
    RADIANS(Set.of(Quantity.ANGLE)),
    /** Degrees. */
    DEGREES(Set.of(Quantity.ANGLE)),
    /** Degrees per second. */
    DEGREES_PER_SECOND(Set.of(Quantity.ANGULAR_RATE)),
    /** Radians per second. */
    RADIANS_PER_SECOND(Set.of(Quantity.ANGULAR_RATE)),
    /** Metres per second squared. */
    METERS_PER_SECOND_SQUARED(Set.of(Quantity.ACCELERATION)),
    /** Lux; fits light sensors whose description gives a lux calibration. */
    LUX(Set.of(Quantity.RATIO)),
    /** Decibels. */
    DECIBELS(Set.of(Quantity.SOUND_LEVEL)),
    /** The colour number. */
    COLOR_ID(Set.of(Quantity.COLOR_ID)),
    /**
     * 1.0 for true, 0.0 for false. Fits switches, and any sensor whose description gives a
     * threshold.
     */
    BOOLEAN(Set.of(Quantity.PRESENCE));

    private final Set<Quantity> fits;

    ReturnType(Set<Quantity> fits) {
        this.fits = fits;
    }

    /**
     * @param quantity a sensor's quantity
     * @return whether a reading of that quantity can always be given in this unit
     */
    public boolean fits(Quantity quantity) {
        return fits.contains(quantity);
    }
}
