package io.robomw.api;

/**
 * A robot's position, heading and altitude.
 *
 * <h2>Frame</h2>
 * Right-handed, z up: x and y in the plane (a robot's own pose starts at x = y = 0, facing along
 * x, where it was opened or last reset; a simulated world's x is east and y north), heading
 * anti-clockwise from the x axis seen from above, z the altitude in metres above the ground (or the
 * water) where the robot started: 0 for every robot that does not fly, and for a multirotor on the
 * ground.
 *
 * @param x       metres
 * @param y       metres
 * @param heading radians, anti-clockwise from the x axis, normalised to (-π, π]
 * @param z       metres up, the altitude above the starting point's ground
 */
public record Pose(double x, double y, double heading, double z) implements java.io.Serializable {

    private static final long serialVersionUID = 1L;


    /** The origin, facing along x. */
    public static final Pose ORIGIN = new Pose(0, 0, 0);

    /** Normalises the heading and refuses values that are not numbers. */
    public Pose {
        if (!Double.isFinite(x) || !Double.isFinite(y) || !Double.isFinite(heading) || !Double.isFinite(z)) {
            throw new IllegalArgumentException("pose values must be finite, got x=" + x + " y=" + y + " heading=" + heading + " z=" + z);
        }
        heading = normalize(heading);
    }

    /**
     * A pose on the ground (z = 0).
     *
     * @param x       metres
     * @param y       metres
     * @param heading radians, anti-clockwise from the x axis
     */
    public Pose(double x, double y, double heading) {
        this(x, y, heading, 0);
    }

    /**
     * @param other another pose
     * @return the straight-line distance between the two positions, metres
     */
    public double distanceTo(Pose other) {
        return Math.hypot(other.x - x, other.y - y);
    }

    /**
     * @param radians an angle
     * @return the same angle in (-π, π]
     */
    public static double normalize(double radians) {
        if (radians > -Math.PI && radians <= Math.PI) {
            return radians;
        }
        // floor, not Math.IEEEremainder: that is a native call (JDK 17), and a simulation normalizes every robot's heading every step
        double a = radians - 2 * Math.PI * Math.floor((radians + Math.PI) / (2 * Math.PI));
        if (a <= -Math.PI) {
            return a + 2 * Math.PI;
        }
        return a > Math.PI ? a - 2 * Math.PI : a;
    }
}
