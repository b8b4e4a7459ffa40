package io.robomw.config.sensing;

import io.robomw.api.Quantity;
import io.robomw.api.ReturnType;
import io.robomw.api.SensorType;
import io.robomw.api.UnsupportedActionException;
import io.robomw.config.description.Conversion;
import io.robomw.config.description.SensorSpec;

/**
 * Converts a sensor's raw reading into the unit a program asks for: first into the SI unit of the
 * sensor's quantity with the description's {@link Conversion}, then into the {@link ReturnType}.
 * Tachometers report motor degrees and joints their servo's degrees, and their conversion is applied
 * in degrees (a gear ratio, say) before the result is taken as an angle. Stateless.
 */
public final class SensorConverter {

    private SensorConverter() {
    }

    /**
     * @param robot      the robot's name, for the error
     * @param sensor     the sensor
     * @param returnType the unit wanted
     * @throws UnsupportedActionException if the sensor's readings cannot be given in that unit
     */
    public static void check(String robot, SensorSpec sensor, ReturnType returnType) {
        Quantity q = sensor.type().quantity();
        boolean ok = switch (returnType) {
            case BOOLEAN -> q == Quantity.PRESENCE || sensor.conversion().threshold().isPresent();
            case LUX -> q == Quantity.RATIO && sensor.conversion().luxAtFullScale().isPresent();
            default -> returnType.fits(q);
        };
        if (!ok) {
            throw new UnsupportedActionException(robot, "read sensor '" + sensor.name() + "' in " + returnType,
                    "a " + sensor.type() + " sensor measures " + q + (returnType == ReturnType.BOOLEAN
                            ? "; give its conversion a threshold to read it as BOOLEAN"
                            : returnType == ReturnType.LUX ? "; give its conversion lux_at_full_scale to read it in LUX" : ""));
        }
    }

    /**
     * @param robot      the robot's name, for the error
     * @param sensor     the sensor
     * @param raw        its raw reading
     * @param returnType the unit wanted
     * @return the reading in that unit
     */
    public static double convert(String robot, SensorSpec sensor, double raw, ReturnType returnType) {
        check(robot, sensor, returnType);
        if (returnType == ReturnType.RAW) {
            return raw;
        }
        double si = toSi(sensor, raw);
        return switch (returnType) {
            case RAW -> raw;
            case PERCENT -> si * 100;
            case METERS, RADIANS, RADIANS_PER_SECOND, METERS_PER_SECOND_SQUARED, DECIBELS, COLOR_ID -> si;
            case CENTIMETERS -> si * 100;
            case MILLIMETERS -> si * 1000;
            case DEGREES, DEGREES_PER_SECOND -> Math.toDegrees(si);
            case LUX -> si * sensor.conversion().luxAtFullScale().orElseThrow();
            case BOOLEAN -> booleanValue(sensor, si);
        };
    }

    private static double toSi(SensorSpec sensor, double raw) {
        double converted = sensor.conversion().apply(raw);
        return sensor.type() == SensorType.TACHO || sensor.type() == SensorType.JOINT ? Math.toRadians(converted) : converted;
    }

    private static double booleanValue(SensorSpec sensor, double si) {
        Conversion c = sensor.conversion();
        if (c.threshold().isPresent()) {
            double t = c.threshold().getAsDouble();
            return (c.trueBelow() ? si <= t : si >= t) ? 1.0 : 0.0;
        }
        return si >= 0.5 ? 1.0 : 0.0;
    }
}
