package io.robomw.config.description;

import java.util.List;
import java.util.OptionalDouble;

/**
 * How a sensor's raw value becomes a value of its quantity in SI units (metres, radians, a 0..1
 * fraction, decibels, presence 0/1), and which extra return types it supports.
 *
 * <p>The value is {@code raw * scale + offset}, or, when a table is given, the piecewise-linear
 * interpolation of the table (clamped at its ends). A threshold lets the reading be asked as
 * {@link io.robomw.api.ReturnType#BOOLEAN}: true when the value is at or above it, or at or below
 * it when {@code trueBelow} is set.
 *
 * @param scale          multiplier on the raw value
 * @param offset         added after scaling
 * @param table          raw → value points, ascending in raw; empty for the linear form
 * @param threshold      boundary for boolean readings, in the converted unit, if any
 * @param trueBelow      whether values at or below the threshold read true
 * @param luxAtFullScale lux at a light reading of 1.0, if calibrated
 */
public record Conversion(double scale, double offset, List<Point> table, OptionalDouble threshold,
                         boolean trueBelow, OptionalDouble luxAtFullScale) {

    /** Raw values unchanged. */
    public static final Conversion IDENTITY = new Conversion(1, 0, List.of(), OptionalDouble.empty(), false, OptionalDouble.empty());

    /** Copies the table. */
    public Conversion {
        table = List.copyOf(table);
    }

    /**
     * @param raw a raw reading
     * @return the value in the sensor quantity's SI unit
     */
    public double apply(double raw) {
        if (table.isEmpty()) {
            return raw * scale + offset;
        }
        if (raw <= table.get(0).raw()) {
            return table.get(0).value();
        }
        for (int i = 1; i < table.size(); i++) {
            Point a = table.get(i - 1);
            Point b = table.get(i);
            if (raw <= b.raw()) {
                return a.value() + (raw - a.raw()) * (b.value() - a.value()) / (b.raw() - a.raw());
            }
        }
        return table.get(table.size() - 1).value();
    }

    /**
     * The raw value a sensor described by this conversion reports for an SI value: what a
     * simulator or an emulator must produce so that {@link #apply} gives the value back. For a
     * table, the first segment whose values span {@code value} is inverted (tables of distance
     * sensors fall as raw rises); values beyond the table give its end points.
     *
     * @param value a value in the quantity's SI unit
     * @return the raw reading
     */
    public double invert(double value) {
        if (table.isEmpty()) {
            return (value - offset) / scale;
        }
        for (int i = 1; i < table.size(); i++) {
            Point a = table.get(i - 1);
            Point b = table.get(i);
            double lo = Math.min(a.value(), b.value());
            double hi = Math.max(a.value(), b.value());
            if (value >= lo && value <= hi && a.value() != b.value()) {
                return a.raw() + (value - a.value()) * (b.raw() - a.raw()) / (b.value() - a.value());
            }
        }
        Point first = table.get(0);
        Point last = table.get(table.size() - 1);
        return Math.abs(value - first.value()) <= Math.abs(value - last.value()) ? first.raw() : last.raw();
    }

    /**
     * One point of a conversion table.
     *
     * @param raw   the raw value
     * @param value the converted value
     */
    public record Point(double raw, double value) {
    }
}
