package io.robomw.api.spi;

import java.util.Objects;

/**
 * What one motor is to do: turn at a speed, for a number of degrees or until told otherwise.
 *
 * @param port             the motor port, as the platform names it ({@code "B"}, {@code "M1"})
 * @param degreesPerSecond signed speed of the motor shaft; positive is the motor's forward
 * @param degrees          how far to turn, ≥ 0, in degrees of the motor shaft, or
 *                         {@link Double#POSITIVE_INFINITY} to run until another command or a stop
 */
public record MotorTarget(String port, double degreesPerSecond, double degrees) {

    /** Checks the values. */
    public MotorTarget {
        Objects.requireNonNull(port, "port");
        if (!Double.isFinite(degreesPerSecond)) {
            throw new IllegalArgumentException("motor " + port + ": degreesPerSecond must be finite, got " + degreesPerSecond);
        }
        if (Double.isNaN(degrees) || degrees < 0) {
            throw new IllegalArgumentException("motor " + port + ": degrees must be >= 0 or infinite, got " + degrees);
        }
    }

    /**
     * @param port             the motor port
     * @param degrees          signed rotation; the sign gives the direction
     * @param degreesPerSecond speed magnitude
     * @return a target that rotates by {@code degrees} and stops
     */
    public static MotorTarget rotate(String port, double degrees, double degreesPerSecond) {
        return new MotorTarget(port, Math.copySign(Math.abs(degreesPerSecond), degrees), Math.abs(degrees));
    }

    /**
     * @param port             the motor port
     * @param degreesPerSecond signed speed
     * @return a target that runs until another command or a stop
     */
    public static MotorTarget run(String port, double degreesPerSecond) {
        return new MotorTarget(port, degreesPerSecond, Double.POSITIVE_INFINITY);
    }

    /** @return whether this target runs until told otherwise */
    public boolean continuous() {
        return Double.isInfinite(degrees);
    }
}
