package io.robomw.platform.ev3;

import io.robomw.api.RobotException;
import io.robomw.api.RobotLinkException;
import io.robomw.api.SensorType;
import io.robomw.api.spi.SensorChannel;
import io.robomw.platform.motor.MotorPlatform;
import io.robomw.platform.sensor.Sensor;
import io.robomw.platform.sensor.SensorPlatform;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.io.IOException;
import java.util.Map;
import java.util.concurrent.CompletableFuture;

/**
 * The EV3's sensor platform: sensors on S1..S4 are read with opINPUT_DEVICE READY_SI, which
 * returns the value in the unit the brick reports (its "SI" value, as a float), once the device is
 * ready in the asked type and mode. The robot description's conversion turns that into the
 * quantity's SI unit.
 *
 * <table>
 *   <caption>device type and mode by sensor type</caption>
 *   <tr><th>sensor {@code type}</th><th>EV3 type / mode</th><th>value the brick reports</th><th>conversion</th></tr>
 *   <tr><td>touch</td><td>16 / 0</td><td>1 pressed, 0 released</td><td>none</td></tr>
 *   <tr><td>light</td><td>29 / 0 (reflected)</td><td>percent 0..100</td><td>{@code scale: 0.01}</td></tr>
 *   <tr><td>color</td><td>29 / 2</td><td>colour number 0..7</td><td>none</td></tr>
 *   <tr><td>sonar</td><td>30 / 0</td><td>centimetres 0..255 (255: nothing in range)</td><td>{@code scale: 0.01}</td></tr>
 *   <tr><td>gyro</td><td>32 / 0</td><td>degrees, clockwise positive</td><td>{@code scale: -0.0174533}</td></tr>
 *   <tr><td>infrared</td><td>33 / 0</td><td>proximity percent 0..100 (about 70 cm at 100)</td><td>{@code scale: 0.007}</td></tr>
 * </table>
 *
 * Sensor options: {@code ev3_type: N} and {@code ev3_mode: M} ask for another device type or mode
 * (any sensor type may then be used); {@code ev3_value: raw} reads with READY_RAW, which returns
 * the device's raw integer instead. Each port is set to its type and mode with one read when the
 * robot opens. A value the brick marks as missing (NaN) fails the read, naming the port: usually
 * nothing, or another device, is plugged in there. Reads run on the caller's thread, one exchange
 * at a time on the brick's channel.
 */
public final class Ev3SensorPlatform extends SensorPlatform {

    private static final Logger LOG = LoggerFactory.getLogger(Ev3SensorPlatform.class);

    /** Option: the device type number to ask for. */
    public static final String OPTION_TYPE = "ev3_type";
    /** Option: the mode to ask for. */
    public static final String OPTION_MODE = "ev3_mode";
    /** Option: {@code si} (default, READY_SI) or {@code raw} (READY_RAW). */
    public static final String OPTION_VALUE = "ev3_value";

    private final Ev3Brick brick;

    /**
     * @param motors the motor platform (for tachometers)
     * @param brick  the brick
     */
    public Ev3SensorPlatform(MotorPlatform motors, Ev3Brick brick) {
        super(motors);
        this.brick = brick;
    }

    /** How a sensor is read. */
    public enum Reading {
        /** READY_SI: DATAF in the device's unit. */
        SI,
        /** READY_RAW: DATA32, the device's raw value. */
        RAW
    }

    /**
     * A port's device type, mode and reading.
     *
     * @param type    the device type number
     * @param mode    the mode
     * @param reading how it is read
     */
    public record Setup(int type, int mode, Reading reading) {
    }

