package io.robomw.api;

/** What a sensor measures, as {@link Perception#getValue} names it. */
public enum SensorType {
    /** A switch or bumper: pressed or not. */
    TOUCH(Quantity.PRESENCE),
    /** Reflected or ambient light, as a fraction of full scale. */
    LIGHT(Quantity.RATIO),
    /** A colour sensor's colour number. */
    COLOR(Quantity.COLOR_ID),
    /** Sound level. */
    SOUND(Quantity.SOUND_LEVEL),
    /** Ultrasonic range finder: distance to the nearest obstacle in its beam. */
    SONAR(Quantity.DISTANCE),
    /** Infra-red range finder. */
    INFRARED(Quantity.DISTANCE),
    /** Laser range finder: a single-beam lidar or a time-of-flight distance sensor. */
    LASER(Quantity.DISTANCE),
    /**
     * Any range finder: asked for in {@link Perception#getValue}, it matches the sensor at that
     * position that measures distance ({@link #SONAR}, {@link #INFRARED}, {@link #LASER}, or one a
     * description declares as {@code range}), so one program reads the distance ahead on every
     * robot whatever its hardware.
     */
    RANGE(Quantity.DISTANCE),
    /** Gyroscope: heading turned since reset. */
    GYRO(Quantity.ANGLE),
    /** Compass: heading. */
    COMPASS(Quantity.ANGLE),
    /** A motor's rotation counter (tachometer). */
    TACHO(Quantity.ANGLE),
    /** Acceleration along one axis of the robot's body (an accelerometer axis). */
    ACCELEROMETER(Quantity.ACCELERATION),
    /** A joint's angle as its servo reports it (a leg, the neck, the tail of a legged robot). */
    JOINT(Quantity.ANGLE),
    /** A vehicle's altitude: metres above its home's ground, as its autopilot reports it. */
    ALTITUDE(Quantity.DISTANCE),
    /** A vehicle's battery: the charge left, a fraction of full (0 to 1; {@link ReturnType#PERCENT} gives 0 to 100). */
    BATTERY(Quantity.RATIO),
    /** A vehicle's latitude from its GPS, north positive. */
    LATITUDE(Quantity.ANGLE),
    /** A vehicle's longitude from its GPS, east positive. */
    LONGITUDE(Quantity.ANGLE);

    private final Quantity quantity;

    SensorType(Quantity quantity) {
        this.quantity = quantity;
    }

    /** @return what its converted readings measure */
    public Quantity quantity() {
        return quantity;
    }

    /**
     * @param declared the type a sensor is declared with
     * @return whether a reading asked for as this type is answered by that sensor: the same type,
     *         or {@link #RANGE} asked of any range finder
     */
    public boolean matches(SensorType declared) {
        return this == declared || (this == RANGE && declared.ranging());
    }

    /** @return whether this is a range finder's type, which {@link #RANGE} matches */
    public boolean ranging() {
        return this == SONAR || this == INFRARED || this == LASER || this == RANGE;
    }
}
