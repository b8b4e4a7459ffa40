package io.robomw.config.robot;

import io.robomw.api.Clock;
import io.robomw.api.ManualClock;
import io.robomw.api.spi.HighLevelCommand;
import io.robomw.api.spi.HighLevelPlatform;
import io.robomw.api.spi.MotorCommand;
import io.robomw.api.spi.RobotPlatform;

import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.CompletableFuture;

/**
 * A platform that takes high-level commands and records them, each with a future the test
 * completes, on a manual clock. Motor commands are refused, as a legged robot's platform refuses
 * them.
 */
final class FakeHighLevelPlatform implements RobotPlatform, HighLevelPlatform {

    final ManualClock clock = new ManualClock();
    final List<HighLevelCommand> commands = new ArrayList<>();
    final List<CompletableFuture<Void>> futures = new ArrayList<>();
    int stops;

    @Override
    public synchronized CompletableFuture<Void> execute(HighLevelCommand command) {
        commands.add(command);
        CompletableFuture<Void> f = new CompletableFuture<>();
        futures.add(f);
        return f;
    }

    @Override
    public Clock clock() {
        return clock;
    }

    /** @return the last command sent */
    synchronized HighLevelCommand last() {
        return commands.get(commands.size() - 1);
    }

    @Override
    public CompletableFuture<Void> run(MotorCommand command) {
        return CompletableFuture.failedFuture(new IllegalStateException("a legged robot's platform takes no motor commands: " + command));
    }

    @Override
    public synchronized CompletableFuture<Void> stopAll() {
        stops++;
        return CompletableFuture.completedFuture(null);
    }

    @Override
    public CompletableFuture<Double> readRaw(String sensorName) {
        return CompletableFuture.completedFuture(0.0);
    }

    @Override
    public double motorDegrees(String port) {
        throw new UnsupportedOperationException("no motors");
    }

    @Override
    public boolean hasEncoder(String port) {
        return false;
    }

    @Override
    public void close() {
    }
}
