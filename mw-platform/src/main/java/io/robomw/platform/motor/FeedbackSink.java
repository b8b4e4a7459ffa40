package io.robomw.platform.motor;

/**
 * Where a {@link MotorDriver} reports what it reads from the brick, on the link side. A reading is
 * dated by the driver's {@link LinkTiming#oneWayDelayNanos()}: the brick took it that long before
 * it arrived.
 */
public interface FeedbackSink {

    /**
     * Records an encoder reading, by the port's position in the description's motor ports (for
     * drivers that read every motor in that order: no lookup by name).
     *
     * @param portIndex the port's index in the platform's ports
     * @param degrees   degrees of the motor shaft since the platform opened
     */
    void degrees(int portIndex, double degrees);

    /**
     * Records an encoder reading.
     *
     * @param port    the motor port
     * @param degrees degrees of the motor shaft since the platform opened
     * @throws IllegalArgumentException if the platform drives no motor on that port
     */
    void degrees(String port, double degrees);

    /**
     * Says that the brick has stopped this motor by itself (it reports the output idle) after the
     * last state sent for it: a limited rotation it ends at its limit (the NXT's tacho limit; see
     * {@link LinkTiming#stopsAtLimit()}). Ends the rotation that state started, if it did; a
     * rotation meant to end braked is braked from the link side at once, with no word from the
     * action thread.
     *
     * @param port the motor port
     */
    void stoppedAtLimit(String port);
}
