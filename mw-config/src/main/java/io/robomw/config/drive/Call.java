package io.robomw.config.drive;

import io.robomw.api.UnsupportedActionException;

import java.util.Locale;

/**
 * One call of a verb on one robot, and the checks of its arguments. Every check that fails throws
 * an {@link UnsupportedActionException} before anything is sent, in one format (as dyn4j's
 * {@code ValueOutOfRangeException} builds every range error): the robot, the call, then the value
 * by its name and the rule it broke, with the robot file's key that sets the limit:
 * <pre>
 * robot 'scout' cannot move(1.000, 0.500): speed 0.500 m/s is above its maximum of 0.300 m/s (drive.max_speed)
 * robot 'scout' cannot turn(NaN, 1.0000): angle must be a finite number, got NaN
 * </pre>
 * Each check returns the value, so a check reads as the assignment it guards.
 *
 * @param robot the robot's name
 * @param text  the call as messages name it, {@code move(1.000, 0.500)}
 */
public record Call(String robot, String text) {

    /** A value may exceed its maximum by this fraction (rounding in the caller's arithmetic), no more. */
    private static final double TOLERANCE = 1e-9;

    /**
     * @param robot  the robot's name
     * @param format the call's text as a {@link String#format} pattern ({@code "move(%.3f, %.3f)"})
     * @param args   its arguments
     * @return the call
     */
    public static Call of(String robot, String format, Object... args) {
        return new Call(robot, String.format(Locale.ROOT, format, args));
    }

    /**
     * @param value a value
     * @param name  what it is ({@code "distance"})
     * @return the value
     * @throws UnsupportedActionException if it is not a finite number
     */
    public double finite(double value, String name) {
        if (!Double.isFinite(value)) {
            throw refused(name + " must be a finite number, got " + value);
        }
        return value;
    }

    /**
     * @param value a value
     * @param name  what it is ({@code "speed"})
     * @return the value
     * @throws UnsupportedActionException if it is not a finite number &gt; 0
     */
    public double positive(double value, String name) {
        if (!(value > 0) || !Double.isFinite(value)) {
            throw refused(name + " must be a number > 0, got " + value);
        }
        return value;
    }

    /**
     * @param value a value, whose magnitude is checked (a signed speed)
     * @param max   its maximum magnitude
     * @param name  what it is ({@code "wheel speed"})
     * @param unit  its unit ({@code "m/s"})
     * @param key   the robot file's key that sets the maximum ({@code "drive.max_speed"})
     * @return the value
     * @throws UnsupportedActionException if its magnitude is above the maximum
     */
    public double atMost(double value, double max, String name, String unit, String key) {
        if (Math.abs(value) > max * (1 + TOLERANCE)) {
            throw refused(String.format(Locale.ROOT, "%s %.3f %s is above its maximum of %.3f %s (%s)", name, value, unit, max, unit, key));
        }
        return value;
    }

    /**
     * {@link #positive} and then {@link #atMost}.
     *
     * @param value a value
     * @param max   its maximum
     * @param name  what it is
     * @param unit  its unit
     * @param key   the robot file's key that sets the maximum
     * @return the value
     */
    public double positiveAtMost(double value, double max, String name, String unit, String key) {
        return atMost(positive(value, name), max, name, unit, key);
    }

    /**
     * @param reason why the robot cannot do it
     * @return the exception to throw, naming the robot and the call
     */
    public UnsupportedActionException refused(String reason) {
        return new UnsupportedActionException(robot, text, reason);
    }
}
