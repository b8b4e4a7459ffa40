package io.robomw.platform.sensor;

import io.robomw.api.ReturnType;
import io.robomw.api.SensorType;
import io.robomw.api.spi.SensorChannel;
import io.robomw.platform.motor.MotorPlatform;

import java.io.IOException;
import java.util.concurrent.CompletableFuture;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Map;

/**
 * The paper's sensor platform: sets up a robot's sensors on its brick and reads them. A platform
 * writer implements {@link #createSensor} (configure the input port, return a reader);
 * {@link #selectMotorSensor} gives a motor's encoder as a sensor.
 */
public abstract class SensorPlatform {

    private final MotorPlatform motors;

    /**
     * @param motors the motor platform whose encoders {@link #selectMotorSensor} reads
     */
    protected SensorPlatform(MotorPlatform motors) {
        this.motors = java.util.Objects.requireNonNull(motors, "motors");
    }

    /**
     * For a platform without motor encoders (a robot that moves by high-level commands):
     * {@link #selectMotorSensor} then refuses every motor sensor.
     */
    protected SensorPlatform() {
        this.motors = null;
    }

    /**
     * Sets up one sensor on the brick (its input mode, say) and returns its reader.
     *
     * @param sensorObject the sensor as the description gives it
     * @return its reader
     * @throws IOException if the brick refused or did not answer
     */
    public abstract Sensor createSensor(SensorChannel sensorObject) throws IOException;

    /**
     * Sets up every sensor of a description: a {@link SensorType#TACHO} channel is its motor's
     * encoder ({@link #selectMotorSensor}), every other one {@link #createSensor}'s reader, in the
     * description's order. A driver may override it to answer all of a robot's sensors from one
     * object (the same reads, less heap a robot).
     *
     * @param channels the sensors as the description gives them
     * @return the robot's sensors, by name
     * @throws IOException if the brick refused one or did not answer
     */
    public Sensors createSensors(List<SensorChannel> channels) throws IOException {
        Map<String, Sensor> byName = new LinkedHashMap<>();
        for (SensorChannel channel : channels) {
            Sensor sensor = channel.type() == SensorType.TACHO
                    ? selectMotorSensor(channel.port(), channel.type(), ReturnType.RAW)
                    : createSensor(channel);
            byName.put(channel.name(), sensor);
        }
        return name -> {
            Sensor sensor = byName.get(name);
            return sensor == null ? null : sensor.readRaw();
        };
    }

    /**
     * A motor's built-in sensor. The default gives the encoder ({@link SensorType#TACHO}) in motor
     * degrees; the return type is converted above this layer.
     *
     * @param motorPort  the motor port
     * @param type       the sensor type
     * @param returnType the unit the program wants (checked above; raw degrees are returned here)
     * @return its reader
     * @throws IllegalArgumentException if the motor has no such sensor
     */
    public Sensor selectMotorSensor(String motorPort, SensorType type, ReturnType returnType) {
        if (motors == null) {
            throw new IllegalArgumentException("motor " + motorPort + " has no " + type + " sensor: this platform has no motors of its own");
        }
        if (type != SensorType.TACHO || !motors.hasEncoder(motorPort)) {
            throw new IllegalArgumentException("robot '" + motors.robot() + "': motor " + motorPort + " has no " + type + " sensor");
        }
        return () -> CompletableFuture.completedFuture(motors.motorDegrees(motorPort));
    }
}
