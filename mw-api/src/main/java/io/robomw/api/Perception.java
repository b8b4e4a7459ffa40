package io.robomw.api;

import java.util.concurrent.CompletableFuture;

/**
 * Sensing: the paper's {@code getValue(position, type, returnType)} and the robot's own pose
 * estimate.
 *
 * <p>A sensor is found by where it sits on the robot and what it measures; the robot's
 * description says which port it is on and how its raw values convert into units.
 */
public interface Perception {

    /**
     * Reads a sensor and converts its reading. Blocks until the reading arrives (bounded by the
     * platform's reply timeout, and at most {@link Futures#DEFAULT_TIMEOUT} in all).
     *
     * <p>{@link SensorType#RANGE} asks for whatever range finder sits at the position (a sonar, an
     * infra-red or a laser one), so one program reads "the distance ahead" on every robot.
     *
     * <p>Boolean readings ({@link ReturnType#BOOLEAN}) are 1.0 for true (pressed, detected) and
     * 0.0 for false.
     *
     * @param position   where the sensor sits
     * @param type       what it measures
     * @param returnType the unit wanted
     * @return the reading, in {@code returnType}
     * @throws UnsupportedActionException if the robot has no such sensor, or its readings cannot be given in that unit
     * @throws RobotLinkException         if the hardware did not answer
     */
    default double getValue(Position position, SensorType type, ReturnType returnType) {
        return Futures.await(getValueAsync(position, type, returnType), Futures.DEFAULT_TIMEOUT,
                "getValue(" + position + ", " + type + ", " + returnType + ")");
    }

    /**
     * Non-blocking form of {@link #getValue}.
     *
     * @param position   where the sensor sits
     * @param type       what it measures
     * @param returnType the unit wanted
     * @return completes with the reading
     */
    CompletableFuture<Double> getValueAsync(Position position, SensorType type, ReturnType returnType);

    /**
     * Reads a sensor by its name in the description.
     *
     * @param sensorName the sensor's {@code name}
     * @param returnType the unit wanted
     * @return the reading
     */
    default double getValue(String sensorName, ReturnType returnType) {
        return Futures.await(getValueAsync(sensorName, returnType), Futures.DEFAULT_TIMEOUT,
                "getValue(\"" + sensorName + "\", " + returnType + ")");
    }

    /**
     * Non-blocking form of {@link #getValue(String, ReturnType)}.
     *
     * @param sensorName the sensor's name
     * @param returnType the unit wanted
     * @return completes with the reading
     */
    CompletableFuture<Double> getValueAsync(String sensorName, ReturnType returnType);

    /**
     * The robot's pose as estimated from its wheel encoders (odometry), relative to where it was
     * opened (or last {@link #resetPose reset}). Does not block on the hardware.
     *
     * <p>A legged robot (its description has a legged drive) reports no wheel travel: its pose is
     * dead reckoning from the commanded gait. Each walking command counts at its commanded
     * velocities, whole when the robot reports it done, for the time it ran when it was ended
     * early; slipping feet, stumbles and walls are not seen, so the estimate drifts as the real
     * robot's does.
     *
     * @return the estimated pose
     * @throws UnsupportedActionException if the robot has no encoders to estimate from
     */
    Pose pose();

    /**
     * Sets the odometry estimate to the given pose.
     *
     * @param pose the robot's pose now
     */
    void resetPose(Pose pose);
}
