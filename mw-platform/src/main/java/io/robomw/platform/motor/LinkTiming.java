package io.robomw.platform.motor;

/**
 * A driver's link, as the motor platform needs to know it to stop motors on target: the handful of
 * figures a driver measures or knows about its brick, in one value, which the
 * {@link RotationPredictor} reads (a slow link's delays must not become overshoot). Every figure
 * has a default that suits a link without delay, so a driver on a fast link implements none; one
 * on a slow link overrides what it measures (a {@code RoundTripEstimate}). Figures may change
 * while the platform runs (a measured round trip, a firmware feature learnt when the robot opened);
 * they are read on any thread and must not block.
 */
public interface LinkTiming {

    /** A link without delay, whose brick does nothing by itself: every default. */
    LinkTiming NONE = new LinkTiming() {
    };

    /**
     * How long the link takes one way: a reading is that old when it arrives, and a command takes
     * that long to reach the brick. Drivers on slow links give half their measured round trip.
     *
     * @return nanoseconds; 0 by default
     */
    default long oneWayDelayNanos() {
        return 0;
    }

    /**
     * @return how long until the exchange under way on the link ends (on a link that carries one
     *         exchange at a time, a command handed to it now waits that long), nanoseconds; 0 by default
     */
    default long nanosUntilFree() {
        return 0;
    }

    /**
     * How long a command handed to the link now takes to reach the brick.
     *
     * @return nanoseconds; by default {@link #nanosUntilFree()} plus {@link #oneWayDelayNanos()}
     */
    default long commandDelayNanos() {
        return nanosUntilFree() + oneWayDelayNanos();
    }

    /**
     * @return how long before {@link MotorDriver#send} returns the brick acted on the last command
     *         it sent, nanoseconds; by default the one-way delay (the reply's way back)
     */
    default long actedNanosAgo() {
        return oneWayDelayNanos();
    }

    /**
     * How long until the link side can next send a command after this service: a cycle, or the
     * exchanges a service runs if they take longer (a slow link).
     *
     * @param cycleNanos the execution action thread's period
     * @return nanoseconds; by default a cycle
     */
    default long nextSendNanos(long cycleNanos) {
        return cycleNanos;
    }

    /**
     * @return whether the brick ends a limited rotation ({@link MotorState#limitDegrees()}) by
     *         itself and the driver says so ({@link FeedbackSink#stoppedAtLimit}); by default no: the
     *         middleware stops it by the encoder
     */
    default boolean stopsAtLimit() {
        return false;
    }

    /**
     * @return whether the link side stops limited rotations itself, just in time by its own
     *         prediction, rather than waiting for the execution action thread's decision (which a
     *         slow link carrying one exchange at a time can send an exchange late); by default no
     */
    default boolean stopsOnLinkSide() {
        return false;
    }

    /**
     * @param port a motor port
     * @return the degrees one count of its encoder stands for, when the encoder is so coarse that a
     *         reading is only the nearest count (a rotation sensor's 22.5°): the platform then
     *         predicts by the motor's own speed since it started, within half a count of the
     *         reading; 0 (the default) for encoders whose readings are taken as they are
     */
    default double encoderResolutionDegrees(String port) {
        return 0;
    }

    /**
     * The speed a brick actually turns a motor at in a state: a brick that sets speeds in steps
     * (the RCX's eight power steps) gives its step's speed, so predictions of where the motor is
     * use it.
     *
     * @param state a motor state
     * @return degrees per second, signed; by default the state's own speed
     */
    default double actualDegreesPerSecond(MotorState state) {
        return state.degreesPerSecond();
    }
}
