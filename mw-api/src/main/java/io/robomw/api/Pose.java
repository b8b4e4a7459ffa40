package io.robomw.api;

/**
 * A robot's position and heading in the plane.
 *
 * @param x       metres
 * @param y       metres
 * @param heading radians, anti-clockwise from the x axis, normalised to (-π, π]
 */
public record Pose(double x, double y, double heading) implements java.io.Serializable {

    private static final long serialVersionUID = 1L;


    /** The origin, facing along x. */
    public static final Pose ORIGIN = new Pose(0, 0, 0);

    /** Normalises the heading and refuses values that are not numbers. */
    public Pose {
        if (!Double.isFinite(x) || !Double.isFinite(y) || !Double.isFinite(heading)) {
            throw new IllegalArgumentException("pose values must be finite, got x=" + x + " y=" + y + " heading=" + heading);
        }
        heading = normalize(heading);
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
        double a = Math.IEEEremainder(radians, 2 * Math.PI);
        return a <= -Math.PI ? a + 2 * Math.PI : a;
    }
}
