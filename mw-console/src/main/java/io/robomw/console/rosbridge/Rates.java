package io.robomw.console.rosbridge;

/**
 * How often the bridge samples its robots for ROS topics.
 *
 * @param odometryHz {@code /<robot>/odom} and {@code /tf} messages per second (each robot's pose
 *                   is sampled at this rate while either has a subscriber)
 * @param sensorHz   range and joint readings per second; 0: each sensor's own rate from its robot
 *                   file or the simulator ({@code rate_hz}, default {@value SensorGeometry#DEFAULT_RATE_HZ})
 */
public record Rates(double odometryHz, double sensorHz) {

    /** The defaults: odometry at 20 Hz, sensors at their own rates. */
    public static final Rates DEFAULTS = new Rates(20, 0);
    /** The fastest rate taken, per second. */
    public static final double MAX_HZ = 1000;

    /** Checks the rates. */
    public Rates {
        if (!(odometryHz > 0 && odometryHz <= MAX_HZ) || !(sensorHz >= 0 && sensorHz <= MAX_HZ)) {
            throw new IllegalArgumentException("odometry rate must be above 0 and at most " + MAX_HZ + " Hz, sensor rate 0 (each sensor's own) to "
                    + MAX_HZ + " Hz; got " + odometryHz + " and " + sensorHz);
        }
    }

    /**
     * @param geometry a sensor's geometry
     * @return the rate to read it at
     */
    double sensorRate(SensorGeometry geometry) {
        return sensorHz > 0 ? sensorHz : geometry.rateHz();
    }
}
