package io.robomw.agents;

import io.robomw.api.Agency;
import io.robomw.api.Capability;
import io.robomw.api.Messaging;
import io.robomw.api.Pose;
import io.robomw.api.Position;
import io.robomw.api.ReturnType;
import io.robomw.api.Robot;
import io.robomw.api.RobotLinkException;
import io.robomw.api.SensorInfo;
import io.robomw.api.SensorType;
import io.robomw.api.UnsupportedActionException;

import java.util.List;
import java.util.Set;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.CopyOnWriteArrayList;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.TimeUnit;

/** A test robot whose motions end only when the test completes them, or when they are cancelled; it counts its stops. */
public final class HeldRobot implements Robot {
    public final List<CompletableFuture<Void>> moves = new CopyOnWriteArrayList<>();
    public final List<CompletableFuture<Void>> turns = new CopyOnWriteArrayList<>();
    public final java.util.concurrent.atomic.AtomicInteger stops = new java.util.concurrent.atomic.AtomicInteger();
    public final CountDownLatch stopEntered = new CountDownLatch(1);
    private volatile CountDownLatch stopRelease;
    private volatile boolean failStops;

    public void holdStops() {
        stopRelease = new CountDownLatch(1);
    }

    public void releaseStops() {
        stopRelease.countDown();
    }

    public void failStops() {
        failStops = true;
    }

    @Override
    public String name() {
        return "held";
    }

    @Override
    public Set<Capability> capabilities() {
        return Set.of(Capability.GROUND);
    }

    @Override
    public List<SensorInfo> sensors() {
        return List.of();
    }

    @Override
    public List<String> actions() {
        return List.of();
    }

    @Override
    public Messaging messaging() {
        throw new UnsupportedActionException("held", "messaging", "a test robot");
    }

    @Override
    public Agency agency() {
        throw new UnsupportedActionException("held", "agency", "a test robot");
    }

    @Override
    public CompletableFuture<Void> moveAsync(double distance, double speed) {
        CompletableFuture<Void> f = new CompletableFuture<>();
        moves.add(f);
        return f;
    }

    @Override
    public CompletableFuture<Void> turnAsync(double radians, double speed) {
        CompletableFuture<Void> f = new CompletableFuture<>();
        turns.add(f);
        return f;
    }

    @Override
    public CompletableFuture<Void> arcAsync(double radius, double angle, double speed) {
        return new CompletableFuture<>();
    }

    @Override
    public void drive(double linearSpeed, double angularSpeed) {
    }

    @Override
    public void stop() {
        stopEntered.countDown();
        CountDownLatch release = stopRelease;
        if (release != null) {
            try {
                if (!release.await(30, TimeUnit.SECONDS)) {
                    throw new IllegalStateException("the test never released the stop");
                }
            } catch (InterruptedException e) {
                Thread.currentThread().interrupt();
            }
        }
        if (failStops) {
            throw new RobotLinkException("robot 'held': the stop could not be handed to its link: the link is down", null);
        }
        stops.incrementAndGet();
    }

    @Override
    public CompletableFuture<Void> changeAltitudeAsync(double metres, double speed) {
        return CompletableFuture.failedFuture(new UnsupportedActionException("held", "changeAltitude", "it is a ground robot"));
    }

    @Override
    public CompletableFuture<Void> performAsync(String action, double... args) {
        return CompletableFuture.failedFuture(new UnsupportedActionException("held", action, "it has no actions"));
    }

    @Override
    public CompletableFuture<Double> getValueAsync(Position position, SensorType type, ReturnType returnType) {
        return CompletableFuture.failedFuture(new UnsupportedActionException("held", "getValue", "it has no sensors"));
    }

    @Override
    public CompletableFuture<Double> getValueAsync(String sensorName, ReturnType returnType) {
        return CompletableFuture.failedFuture(new UnsupportedActionException("held", "getValue", "it has no sensors"));
    }

    @Override
    public Pose pose() {
        return new Pose(0, 0, 0);
    }

    @Override
    public void resetPose(Pose pose) {
    }

    @Override
    public void close() {
    }
}
