package io.robomw.platform.rcx;

import io.robomw.api.RobotLinkException;
import io.robomw.api.spi.SensorChannel;
import io.robomw.platform.motor.MotorPlatform;
import io.robomw.platform.sensor.Sensor;
import io.robomw.platform.sensor.SensorPlatform;

import java.io.IOException;
import java.util.concurrent.CompletableFuture;

/**
 * The RCX's sensors on inputs S1..S3 ({@code port: S1}, or {@code 1}): each is set to its type
 * and mode with Set sensor type and Set sensor mode when the robot opens, and read with Get value
 * of its value in that mode:
 * <ul>
 *   <li>{@code touch}: type touch, mode boolean: 1 pressed, 0 released;</li>
 *   <li>{@code light}: type light (the sensor's lamp powered), mode percent: 0..100, as the
 *   firmware scales the raw reading ({@code (1023 - raw) × 25 / 156}, 100 at raw 391 or less);
 *   {@code options: { rcx_value: raw }} reads the raw 0..1023 instead (mode raw).</li>
 * </ul>
 * Rotation sensors that count wheels are the motor platform's (a wheel's {@code counter:}).
 */
public final class RcxSensorPlatform extends SensorPlatform {

    private final RcxBrick brick;

    /**
     * @param motors the motor platform (for tachometers)
     * @param brick  the brick
     */
    public RcxSensorPlatform(MotorPlatform motors, RcxBrick brick) {
        super(motors);
        this.brick = brick;
    }

    /**
     * @param port   an input port name: S1..S3 or 1..3
     * @param source where the name comes from, for messages
     * @return its index: S1 = 0 ... S3 = 2
     * @throws IllegalArgumentException if the RCX has no such input
     */
    static int inputIndex(String port, String source) {
        String p = port.startsWith("S") ? port.substring(1) : port;
        return switch (p) {
            case "1" -> 0;
            case "2" -> 1;
            case "3" -> 2;
            default -> throw new IllegalArgumentException(source + ": the RCX has inputs S1 to S3, not '" + port + "'");
        };
    }

    @Override
    public Sensor createSensor(SensorChannel sensor) throws IOException {
        int input = inputIndex(sensor.port(), "robot '" + brick.robot() + "', sensor '" + sensor.name() + "'");
        return switch (sensor.type()) {
            case TOUCH -> setUp(input, RcxPacket.TYPE_TOUCH, RcxPacket.MODE_BOOLEAN);
            case LIGHT -> setUp(input, RcxPacket.TYPE_LIGHT, "raw".equals(sensor.options().get("rcx_value")) ? RcxPacket.MODE_RAW : RcxPacket.MODE_PERCENT);
            default -> throw new IOException("robot '" + brick.robot() + "': sensor '" + sensor.name() + "': the RCX has no standard "
                    + sensor.type() + " sensor (it supports touch and light; rotation sensors count wheels, as a wheel's counter)");
        };
    }

    private Sensor setUp(int input, int type, int mode) throws IOException {
        brick.request(RcxPacket.SET_SENSOR_TYPE, RcxPacket.setSensorType(input, type));
        brick.request(RcxPacket.SET_SENSOR_MODE, RcxPacket.setSensorMode(input, mode));
        return () -> read(input);
    }

    private CompletableFuture<Double> read(int input) {
        try {
            return CompletableFuture.completedFuture((double) brick.request(RcxPacket.GET_VALUE,
                    RcxPacket.getValue(RcxPacket.SOURCE_SENSOR_VALUE, input)).s16());
        } catch (IOException e) {
            return CompletableFuture.failedFuture(new RobotLinkException("robot '" + brick.robot() + "': reading the RCX failed: " + e.getMessage(), e));
        } catch (RuntimeException e) {
            return CompletableFuture.failedFuture(e);
        }
    }
}
