package io.robomw.console.rosbridge.robot;

import io.robomw.api.Pose;

import java.time.Instant;

/**
 * A robot's pose at one moment, with its velocity over the last {@link #WINDOW} of samples (a
 * difference over a window, not from one sample to the next: samples taken back to back, when a
 * late tick is caught up, would otherwise show a moving robot standing still).
 *
 * @param pose    the odometry estimate
 * @param z       the pose's altitude, metres, z up ({@link Pose#z()}: 0 for robots on the ground)
 * @param stamp   when it was taken (wall clock)
 * @param forward speed along the body's x axis since the last sample, m/s
 * @param turning turn rate since the last sample, rad/s, positive left
 */
record PoseSample(Pose pose, double z, Instant stamp, double forward, double turning) {

    /** The span velocities are taken over. */
    static final java.time.Duration WINDOW = java.time.Duration.ofMillis(200);

    /**
     * @param previous the oldest sample of the window, or {@code null}
     * @param pose     the pose now
     * @param stamp    now
     * @return the sample, its velocity from the difference (0 for the first)
     */
    static PoseSample after(PoseSample previous, Pose pose, Instant stamp) {
        if (previous == null) {
            return new PoseSample(pose, pose.z(), stamp, 0, 0);
        }
        double dt = java.time.Duration.between(previous.stamp, stamp).toNanos() / 1e9;
        if (!(dt > 0)) {
            return new PoseSample(pose, pose.z(), stamp, previous.forward, previous.turning);
        }
        double dx = pose.x() - previous.pose.x();
        double dy = pose.y() - previous.pose.y();
        double h = previous.pose.heading();
        double forward = (dx * Math.cos(h) + dy * Math.sin(h)) / dt;
        double turning = Pose.normalize(pose.heading() - h) / dt;
        return new PoseSample(pose, pose.z(), stamp, forward, turning);
    }
}
