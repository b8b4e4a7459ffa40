package io.robomw.config.drive;

import io.robomw.api.Pose;
import io.robomw.api.spi.RobotPlatform;
import io.robomw.config.kinematics.DifferentialKinematics;
import io.robomw.config.kinematics.Odometry;

/**
 * The pose of a robot on two wheels with encoders: its {@link Odometry}, integrated from the wheel
 * motors' readings, kept across reloads of the description.
 *
 * <p>Thread-safe: every method holds the object's lock.
 */
final class WheelOdometry {

    private final RobotPlatform platform;
    private DifferentialKinematics kinematics;
    private Odometry odometry;

    /**
     * Records the wheels' readings now: the origin of the estimate.
     *
     * @param platform   where the readings come from
     * @param kinematics the wheel layout in force
     */
    WheelOdometry(RobotPlatform platform, DifferentialKinematics kinematics) {
        this.platform = platform;
        this.kinematics = kinematics;
        this.odometry = new Odometry(kinematics);
        integrate();
    }

    /**
     * The same estimate, continued with the wheel layout of a reloaded description: the travel so
     * far is integrated with the layout it was driven under, what follows with the new one.
     *
     * @param next the new wheel layout
     */
    synchronized void continueWith(DifferentialKinematics next) {
        integrate();
        if (!next.drive().equals(kinematics.drive())) {
            odometry = odometry.rebased(next);
        }
        kinematics = next;
    }

    /** Moves the estimate on to the wheels' readings now (at a motion's boundary). */
    synchronized void integrate() {
        odometry.integrate(platform.motorDegrees(kinematics.drive().left().port()), platform.motorDegrees(kinematics.drive().right().port()));
    }

    /** @return the estimate now */
    synchronized Pose pose() {
        integrate();
        return odometry.pose();
    }

    /**
     * @param pose the robot's pose now
     */
    synchronized void reset(Pose pose) {
        integrate();
        odometry.reset(pose);
    }
}
