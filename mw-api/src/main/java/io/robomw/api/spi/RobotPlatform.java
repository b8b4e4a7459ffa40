package io.robomw.api.spi;

import java.util.concurrent.CompletableFuture;

/**
 * A running robot platform, as the Configuration Layer drives it: motor commands in degrees, raw
 * sensor values. Implementations run motor commands through their execution action thread and
 * must not block the caller on I/O except in {@link #readRaw} (bounded by a timeout) and
 * {@link #close()}.
 */
public interface RobotPlatform extends AutoCloseable {

    /**
     * Runs a motor command. Returns at once.
     *
     * @param command the motors and their targets
     * @return completes when every target is reached; fails with
     *         {@link io.robomw.api.CommandPreemptedException} when a newer command takes one of its
     *         motors, or {@link io.robomw.api.RobotLinkException} when the link fails
     */
    CompletableFuture<Void> run(MotorCommand command);

    /** Stops every motor with safety priority. Returns once the stop is scheduled. */
    void stopAll();

    /**
     * Reads one sensor's raw value.
     *
     * @param sensorName the sensor's name, as in {@link PlatformConfig#sensors()}
     * @return completes with the raw value, or fails with {@link io.robomw.api.RobotLinkException}
     */
    CompletableFuture<Double> readRaw(String sensorName);

    /**
     * The latest known rotation of a motor, from its encoder, without blocking on I/O.
     *
     * @param port the motor port
     * @return degrees of the motor shaft since the platform opened; positive is the motor's forward
     * @throws UnsupportedOperationException if the motor has no encoder
     */
    double motorDegrees(String port);

    /**
     * @param port the motor port
     * @return whether {@link #motorDegrees} can be asked for this motor
     */
    boolean hasEncoder(String port);

    /** Stops the motors and closes the link. Idempotent. */
    @Override
    void close();
}
