package io.robomw.config.robot;

import io.robomw.api.spi.MotorCommand;
import io.robomw.api.spi.RobotPlatform;

import java.util.ArrayList;
import java.util.HashMap;
import java.util.List;
import java.util.Map;
import java.util.concurrent.CompletableFuture;

/**
 * A platform that records the commands it is given and completes them at once, with raw sensor
 * values and motor rotations set by the test.
 */
final class FakePlatform implements RobotPlatform {

    final List<MotorCommand> commands = new ArrayList<>();
    final Map<String, Double> raw = new HashMap<>();
    final Map<String, Double> motorDegrees = new HashMap<>();
    boolean encoders = true;
    int stops;
    boolean closed;
    /** How often the layer above asked whether a motor has an encoder. */
    int encoderQuestions;

    @Override
    public synchronized CompletableFuture<Void> run(MotorCommand command) {
        commands.add(command);
        return CompletableFuture.completedFuture(null);
    }

    @Override
    public synchronized CompletableFuture<Void> stopAll() {
        stops++;
        return CompletableFuture.completedFuture(null);
    }

    @Override
    public synchronized CompletableFuture<Double> readRaw(String sensorName) {
        Double value = raw.get(sensorName);
        return value == null ? CompletableFuture.failedFuture(new IllegalStateException("no raw value for " + sensorName))
                : CompletableFuture.completedFuture(value);
    }

    @Override
    public synchronized double motorDegrees(String port) {
        if (!encoders) {
            throw new UnsupportedOperationException("motor " + port + " has no encoder");
        }
        return motorDegrees.getOrDefault(port, 0.0);
    }

    @Override
    public synchronized boolean hasEncoder(String port) {
        encoderQuestions++;
        return encoders;
    }

    @Override
    public synchronized void close() {
        closed = true;
    }
}
