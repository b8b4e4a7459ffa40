package io.robomw.sim;

import io.robomw.api.spi.AgencyComponent;
import io.robomw.api.Capability;
import io.robomw.api.spi.MessagingComponent;
import io.robomw.api.Pose;
import io.robomw.api.Position;
import io.robomw.api.ReturnType;
import io.robomw.api.Robot;
import io.robomw.api.SensorInfo;
import io.robomw.api.SensorType;
import io.robomw.config.robot.ConfiguredRobot;

import java.util.List;
import java.util.Set;
import java.util.concurrent.CompletableFuture;

/**
 * A simulated robot that its world drives in a {@linkplain SimWorld#batchRobots() batch} until a
 * program or an agent addresses it one by one: its first verb (a motion, a stop, a sensor read,
 * its pose) {@linkplain SimWorld#promote promotes} it out of the batch, and from then on every
 * call goes to its own {@link ConfiguredRobot}, through its own execution action thread, exactly as
 * for a robot that was never batched. Its name, capabilities, sensors, actions, messaging and
 * agency are its own robot's and promote nothing. Thread-safe.
 */
final class BatchedRobot implements Robot {

    private final ConfiguredRobot robot;
    private final SimWorld world;
    private final int index;
    private volatile boolean promoted;

    BatchedRobot(ConfiguredRobot robot, SimWorld world, int index) {
        this.robot = robot;
        this.world = world;
        this.index = index;
    }

    /** @return its own robot, promoted out of its batch first */
    private ConfiguredRobot own() {
        if (!promoted) {
            if (Parallel.onWorker()) {
                // a controller in the world's pass: the promotion waits for the next step (see SimWorld.promote), and this
                // thread takes no lock a program promoting the robot may hold while it waits for the step to end
                world.promote(index, robot::resetPose);
                promoted = true;
            } else {
                synchronized (this) {
                    if (!promoted) {
                        // its own odometry goes on from the batch's estimate
                        world.promote(index, robot::resetPose);
                        promoted = true;
                    }
                }
            }
        }
        return robot;
    }

    /** @return its own robot, without promoting it */
    ConfiguredRobot configured() {
        return robot;
    }

    @Override
    public String name() {
        return robot.name();
    }

    @Override
    public Set<Capability> capabilities() {
        return robot.capabilities();
    }

    @Override
    public List<SensorInfo> sensors() {
        return robot.sensors();
    }

    @Override
    public List<String> actions() {
        return robot.actions();
    }

    @Override
    public MessagingComponent messaging() {
        return robot.messaging();
    }

    @Override
    public AgencyComponent agency() {
        return robot.agency();
    }

    @Override
    public CompletableFuture<Void> moveAsync(double distance, double speed) {
        return own().moveAsync(distance, speed);
    }

    @Override
    public CompletableFuture<Void> turnAsync(double radians, double speed) {
        return own().turnAsync(radians, speed);
    }

    @Override
    public CompletableFuture<Void> arcAsync(double radius, double angle, double speed) {
        return own().arcAsync(radius, angle, speed);
    }

    @Override
    public void drive(double linearSpeed, double angularSpeed) {
        own().drive(linearSpeed, angularSpeed);
    }

    @Override
    public CompletableFuture<Void> changeAltitudeAsync(double metres, double speed) {
        return own().changeAltitudeAsync(metres, speed);
    }

    @Override
    public CompletableFuture<Void> takeOffAsync(double altitude) {
        return own().takeOffAsync(altitude);
    }

    @Override
    public CompletableFuture<Void> landAsync() {
        return own().landAsync();
    }

    @Override
    public void stop() {
        own().stop();
    }

    @Override
    public CompletableFuture<Void> performAsync(String action, double... args) {
        return own().performAsync(action, args);
    }

    @Override
    public CompletableFuture<Double> getValueAsync(Position position, SensorType type, ReturnType returnType) {
        return own().getValueAsync(position, type, returnType);
    }

    @Override
    public CompletableFuture<Double> getValueAsync(String sensorName, ReturnType returnType) {
        return own().getValueAsync(sensorName, returnType);
    }

    @Override
    public Pose pose() {
        return own().pose();
    }

    @Override
    public void resetPose(Pose pose) {
        own().resetPose(pose);
    }

    @Override
    public void close() {
        robot.close();
    }

    @Override
    public String toString() {
        return robot.toString();
    }
}
