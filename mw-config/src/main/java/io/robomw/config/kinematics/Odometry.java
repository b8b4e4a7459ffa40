package io.robomw.config.kinematics;

import io.robomw.api.Pose;

/**
 * Dead reckoning from wheel encoders: integrates the wheel travel between two readings as a
 * circular arc (exact when the wheel speeds were constant in between, as they are within one
 * {@code move}, {@code turn} or {@code arc}).
 *
 * <p>Not thread-safe: callers synchronise (the robot updates it under its own lock).
 */
public final class Odometry {

    private final DifferentialKinematics kinematics;
    private Pose pose = Pose.ORIGIN;
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
        if (!Double.isNaN(lastLeft)) {
            double dl = kinematics.wheelMetres(leftMotorDegrees - lastLeft, kinematics.drive().left().reversed());
            double dr = kinematics.wheelMetres(rightMotorDegrees - lastRight, kinematics.drive().right().reversed());
            pose = advance(pose, dl, dr, kinematics.drive().trackWidth());
        }
        lastLeft = leftMotorDegrees;
        lastRight = rightMotorDegrees;
        return pose;
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
        o.pose = pose;
        o.lastLeft = lastLeft;
        o.lastRight = lastRight;
        return o;
    }

    /** @return the current estimate */
    public Pose pose() {
        return pose;
    }

    /**
     * @param pose the robot's pose now; the next update integrates from the last readings
     */
    public void reset(Pose pose) {
        this.pose = pose;
    }

    /**
     * @param from  the pose before
     * @param left  metres the left wheel rolled
     * @param right metres the right wheel rolled
     * @param track the track width
     * @return the pose after rolling along the arc those distances define
     */
    static Pose advance(Pose from, double left, double right, double track) {
        double ds = (left + right) / 2;
        double dTheta = (right - left) / track;
        double x;
        double y;
        if (Math.abs(dTheta) < 1e-12) {
            x = from.x() + ds * Math.cos(from.heading());
            y = from.y() + ds * Math.sin(from.heading());
        } else {
            double r = ds / dTheta;
            x = from.x() + r * (Math.sin(from.heading() + dTheta) - Math.sin(from.heading()));
            y = from.y() - r * (Math.cos(from.heading() + dTheta) - Math.cos(from.heading()));
        }
        return new Pose(x, y, from.heading() + dTheta);
    }
}
