package io.robomw.api.spi;

import io.robomw.api.Pose;

import java.util.Optional;

/**
 * A platform that knows where its robot is by itself: a vehicle's autopilot reports its position,
 * heading and altitude (MAVLink's LOCAL_POSITION_NED and ATTITUDE), a simulator knows the truth.
 * The Configuration Layer's vehicle drive takes the robot's pose from here instead of integrating
 * what it commanded. Optional: a {@link RobotPlatform} implements it when it can.
 *
 * <p>Thread-safe; never blocks on I/O (the latest report).
 */
public interface PoseSource {

    /**
     * @return the robot's pose in the platform's own local frame, if reported yet: x east and y
     *         north of the platform's origin (a vehicle's home), heading anti-clockwise from east,
     *         z metres up from the origin's ground
     */
    Optional<Pose> reportedPose();
}
