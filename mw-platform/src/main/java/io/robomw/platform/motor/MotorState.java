package io.robomw.platform.motor;

/**
 * What one motor should be doing, as the {@link MotorPlatform} hands it to a driver ({@link MotorDriver#send}).
 *
 * @param port             the motor port
 * @param degreesPerSecond signed speed; 0 stops the motor
 * @param limitDegrees     degrees still to turn from now before the logic stops it, or
 *                         {@link Double#POSITIVE_INFINITY}; drivers whose brick can stop at a
 *                         rotation limit by itself may pass it on
 * @param stopMode         how to stop when the speed is 0
 */
public record MotorState(String port, double degreesPerSecond, double limitDegrees, StopMode stopMode) {

    /**
     * @param port the motor port
     * @param mode how to stop
     * @return a stopped motor
     */
    public static MotorState stopped(String port, StopMode mode) {
        return new MotorState(port, 0, 0, mode);
    }

    /**
     * The record's own equality (the port equal, the numbers by {@link Double#compare}, the stop
     * mode the same), written out: the motor platform compares states at every cycle of every
     * robot, and the generated one goes through method handles the JIT does not always inline.
     */
    @Override
    public boolean equals(Object o) {
        return this == o || o instanceof MotorState m
                && Double.compare(degreesPerSecond, m.degreesPerSecond) == 0
                && Double.compare(limitDegrees, m.limitDegrees) == 0
                && stopMode == m.stopMode
                && java.util.Objects.equals(port, m.port);
    }

    /** @return whether the motor should be turning */
    public boolean running() {
        return degreesPerSecond != 0;
    }

    /** How a motor stops. */
    public enum StopMode {
        /** Short the motor: it stops at once and holds. */
        BRAKE,
        /** Let it spin down freely. */
        COAST
    }
}
