package io.robomw.config.robot;

import io.robomw.api.CommandPreemptedException;
import io.robomw.api.spi.MotorCommand;
import io.robomw.api.spi.RobotPlatform;

import java.util.ArrayList;
import java.util.HashMap;
import java.util.List;
import java.util.Map;
import java.util.concurrent.CompletableFuture;

/**
 * A platform that records the commands it is given and completes them at once (or, when
 * {@link #pending}, leaves their futures to the test), with raw sensor values and motor rotations
 * set by the test.
 */
final class FakePlatform implements RobotPlatform {

    final List<MotorCommand> commands = new ArrayList<>();
    /** The future of each command {@link #run} was given, in order. */
    final List<CompletableFuture<Void>> futures = new ArrayList<>();
    /** The future of each read while {@link #pending}, in order. */
    final List<CompletableFuture<Double>> reads = new ArrayList<>();
    final Map<String, Double> raw = new HashMap<>();
    final Map<String, Double> motorDegrees = new HashMap<>();
    boolean encoders = true;
    /** Whether {@link #run} and {@link #readRaw} leave their futures for the test to complete. */
    volatile boolean pending;
    /** The future {@link #stopAll} returns, or {@code null} for one completed at once. */
    volatile CompletableFuture<Void> stopFuture;
    /** Called with the port before every encoder reading, outside the platform's lock (to block a reader). */
    volatile java.util.function.Consumer<String> beforeRead = port -> { };
    int stops;
    boolean closed;
    /** How often the layer above asked whether a motor has an encoder. */
    int encoderQuestions;

    @Override
    public synchronized CompletableFuture<Void> run(MotorCommand command) {
        CompletableFuture<Void> stop = stopFuture;
        if (stop != null && !stop.isDone()) {
            // As an execution action thread refuses a normal command while the safety stop holds the motors
            return CompletableFuture.failedFuture(CommandPreemptedException.refused(command.name(), "stop"));
        }
        commands.add(command);
        CompletableFuture<Void> f = pending ? new CompletableFuture<>() : CompletableFuture.completedFuture(null);
        futures.add(f);
        return f;
    }

    /** @return the future of the command run last */
    synchronized CompletableFuture<Void> lastFuture() {
        return futures.get(futures.size() - 1);
    }

    @Override
    public synchronized CompletableFuture<Void> stopAll() {
        stops++;
        CompletableFuture<Void> f = stopFuture;
        return f != null ? f : CompletableFuture.completedFuture(null);
    }

    @Override
    public synchronized CompletableFuture<Double> readRaw(String sensorName) {
        if (pending) {
            CompletableFuture<Double> read = new CompletableFuture<>();
            reads.add(read);
            return read;
        }
        Double value = raw.get(sensorName);
        return value == null ? CompletableFuture.failedFuture(new IllegalStateException("no raw value for " + sensorName))
                : CompletableFuture.completedFuture(value);
    }

    @Override
    public double motorDegrees(String port) {
        beforeRead.accept(port);
        return reading(port);
    }

    private synchronized double reading(String port) {
        if (!encoders) {
            throw new UnsupportedOperationException("motor " + port + " has no encoder");
        }
        return motorDegrees.getOrDefault(port, 0.0);
    }

    /**
     * @param port    a motor
     * @param degrees its encoder's reading from now on
     */
    synchronized void turn(String port, double degrees) {
        motorDegrees.put(port, degrees);
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
