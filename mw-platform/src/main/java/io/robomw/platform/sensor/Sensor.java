package io.robomw.platform.sensor;

import java.util.concurrent.CompletableFuture;

/** One sensor a {@link SensorPlatform} created: reads raw values. */
@FunctionalInterface
public interface Sensor {

    /**
     * @return completes with a raw value, or fails with {@link io.robomw.api.RobotLinkException}
     */
    CompletableFuture<Double> readRaw();
}
