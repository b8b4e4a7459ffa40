package io.robomw.sim.vehicle;

/**
 * What a vehicle's autopilot asks of its motors at one moment: velocities in the world's frame
 * (x east, y north, z up) and a yaw rate (anti-clockwise positive). A boat or rover follows the
 * horizontal velocity's part along its heading (it cannot move sideways by itself) and ignores
 * {@code vz}.
 *
 * @param vx      m/s east
 * @param vy      m/s north
 * @param vz      m/s up
 * @param yawRate rad/s, anti-clockwise
 */
public record VehicleTarget(double vx, double vy, double vz, double yawRate) {

    /** Hold still. */
    public static final VehicleTarget HOLD = new VehicleTarget(0, 0, 0, 0);

    /** Checks the values are numbers. */
    public VehicleTarget {
        if (!Double.isFinite(vx) || !Double.isFinite(vy) || !Double.isFinite(vz) || !Double.isFinite(yawRate)) {
            throw new IllegalArgumentException("a vehicle target must be finite, got " + vx + ", " + vy + ", " + vz + ", " + yawRate);
        }
    }
}
