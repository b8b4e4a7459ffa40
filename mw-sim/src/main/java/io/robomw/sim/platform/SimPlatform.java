package io.robomw.sim.platform;

import io.robomw.api.spi.MotorCommand;
import io.robomw.api.spi.RobotPlatform;
import io.robomw.platform.BrickPlatform;
import io.robomw.sim.lockstep.Lockstep;
import io.robomw.sim.lockstep.SimFuture;

import java.util.concurrent.CompletableFuture;
import java.util.concurrent.CompletionException;

/**
 * A simulated robot's platform as the Configuration Layer sees it: the standard
 * {@link BrickPlatform}, with its futures turned into {@link SimFuture}s so a program blocking on
 * them lets simulated time advance.
 */
final class SimPlatform implements RobotPlatform {

    private final BrickPlatform platform;
    private final Lockstep lockstep;

    SimPlatform(BrickPlatform platform, Lockstep lockstep) {
        this.platform = platform;
        this.lockstep = lockstep;
    }

    @Override
    public CompletableFuture<Void> run(MotorCommand command) {
        return wrap(platform.run(command));
    }

    @Override
    public void stopAll() {
        platform.stopAll();
    }

    @Override
    public CompletableFuture<Double> readRaw(String sensorName) {
        return wrap(platform.readRaw(sensorName));
    }

    @Override
    public double motorDegrees(String port) {
        return platform.motorDegrees(port);
    }

    @Override
    public boolean hasEncoder(String port) {
        return platform.hasEncoder(port);
    }

    @Override
    public void close() {
        platform.close();
    }

    private <T> CompletableFuture<T> wrap(CompletableFuture<T> inner) {
        if (inner instanceof SimFuture) {
            return inner;
        }
        SimFuture<T> f = lockstep.newFuture();
        inner.whenComplete((v, e) -> lockstep.defer(() -> {
            if (e == null) {
                f.complete(v);
            } else {
                f.completeExceptionally(e instanceof CompletionException && e.getCause() != null ? e.getCause() : e);
            }
        }));
        return f;
    }
}