    /**
     * @param sensor a sensor of the description
     * @return the device type, mode and reading it gets: the options' override, else the default
     *         for its type (the brick emulator uses this too, to know which device is plugged in)
     * @throws IllegalArgumentException if an option is malformed, or the type has no EV3 sensor and no override
     */
    public static Setup setup(SensorChannel sensor) {
        Map<String, Object> o = sensor.options();
        int[] byType = defaultTypeAndMode(sensor.type());
        Integer type = option(sensor, OPTION_TYPE, 1, 127);
        Integer mode = option(sensor, OPTION_MODE, 0, 7);
        if (type == null && byType == null) {
            throw new IllegalArgumentException("sensor '" + sensor.name() + "': the EV3 has no standard " + sensor.type()
                    + " sensor (it supports touch, light, color, sonar, gyro and infrared); give options: { ev3_type: N, ev3_mode: M }");
        }
        Object value = o.getOrDefault(OPTION_VALUE, "si");
        Reading reading = switch (value.toString().toLowerCase(java.util.Locale.ROOT)) {
            case "si" -> Reading.SI;
            case "raw" -> Reading.RAW;
            default -> throw new IllegalArgumentException("sensor '" + sensor.name() + "': option " + OPTION_VALUE + " must be si or raw, got '" + value + "'");
        };
        return new Setup(type != null ? type : byType[0], mode != null ? mode : type != null ? 0 : byType[1], reading);
    }

    private static int[] defaultTypeAndMode(SensorType type) {
        return switch (type) {
            case TOUCH -> new int[]{Ev3Device.TOUCH.type(), 0};
            case LIGHT -> new int[]{Ev3Device.COLOR.type(), 0};
            case COLOR -> new int[]{Ev3Device.COLOR.type(), 2};
            case SONAR -> new int[]{Ev3Device.ULTRASONIC.type(), 0};
            case GYRO -> new int[]{Ev3Device.GYRO.type(), 0};
            case INFRARED -> new int[]{Ev3Device.INFRARED.type(), 0};
            default -> null;
        };
    }

    private static Integer option(SensorChannel sensor, String key, int min, int max) {
        Object v = sensor.options().get(key);
        if (v == null) {
            return null;
        }
        if (v instanceof Number n && n.doubleValue() == Math.rint(n.doubleValue()) && n.intValue() >= min && n.intValue() <= max) {
            return n.intValue();
        }
        throw new IllegalArgumentException("sensor '" + sensor.name() + "': option " + key + " must be an integer " + min + ".." + max + ", got '" + v + "'");
    }

    @Override
    public Sensor createSensor(SensorChannel sensor) throws IOException {
        int no = Ev3Ports.inputNumber(sensor.port());
        Setup setup = setup(sensor);
        Ev3Command.Builder b = Ev3Command.withReply(4);
        Ev3Command read = (setup.reading() == Reading.SI ? b.inputReadySi(no, setup.type(), setup.mode(), 0)
                : b.inputReadyRaw(no, setup.type(), setup.mode(), 0)).build();
        double first = decode(setup, brick.request(read));
        if (Double.isNaN(first)) {
            LOG.warn("robot '{}': sensor '{}' on {} gives no value yet (device type {} mode {}); is that sensor plugged in there?",
                    brick.robot(), sensor.name(), Ev3Ports.inputName(no), setup.type(), setup.mode());
        }
        return () -> {
            try {
                double v = decode(setup, brick.request(read));
                if (Double.isNaN(v)) {
                    return CompletableFuture.failedFuture(new RobotException("robot '" + brick.robot() + "': sensor '" + sensor.name() + "' on "
                            + Ev3Ports.inputName(no) + ": the EV3 reported no value (NaN) for device type " + setup.type() + " mode " + setup.mode()
                            + "; plug that sensor into " + Ev3Ports.inputName(no) + " or fix the port in the robot file"));
                }
                return CompletableFuture.completedFuture(v);
            } catch (IOException e) {
                return CompletableFuture.failedFuture(new RobotLinkException("robot '" + brick.robot() + "': reading sensor '" + sensor.name()
                        + "' on the EV3 failed: " + e.getMessage(), e));
            } catch (RuntimeException e) {
                return CompletableFuture.failedFuture(e);
            }
        };
    }

    /** @return the reading, or NaN where the brick marked it missing */
    private static double decode(Setup setup, Ev3Reply reply) {
        if (setup.reading() == Reading.SI) {
            return reply.dataF(0);
        }
        int raw = reply.data32(0);
        return raw == Ev3Reply.NAN_DATA32 ? Double.NaN : raw;
    }
}
