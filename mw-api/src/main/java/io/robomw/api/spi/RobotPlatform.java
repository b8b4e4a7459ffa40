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
     *         motors, or {@link io.robomw.api.RobotLinkException} when the link fails. Cancelling
     *         it ends the command at the next cycle: its motors brake
     */
    CompletableFuture<Void> run(MotorCommand command);

    /**
     * Runs a motor command whose completion nobody waits for: a continuous command a controller
     * repeats at every tick (the Instruction Layer's {@code drive}). It goes through the same
     * execution action thread, in the same order and under the same clash rules as {@link #run};
     * only the caller's future is not made, so a platform that wraps futures (a simulator's, which
     * wake programs at the end of a step) need not build and complete one per tick. How the
     * command ends is not reported to the caller, as with {@code run} when its future is dropped.
     * Returns at once.
     *
     * <p>The default runs it with {@link #run} and drops the future.
     *
     * @param command the motors and their targets
     */
    default void runDetached(MotorCommand command) {
        run(command);
    }

    /**
     * Stops every motor with safety priority: every running command ends (interrupted), and no
     * normal command queued with the stop restarts a motor. Returns at once.
     *
     * @return completes once the stop has been handed to the hardware (written to the link; a
     *         simulator's motors have stopped) and the stop no longer holds the motors, so a
     *         command run then is admitted as usual; fails with
     *         {@link io.robomw.api.RobotLinkException} naming the robot if the link is down or the
     *         platform has failed
     */
    CompletableFuture<Void> stopAll();

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
     * @return whether {@link #motorDegrees} can be asked for this motor; the same for the whole
     *         life of the platform (the Configuration Layer may remember it)
     */
    boolean hasEncoder(String port);

    /** Stops the motors and closes the link. Idempotent. */
    @Override
    void close();
}
