package io.robomw.config.sensing;

import io.robomw.api.Futures;
import io.robomw.api.Position;
import io.robomw.api.ReturnType;
import io.robomw.api.SensorType;
import io.robomw.api.spi.RobotPlatform;
import io.robomw.config.description.RobotDescription;
import io.robomw.config.description.SensorSpec;
import io.robomw.config.drive.Call;

import java.util.Arrays;
import java.util.concurrent.CompletableFuture;
import java.util.stream.Collectors;

/**
 * The robot's perception: finds the sensor a reading asks for in the description in force, checks
 * that its readings can be given in the unit asked (before anything is read), reads it raw from
 * the platform and converts it ({@link SensorConverter}).
 *
 * <p>A reading by position and type takes the first sensor of the description at that position
 * whose type {@link SensorType#matches matches}: {@link SensorType#RANGE} matches any range finder
 * (sonar, infrared, laser, or one declared {@code range}), so one program reads the distance ahead
 * on every robot. A refusal lists the sensors the robot has. Stateless; thread-safe.
 */
public final class SensorReader {

    private final RobotPlatform platform;

    /**
     * @param platform the opened platform
     */
    public SensorReader(RobotPlatform platform) {
        this.platform = platform;
    }

    /**
     * @param d          the description in force
     * @param position   where the sensor sits
     * @param type       what it measures; {@link SensorType#RANGE} for any range finder
     * @param returnType the unit wanted
     * @return completes with the reading; cancelling it cancels the platform's read
     * @throws io.robomw.api.UnsupportedActionException if there is no such sensor, or its readings
     *                                                  cannot be given in that unit
     */
    public CompletableFuture<Double> read(RobotDescription d, Position position, SensorType type, ReturnType returnType) {
        SensorSpec sensor = d.sensors().stream().filter(s -> s.position() == position && type.matches(s.type())).findFirst()
                .orElseThrow(() -> new Call(d.name(), "getValue(" + position + ", " + type + ", " + returnType + ")")
                        .refused("it has no " + wanted(type) + " at " + position + "; its sensors are " + describe(d)));
        return read(d, sensor, returnType);
    }

    /**
     * @param d          the description in force
     * @param sensorName the sensor's name in it
     * @param returnType the unit wanted
     * @return completes with the reading; cancelling it cancels the platform's read
     * @throws io.robomw.api.UnsupportedActionException if there is no such sensor, or its readings
     *                                                  cannot be given in that unit
     */
    public CompletableFuture<Double> read(RobotDescription d, String sensorName, ReturnType returnType) {
        SensorSpec sensor = d.sensor(sensorName).orElseThrow(() -> new Call(d.name(), "getValue(\"" + sensorName + "\", " + returnType + ")")
                .refused("it has no sensor named '" + sensorName + "'; its sensors are " + describe(d)));
        return read(d, sensor, returnType);
    }

    private CompletableFuture<Double> read(RobotDescription d, SensorSpec sensor, ReturnType returnType) {
        String robot = d.name();
        SensorConverter.check(robot, sensor, returnType);
        CompletableFuture<Double> raw = platform.readRaw(sensor.name());
        return Futures.cancelling(raw.thenApply(value -> SensorConverter.convert(robot, sensor, value, returnType)), raw);
    }

    /** @return what a type asks for, in a refusal: {@code SONAR sensor}, or for RANGE every type it matches */
    private static String wanted(SensorType type) {
        if (type != SensorType.RANGE) {
            return type + " sensor";
        }
        return "range finder (" + Arrays.stream(SensorType.values()).filter(SensorType::ranging).map(SensorType::name)
                .collect(Collectors.joining(", ")) + " sensor)";
    }

    /**
     * @param d a description
     * @return its sensors for a message: {@code sonar (SONAR at FRONT), bumper (TOUCH at BACK)}, or {@code none}
     */
    static String describe(RobotDescription d) {
        return d.sensors().isEmpty() ? "none" : d.sensors().stream()
                .map(s -> s.name() + " (" + s.type() + " at " + s.position() + ")").collect(Collectors.joining(", "));
    }
}
