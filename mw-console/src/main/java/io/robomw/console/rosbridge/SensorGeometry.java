package io.robomw.console.rosbridge;

import io.robomw.api.Position;
import io.robomw.api.SensorInfo;
import io.robomw.api.SensorType;

import java.util.Map;

/**
 * What a ROS client needs to know about a sensor that the {@link io.robomw.api.Robot} API does not
 * say: a range finder's beam and limits ({@code sensor_msgs/msg/Range}'s fields), where it sits on
 * the body (its frame in {@code /tf_static}), and how often to read it. Taken from the simulator's
 * model of the sensor, or the robot file's sensor {@code options} (the same keys:
 * docs/simulation.md), or else the simulator's defaults for the sensor's type and position.
 *
 * @param radiation   ultrasound or infra-red, as {@code Range.radiation_type} says
 * @param fieldOfView the beam's full angle, radians
 * @param minRange    the nearest distance it measures, metres
 * @param maxRange    the farthest, metres
 * @param rateHz      readings per second the bridge takes
 * @param x           mount point, metres forwards of the body's centre
 * @param y           mount point, metres to the left
 * @param yaw         the direction it faces, radians anti-clockwise from forwards
 */
public record SensorGeometry(Radiation radiation, double fieldOfView, double minRange, double maxRange, double rateHz, double x, double y, double yaw) {

    /** A sonar's defaults in the simulator: beam and limits. */
    static final double SONAR_BEAM = 0.5;
    static final double SONAR_MIN = 0.03;
    static final double SONAR_MAX = 2.55;
    /** Any other range finder's defaults in the simulator. */
    static final double BEAM_MIN = 0.06;
    static final double BEAM_MAX = 0.80;
    /** Readings per second when nothing says. */
    public static final double DEFAULT_RATE_HZ = 10;

    /** {@code sensor_msgs/msg/Range.radiation_type}, with the message's constant values. */
    public enum Radiation {
        /** {@code ULTRASOUND = 0}. */
        ULTRASOUND(0),
        /** {@code INFRARED = 1} (every light-based range finder: infra-red and laser). */
        INFRARED(1);

        private final int code;

        Radiation(int code) {
            this.code = code;
        }

        /** @return its value in the message */
        public int code() {
            return code;
        }
    }

    /** Checks the numbers. */
    public SensorGeometry {
        if (!(rateHz > 0) || !Double.isFinite(rateHz) || !(maxRange >= minRange) || !Double.isFinite(x) || !Double.isFinite(y) || !Double.isFinite(yaw)) {
            throw new IllegalArgumentException("sensor geometry needs a rate > 0, max_range >= min_range and finite numbers, got " + this);
        }
    }

    /**
     * @param sensor a sensor as {@link io.robomw.api.Robot#sensors()} lists it
     * @return the simulator's defaults for its type and position, mounted at the body's centre
     */
    public static SensorGeometry defaults(SensorInfo sensor) {
        boolean sonar = sensor.type() == SensorType.SONAR;
        return new SensorGeometry(sonar ? Radiation.ULTRASOUND : Radiation.INFRARED, sonar ? SONAR_BEAM : 0, sonar ? SONAR_MIN : BEAM_MIN,
                sonar ? SONAR_MAX : BEAM_MAX, DEFAULT_RATE_HZ, 0, 0, yaw(sensor.position()));
    }

    /**
     * @param sensor  the sensor
     * @param options its {@code options} in the robot file ({@code min_range}, {@code max_range},
     *                {@code beam_width}, {@code rate_hz}, {@code x}, {@code y}, {@code angle})
     * @return the defaults with what the options give
     */
    public static SensorGeometry fromOptions(SensorInfo sensor, Map<String, Object> options) {
        SensorGeometry d = defaults(sensor);
        return new SensorGeometry(d.radiation, number(options, "beam_width", d.fieldOfView), number(options, "min_range", d.minRange),
                number(options, "max_range", d.maxRange), number(options, "rate_hz", d.rateHz), number(options, "x", d.x), number(options, "y", d.y),
                number(options, "angle", d.yaw));
    }

    /**
     * @param hz readings per second
     * @return this geometry read at that rate
     */
    public SensorGeometry withRate(double hz) {
        return new SensorGeometry(radiation, fieldOfView, minRange, maxRange, hz, x, y, yaw);
    }

    /**
     * @param position where a sensor sits
     * @return the direction it faces, radians from forwards
     */
    static double yaw(Position position) {
        return switch (position) {
            case FRONT, TOP, BOTTOM, CENTER -> 0;
            case BACK -> Math.PI;
            case LEFT -> Math.PI / 2;
            case RIGHT -> -Math.PI / 2;
            case FRONT_LEFT -> Math.PI / 4;
            case FRONT_RIGHT -> -Math.PI / 4;
            case BACK_LEFT -> 3 * Math.PI / 4;
            case BACK_RIGHT -> -3 * Math.PI / 4;
        };
    }

    private static double number(Map<String, Object> options, String key, double fallback) {
        return options.get(key) instanceof Number n ? n.doubleValue() : fallback;
    }
}
