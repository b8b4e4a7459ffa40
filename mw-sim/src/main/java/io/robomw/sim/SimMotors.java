package io.robomw.sim;

import io.robomw.platform.sensor.Sensor;
import io.robomw.sim.lockstep.SimFuture;

import java.util.Optional;
import java.util.concurrent.CompletableFuture;

/**
 * The hardware face of a simulated robot, for the simulator's platform (and for brick emulators):
 * motor speeds in, encoders and sensor readings out. Every method is for the simulation thread,
 * except {@link #sensor}'s reads, which may be requested from any thread and are answered at the
 * robot's next cycle.
 */
public final class SimMotors {

    private final SimWorld world;
    private final SimRobot robot;

    private SimMotors(SimWorld world, SimRobot robot) {
        this.world = world;
        this.robot = robot;
    }

    /**
     * @param world a world
     * @param name  a robot's name
     * @return its hardware face, if the world has such a robot
     */
    public static Optional<SimMotors> of(SimWorld world, String name) {
        return Optional.ofNullable(world.robot(name)).map(r -> new SimMotors(world, r));
    }

    /** @return the robot */
    public SimRobot robot() {
        return robot;
    }

    /**
     * @param port             a motor port
     * @param degreesPerSecond its commanded speed
     */
    public void command(String port, double degreesPerSecond) {
        robot.command(port, degreesPerSecond);
    }

    /**
     * @param port a motor port
     * @return its encoder, degrees
     */
    public double degrees(String port) {
        return robot.motorDegrees(port);
    }

    /**
     * @param port a motor port
     * @return its index for {@link #degrees(int)}, or -1 if the robot has no motor there
     */
    public int portIndex(String port) {
        return robot.motorPortIndex(port);
    }

    /**
     * @param portIndex a motor's index ({@link #portIndex})
     * @return its encoder, degrees
     */
    public double degrees(int portIndex) {
        return robot.motorDegrees(portIndex);
    }

    /**
     * The true value of a sensor now, in its quantity's SI unit (metres, radians, 0..1, 1/0), for
     * brick emulators, which encode it the way their firmware reports it. Simulation thread only.
     *
     * @param name a sensor's name
     * @return its value
     * @throws IllegalArgumentException if the robot has no such sensor
     */
    public double siValue(String name) {
        SensorModel model = robot.sensors().get(name);
        if (model == null) {
            throw new IllegalArgumentException("simulated robot '" + robot.name() + "' has no sensor '" + name + "'");
        }
        return robot.siValue(model, world);
    }

    /**
     * Reads a sensor by name, as {@link #sensor}'s reader would: answered at the robot's next cycle.
     * A robot's platform reads all its sensors through this one method (no reader a sensor a robot).
     *
     * @param name a sensor's name
     * @return completes with its raw value; {@code null} if the robot has no such sensor
     */
    public CompletableFuture<Double> readRaw(String name) {
        SensorModel model = robot.sensors().get(name);
        if (model == null) {
            return null;
        }
        SimFuture<Double> f = world.lockstep().newFuture();
        robot.requestRead(model, f);
        world.readQueued();
        return f;
    }

    /**
     * @param name a sensor's name
     * @return a reader of its raw values
     * @throws IllegalArgumentException if the robot has no such sensor
     */
    public Sensor sensor(String name) {
        SensorModel model = robot.sensors().get(name);
        if (model == null) {
            throw new IllegalArgumentException("simulated robot '" + robot.name() + "' has no sensor '" + name + "'");
        }
        return () -> {
            SimFuture<Double> f = world.lockstep().newFuture();
            robot.requestRead(model, f);
            world.readQueued();
            return f;
        };
    }
}
