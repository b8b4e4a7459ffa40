package io.robomw.sim.platform;

import io.robomw.api.Clock;
import io.robomw.api.Futures;
import io.robomw.api.spi.HighLevelCommand;
import io.robomw.api.spi.HighLevelPlatform;
import io.robomw.api.spi.MotorCommand;
import io.robomw.api.spi.RobotPlatform;
import io.robomw.sim.lockstep.Lockstep;
import io.robomw.sim.lockstep.SimFuture;

import java.util.concurrent.CompletableFuture;
import java.util.concurrent.CompletionException;

/**
 * A simulated robot's platform as the Configuration Layer sees it: the standard
 * {@link io.robomw.platform.BrickPlatform} (or, for a legged robot, a
 * {@link io.robomw.platform.command.HighLevelRobotPlatform}), with its futures turned into
 * {@link SimFuture}s so a program blocking on them lets simulated time advance; cancelling one
 * cancels the platform's own, which ends its command at the next cycle.
 */
class SimPlatform implements RobotPlatform {

    private final RobotPlatform platform;
    private final Lockstep lockstep;

    SimPlatform(RobotPlatform platform, Lockstep lockstep) {
        this.platform = platform;
        this.lockstep = lockstep;
    }

    /** The same for a legged robot's platform, which also takes high-level commands. */
    static class HighLevel extends SimPlatform implements HighLevelPlatform {
        private final HighLevelPlatform highLevel;

        <P extends RobotPlatform & HighLevelPlatform> HighLevel(P platform, Lockstep lockstep) {
            super(platform, lockstep);
            this.highLevel = platform;
        }

        @Override
        public CompletableFuture<Void> execute(HighLevelCommand command) {
            return wrap(highLevel.execute(command));
        }

        @Override
        public Clock clock() {
            return highLevel.clock();
        }
    }

    /**
     * A vehicle's platform: high-level commands, and its true pose in the world (x east, y north,
     * heading anti-clockwise from east, z its altitude) as a vehicle's autopilot reports it.
     */
    static final class Vehicle extends HighLevel implements io.robomw.api.spi.PoseSource {
        private final io.robomw.sim.vehicle.SimVehicle vehicle;
        private final Runnable onClose;

        <P extends RobotPlatform & HighLevelPlatform> Vehicle(P platform, Lockstep lockstep, io.robomw.sim.vehicle.SimVehicle vehicle,
                                                              Runnable onClose) {
            super(platform, lockstep);
            this.vehicle = vehicle;
            this.onClose = onClose;
        }

        @Override
        public java.util.Optional<io.robomw.api.Pose> reportedPose() {
            io.robomw.sim.vehicle.SimVehicle.Snapshot s = vehicle.snapshot();
            return java.util.Optional.of(new io.robomw.api.Pose(s.x(), s.y(), s.heading(), s.z()));
        }

        @Override
        public void close() {
            onClose.run();
            super.close();
        }
    }

    @Override
    public CompletableFuture<Void> run(MotorCommand command) {
        return wrap(platform.run(command));
    }

    /** No simulated future: nobody waits on it, so nothing is deferred to the end of the step for it. */
    @Override
    public void runDetached(MotorCommand command) {
        platform.runDetached(command);
    }

    @Override
    public CompletableFuture<Void> stopAll() {
        return wrap(platform.stopAll());
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

    <T> CompletableFuture<T> wrap(CompletableFuture<T> inner) {
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
        // Cancelling what the program holds (an interrupted or timed-out wait) ends the command: the
        // platform's cycle brakes its motors.
        return Futures.cancelling(f, inner);
    }
}
