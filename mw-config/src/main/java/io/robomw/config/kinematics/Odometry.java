package io.robomw.config.kinematics;

import io.robomw.api.Pose;

/**
 * Dead reckoning from wheel encoders: integrates the wheel travel between two readings as a
 * circular arc (exact when the wheel speeds were constant in between, as they are within one
 * {@code move}, {@code turn} or {@code arc}).
 *
 * <p>Not thread-safe: callers synchronise ({@code io.robomw.config.drive.WheelOdometry} updates it under its own lock).
 */
public final class Odometry {

    private final DifferentialKinematics kinematics;
    // The estimate in three fields, the heading normalised as a Pose holds it: an update (at every
    // drive, ten a second per robot) makes no object and stores no reference into this long-lived one.
    private double x;
    private double y;
    private double heading;
    private double lastLeft = Double.NaN;
    private double lastRight = Double.NaN;

    /**
     * @param kinematics the wheel layout
     */
    public Odometry(DifferentialKinematics kinematics) {
        this.kinematics = kinematics;
    }

    /**
     * Integrates to new encoder readings. The first call only records them.
     *
     * @param leftMotorDegrees  the left motor's rotation, as the motor reports it
     * @param rightMotorDegrees the right motor's rotation
     * @return the new pose
     */
    public Pose update(double leftMotorDegrees, double rightMotorDegrees) {
        integrate(leftMotorDegrees, rightMotorDegrees);
        return pose();
    }

    /**
     * {@link #update} without making the pose: integrates to new encoder readings.
     *
     * @param leftMotorDegrees  the left motor's rotation, as the motor reports it
     * @param rightMotorDegrees the right motor's rotation
     * @throws IllegalArgumentException if the pose would not be finite (as {@link Pose} refuses it);
     *                                  the estimate is then unchanged
     */
    public void integrate(double leftMotorDegrees, double rightMotorDegrees) {
        if (!Double.isNaN(lastLeft)) {
            double dl = kinematics.wheelMetres(leftMotorDegrees - lastLeft, kinematics.drive().left().reversed());
            double dr = kinematics.wheelMetres(rightMotorDegrees - lastRight, kinematics.drive().right().reversed());
            advance(dl, dr, kinematics.drive().trackWidth());
        }
        lastLeft = leftMotorDegrees;
        lastRight = rightMotorDegrees;
    }

    /**
     * The same estimate, continued with other wheel geometry (after a reload): the pose and the
     * last readings carry over, so travel since the last update is not lost.
     *
     * @param next the new wheel layout
     * @return the continued odometry
     */
    public Odometry rebased(DifferentialKinematics next) {
        Odometry o = new Odometry(next);
        o.x = x;
        o.y = y;
        o.heading = heading;
        o.lastLeft = lastLeft;
        o.lastRight = lastRight;
        return o;
    }

    /** @return the current estimate */
    public Pose pose() {
        return new Pose(x, y, heading);
    }

    /**
     * @param pose the robot's pose now; the next update integrates from the last readings
     */
    public void reset(Pose pose) {
        x = pose.x();
        y = pose.y();
        heading = pose.heading();
    }

    /** Moves the estimate along the arc the wheels' distances define (the arithmetic a {@link Pose} per step did). */
    private void advance(double left, double right, double track) {
        double ds = (left + right) / 2;
        double dTheta = (right - left) / track;
        double nx;
        double ny;
        if (Math.abs(dTheta) < 1e-12) {
            nx = x + ds * Math.cos(heading);
            ny = y + ds * Math.sin(heading);
        } else {
            double r = ds / dTheta;
            nx = x + r * (Math.sin(heading + dTheta) - Math.sin(heading));
            ny = y - r * (Math.cos(heading + dTheta) - Math.cos(heading));
        }
        double nh = heading + dTheta;
        if (!Double.isFinite(nx) || !Double.isFinite(ny) || !Double.isFinite(nh)) {
            new Pose(nx, ny, nh); // throws, saying which values are not numbers, as the pose made here did
        }
        x = nx;
        y = ny;
        heading = Pose.normalize(nh);
    }
}
