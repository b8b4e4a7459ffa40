package io.robomw.platform.sensor;

import java.util.concurrent.CompletableFuture;

/**
 * A robot's sensors by name, as its platform reads them: what {@link SensorPlatform#createSensors}
 * sets up. The default is a map of one {@link Sensor} a sensor; a driver with many robots of one
 * description (a simulation) may answer every sensor of a robot from one object.
 */
@FunctionalInterface
public interface Sensors {

    /**
     * @param name a sensor's name
     * @return completes with its raw value (or fails with {@link io.robomw.api.RobotLinkException});
     *         {@code null} if the robot has no sensor of that name
     */
    CompletableFuture<Double> readRaw(String name);
}
