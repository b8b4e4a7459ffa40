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
    /** Gyroscope: heading turned since reset. */
    GYRO(Quantity.ANGLE),
    /** Compass: heading. */
    COMPASS(Quantity.ANGLE),
    /** A motor's rotation counter (tachometer). */
    TACHO(Quantity.ANGLE),
    /** Acceleration along one axis of the robot's body (an accelerometer axis). */
    ACCELEROMETER(Quantity.ACCELERATION),
    /** A joint's angle as its servo reports it (a leg, the neck, the tail of a legged robot). */
    JOINT(Quantity.ANGLE);

    private final Quantity quantity;

    SensorType(Quantity quantity) {
        this.quantity = quantity;
    }

    /** @return what its converted readings measure */
    public Quantity quantity() {
        return quantity;
    }
}
