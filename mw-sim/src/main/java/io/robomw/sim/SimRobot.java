package io.robomw.sim;

import io.robomw.api.Pose;
import io.robomw.config.description.Body;
import io.robomw.config.description.DifferentialDrive;
import io.robomw.config.description.RobotDescription;
import io.robomw.config.description.SensorSpec;
import io.robomw.config.kinematics.DifferentialKinematics;
import io.robomw.sim.legged.AiboDevices;
import io.robomw.sim.legged.Quadruped;
import io.robomw.sim.legged.UrbiKernel;
import io.robomw.sim.lockstep.SimFuture;
import io.robomw.sim.physics.Physics;

import java.util.ArrayList;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Map;
import java.util.OptionalDouble;
import java.util.Queue;
import java.util.concurrent.ConcurrentLinkedQueue;

/**
 * One robot's body in the simulated world: a rigid body of the world's {@link Physics} driven as a differential drive, its
 * motors' encoders computed from how the body actually moved, and its sensors.
 *
 * <p>Driving: the two wheel speeds commanded through the Platform Layer, limited to the
 * description's {@code max_speed}, set the body's forward and angular velocity before each step;
 * the physics then resolves collisions (with the description's mass and friction), so a robot that
 * drives into a wall stops at it. Encoders follow the body's real motion (wheels do not slip), so
 * a blocked robot's encoders stand still, as a stalled motor's do.
 *
 * <p>A robot whose description has a legged drive is a {@link Quadruped} instead: its gait sets
 * the body's velocities, and its URBI server core ({@link UrbiKernel}) answers the Aibo emulator's
 * clients and the simulator's own platform.
 *
 * <p>Every robot has an accelerometer's worth of motion: the body's acceleration in its own frame
 * (x forwards, y left, z up, gravity included) is computed after every step for the robots that
 * have an accelerometer or legs.
 *
 * <p>Touched only by the simulation thread, except {@link #pose()} and the trajectory, which
 * viewers read.
 */
public final class SimRobot {

    private final int index;
    private final String name;
    private final RobotDescription description;
    private final Physics physics;
    /** Its body's number in {@link #physics}. */
    private final int body;
    /** Where its contact points go, if it has a touch sensor or legs; else {@code null}. */
    private final Physics.ContactSink touchPoint;
    private int touchedSides;
    private int touchedQuadrants;
    /** What every robot of its robot file shares: kinematics, motor ports, sensor models. */
    private final RobotModel model;
    private final DifferentialKinematics kinematics;
    /** Its actuators' commanded speeds and encoders, by motor port index (the drive's two motors are in the world's arrays). */
    private final double[] commanded;
    private final double[] motorDegrees;
    private final int leftIndex;
    private final int rightIndex;
    private final int[] actuatorIndex;
    /** Per range sensor (by its place among them): the generator of its noise, if any sensor is noisy; else {@code null}. */
    private final java.util.SplittableRandom[] noise;
    /** Reads waiting for the next cycle, made at the first read. */
    private volatile Queue<PendingRead> reads;
    /** Set after a read is queued, cleared before the queue is drained: a cycle without reads looks no further. */
    private volatile boolean readsPending;
    private final Trajectory trajectory;
    private final boolean hasTouch;
    private final boolean hasAccel;
    private final Quadruped quadruped;
    private final UrbiKernel kernel;
    /** Its dynamics, if it is a vehicle (a drone, boat or rover); else {@code null}. */
    private final io.robomw.sim.vehicle.SimVehicle vehicle;
    private final io.robomw.sim.world.WorldDescription.Surroundings surroundings;
    private double lastVx;
    private double lastVy;
    /** Its acceleration in its own frame, if it has an accelerometer or legs; else {@code null}. */
    private final double[] accel;
    private int contactQuadrants;
    private int contactSides;
    // The true pose, the angle turned and the drive motors' encoders and speeds live in the world's
    // arrays (RobotStates, at this robot's index), not in fields: a step then touches no object of a
    // plain robot at all, and stores no reference into this long-lived one (each such store costs G1
    // a card to refine). Other threads read the pose through its sequence lock there, in pose().
    private final RobotStates states;

    /** A read waiting for the robot's next cycle. */
    private record PendingRead(SensorModel sensor, SimFuture<Double> future) {
    }

    SimRobot(int index, String name, RobotDescription description, Physics physics, int body, long seed,
             java.util.function.LongSupplier nanos, io.robomw.sim.world.WorldDescription.TrajectorySettings trajectorySettings,
             io.robomw.api.spi.FailurePolicy failures, RobotStates states, RobotModel model,
             io.robomw.sim.world.WorldDescription.Surroundings surroundings) {
        this.surroundings = surroundings;
        this.index = index;
        this.model = model;
        this.states = states;
        this.trajectory = new Trajectory(trajectorySettings);
        this.name = name;
        this.description = description;
        this.physics = physics;
        this.body = body;
        this.kinematics = model.kinematics;
        boolean actuators = model.actuatorIndex.length > 0;
        commanded = actuators ? new double[model.ports.length] : NO_MOTORS;
        motorDegrees = actuators ? new double[model.ports.length] : NO_MOTORS;
        leftIndex = model.leftIndex;
        rightIndex = model.rightIndex;
        actuatorIndex = model.actuatorIndex;
        if (model.noisy) {
            noise = new java.util.SplittableRandom[model.rangeSensors.size()];
            for (int i = 0; i < model.sensors.size(); i++) {
                SensorModel m = model.sensors.get(i);
                if (m.rangeIndex() >= 0 && m.noisy()) {
                    noise[m.rangeIndex()] = new java.util.SplittableRandom(seed * 0x9E3779B97F4A7C15L + index * 1_000_003L + i);
                }
            }
        } else {
            noise = null;
        }
        this.hasTouch = model.hasTouch;
        this.hasAccel = model.hasAccel;
        this.quadruped = description.leggedDrive().map(d -> new Quadruped(d, seed * 0x9E3779B97F4A7C15L + index * 7_919L + 17)).orElse(null);
        this.touchPoint = hasTouch || quadruped != null ? this::touchPoint : null;
        this.accel = hasAccel || quadruped != null ? new double[] {0, 0, Quadruped.GRAVITY} : null;
        this.kernel = quadruped == null ? null : new UrbiKernel(name, quadruped, this::urbiSensor, nanos, failures);
        states.add(index, model.rangeSensors.size());
        states.body[index] = body;
        states.trajectory[index] = trajectory;
        if (kinematics != null) {
            DifferentialDrive d = kinematics.drive();
            states.track[index] = d.trackWidth();
            states.degreesPerMetre[index] = kinematics.motorDegreesPerMetre();
            states.signLeft[index] = d.left().reversed() ? -1 : 1;
            states.signRight[index] = d.right().reversed() ? -1 : 1;
            states.maxSpeed[index] = d.maxSpeed();
            states.command(index, 0, 0);
        }
        this.vehicle = description.vehicleDrive().map(d -> new io.robomw.sim.vehicle.SimVehicle(
                io.robomw.sim.vehicle.VehicleSpec.of(d, description.body()), physics.x(body), physics.y(body), physics.heading(body))).orElse(null);
        states.model[index] = model;
        states.plain[index] = kinematics != null && quadruped == null && vehicle == null && !hasTouch && !hasAccel && actuatorIndex.length == 0;
        states.setPose(index, physics.x(body), physics.y(body), physics.heading(body), physics.cos(body), physics.sin(body));
        trajectory.add(physics.x(body), physics.y(body));
    }

    /** @return what the robots of its robot file share */
    RobotModel model() {
        return model;
    }

    /** @return whether the world steps this robot from its arrays alone ({@link RobotStates}) */
    boolean plain() {
        return states.plain[index];
    }

    /** @return its vehicle dynamics, if it is a vehicle (a drone, boat or rover); else {@code null} */
    public io.robomw.sim.vehicle.SimVehicle vehicle() {
        return vehicle;
    }

    /** @return its index in the world */
    public int index() {
        return index;
    }

    /** @return its name in the world */
    public String name() {
        return name;
    }

    /** @return its description */
    public RobotDescription description() {
        return description;
    }

    /**
     * Where it is now. Any thread may call it: a viewer gets the pose after some whole step, never
     * parts of two.
     *
     * @return where it is now (true pose, not odometry)
     */
    public Pose pose() {
        return states.pose(index);
    }

    /** @return its true x now; the world's threads only (others: {@link #pose()}) */
    double x() {
        return states.x[index];
    }

    /** @return its true y now; the world's threads only */
    double y() {
        return states.y[index];
    }

    /** @return its true heading now, in (-π, π]; the world's threads only */
    double heading() {
        return states.heading[index];
    }

    /** @return the cosine of its heading now, as its body's physics gives it; the world's threads only */
    double cosHeading() {
        return states.cos[index];
    }

    /** @return the sine of its heading now; the world's threads only */
    double sinHeading() {
        return states.sin[index];
    }

    /** @return the path it has driven, sampled as the world's {@code trajectory} settings say (bounded) */
    public Trajectory trajectory() {
        return trajectory;
    }

    /** @return its sensors' models, by name (shared by every robot of its robot file) */
    public Map<String, SensorModel> sensors() {
        return model.byName;
    }

    /** @return its range sensors' models (shared by every robot of its robot file), in the order of {@link SensorModel#rangeIndex()} */
    public List<SensorModel> rangeSensors() {
        return model.rangeSensors;
    }

    /**
     * Any thread (a viewer gets the sample of some step).
     *
     * @param sensor one of its range sensors
     * @return its last sample, metres
     */
    public double latest(SensorModel sensor) {
        return states.range(index, sensor.rangeIndex());
    }

    /** @return the generator of a range sensor's noise (by its place among them), or {@code null} */
    java.util.SplittableRandom noise(int rangeIndex) {
        return noise == null ? null : noise[rangeIndex];
    }

    /** @return its body's number in the world's physics */
    int body() {
        return body;
    }

    /** @return its gait and joints, if it is a legged robot; else {@code null} */
    public Quadruped quadruped() {
        return quadruped;
    }

    /** @return its URBI server core, if it is a legged robot; else {@code null} */
    public UrbiKernel kernel() {
        return kernel;
    }

    // ---- motors, as the sim motor platform drives them ----

    /**
     * @param port             a motor port
     * @param degreesPerSecond the commanded motor speed
     */
    void command(String port, double degreesPerSecond) {
        int i = portIndex(port);
        if (i < 0) {
            throw new IllegalArgumentException("simulated robot '" + name + "' has no motor on port " + port);
        }
        command(i, degreesPerSecond);
    }

    /**
     * @param portIndex        a motor's index ({@link #motorPortIndex})
     * @param degreesPerSecond the commanded motor speed
     */
    void command(int portIndex, double degreesPerSecond) {
        if (portIndex == leftIndex) {
            states.command(index, degreesPerSecond, states.commandRight[index]);
        } else if (portIndex == rightIndex) {
            states.command(index, states.commandLeft[index], degreesPerSecond);
        } else {
            commanded[portIndex] = degreesPerSecond;
        }
    }

    /** @return a motor's commanded speed, degrees per second */
    private double commanded(int portIndex) {
        return portIndex == leftIndex ? states.commandLeft[index] : portIndex == rightIndex ? states.commandRight[index] : commanded[portIndex];
    }

    /**
     * @param port a motor port
     * @return its encoder, degrees
     */
    double motorDegrees(String port) {
        int i = portIndex(port);
        return i < 0 ? 0.0 : motorDegrees(i);
    }

    /**
     * @param portIndex a motor's index ({@link #motorPortIndex})
     * @return its encoder, degrees
     */
    double motorDegrees(int portIndex) {
        return portIndex == leftIndex ? states.encoderLeft[index] : portIndex == rightIndex ? states.encoderRight[index] : motorDegrees[portIndex];
    }

    /** @return a motor port's index, or -1 */
    int motorPortIndex(String port) {
        return portIndex(port);
    }

    /** @return a motor port's index, or -1 */
    private int portIndex(String port) {
        return model.portIndex(port);
    }

    private static final double[] NO_MOTORS = new double[0];

    /**
     * Sets every motor to rest and the body's velocities to match, when the world halts (its
     * stepping thread died): what no end action could stop is stopped here.
     */
    void halt() {
        java.util.Arrays.fill(commanded, 0);
        if (kinematics != null) {
            states.command(index, 0, 0);
        }
        if (quadruped != null) {
            quadruped.stop();
        }
        applyDrive();
    }

    /** Sets the body's velocities from the commanded wheel speeds. */
    void applyDrive() {
        double v;
        double w;
        if (vehicle != null) {
            physics.setVelocity(body, vehicle.commandX(), vehicle.commandY(), vehicle.commandYawRate());
            return;
        }
        if (quadruped != null) {
            v = quadruped.linearVelocity();
            w = quadruped.angularVelocity();
        } else if (kinematics != null) {
            states.drive(index, physics);
            return;
        } else {
            return;
        }
        physics.drive(body, v, w);
    }

    /**
     * After a physics step: encoders from the actual motion, contacts, trajectory.
     *
     * @param dt    the step, seconds
     * @param recordTrajectory whether to add the pose to the trajectory this step
     */
    void afterStep(double dt, boolean recordTrajectory) {
        if (hasAccel || quadruped != null) {
            accelerate(dt);
        }
        if (quadruped != null) {
            quadruped.advance(dt);
            contacts();
            kernel.step();
        }
        if (vehicle != null) {
            vehicle.advance(dt, physics.x(body), physics.y(body), Math.atan2(physics.sin(body), physics.cos(body)), physics.vx(body),
                    physics.vy(body), surroundings);
        }
        if (physics.atRest(body) && !hasTouch) {
            if (recordTrajectory) {
                trajectory.add(states.x[index], states.y[index]);
            }
            return;
        }
        states.advance(index, physics, kinematics != null);
        for (int a : actuatorIndex) {
            motorDegrees[a] += commanded[a] * dt;
        }
        if (hasTouch) {
            contactSides = contacts();
        }
        if (recordTrajectory) {
            trajectory.add(states.x[index], states.y[index]);
        }
    }

    /** The body's acceleration in its own frame since the last step, gravity and gait included. */
    private void accelerate(double dt) {
        double vx = physics.vx(body);
        double vy = physics.vy(body);
        double h = Math.atan2(physics.sin(body), physics.cos(body));
        double ax = (vx - lastVx) / dt;
        double ay = (vy - lastVy) / dt;
        lastVx = vx;
        lastVy = vy;
        double pitch = quadruped == null ? 0 : quadruped.pitch();
        double bounce = quadruped == null ? 0 : quadruped.bounce();
        accel[0] = ax * Math.cos(h) + ay * Math.sin(h) + Quadruped.GRAVITY * Math.sin(pitch);
        accel[1] = -ax * Math.sin(h) + ay * Math.cos(h);
        accel[2] = Quadruped.GRAVITY * Math.cos(pitch) + bounce;
    }

    /**
     * A device of the dog's URBI server that is a sensor, in the device's own unit.
     *
     * @param device the device's name
     * @return its value, or empty if the dog has no such sensor device
     */
    private OptionalDouble urbiSensor(String device) {
        switch (device) {
            case "accelX" -> {
                return OptionalDouble.of(accel[0]);
            }
            case "accelY" -> {
                return OptionalDouble.of(accel[1]);
            }
            case "accelZ" -> {
                return OptionalDouble.of(accel[2]);
            }
            case "pawLF" -> {
                return OptionalDouble.of((contactQuadrants & FRONT_LEFT_QUADRANT) != 0 ? 1 : 0);
            }
            case "pawRF" -> {
                return OptionalDouble.of((contactQuadrants & FRONT_RIGHT_QUADRANT) != 0 ? 1 : 0);
            }
            case "pawLH" -> {
                return OptionalDouble.of((contactQuadrants & BACK_LEFT_QUADRANT) != 0 ? 1 : 0);
            }
            case "pawRH" -> {
                return OptionalDouble.of((contactQuadrants & BACK_RIGHT_QUADRANT) != 0 ? 1 : 0);
            }
            default -> {
            }
        }
        Double max = AiboDevices.DISTANCE_MAX_MM.get(device);
        if (max != null) {
            for (SensorModel m : model.rangeSensors) {
                if (m.spec().port().equals(device)) {
                    return OptionalDouble.of(Math.min(max, latest(m) * 1000));
                }
            }
            return OptionalDouble.of(max);
        }
        return AiboDevices.SENSORS.contains(device) ? OptionalDouble.of(0) : OptionalDouble.empty();
    }

    /** @return the head's pan, radians, positive left (0 for a robot without a head) */
    double headPan() {
        Quadruped.Joint j = quadruped == null ? null : quadruped.joint("headPan");
        return j == null ? 0 : Math.toRadians(j.angle());
    }

    /** @return the head's tilt, radians, positive up: the neck's and the head's together */
    double headTilt() {
        if (quadruped == null) {
            return 0;
        }
        return Math.toRadians(quadruped.joint("neck").angle() + quadruped.joint("headTilt").angle());
    }

    private static final int FRONT = 1;
    private static final int BACK = 2;
    private static final int LEFT = 4;
    private static final int RIGHT = 8;
    private static final int FRONT_LEFT_QUADRANT = 1;
    private static final int FRONT_RIGHT_QUADRANT = 2;
    private static final int BACK_LEFT_QUADRANT = 4;
    private static final int BACK_RIGHT_QUADRANT = 8;

    /** @return a bit set of the sides of the body touching something */
    private int contacts() {
        touchedSides = 0;
        touchedQuadrants = 0;
        physics.contacts(body, touchPoint);
        contactQuadrants = touchedQuadrants;
        return touchedSides;
    }

    /** One contact point, in the body's frame: which sides and quadrant it is on. */
    private void touchPoint(double x, double y) {
        Body b = description.body();
        touchedSides |= x >= b.length() / 4 ? FRONT : 0;
        touchedSides |= x <= -b.length() / 4 ? BACK : 0;
        touchedSides |= y >= b.width() / 4 ? LEFT : 0;
        touchedSides |= y <= -b.width() / 4 ? RIGHT : 0;
        touchedQuadrants |= x >= 0 ? (y >= 0 ? FRONT_LEFT_QUADRANT : FRONT_RIGHT_QUADRANT)
                : (y >= 0 ? BACK_LEFT_QUADRANT : BACK_RIGHT_QUADRANT);
    }

    // ---- sensors ----

    /**
     * Queues a read, completed at the robot's next cycle (a brick takes a round trip too).
     *
     * @param sensor the sensor
     * @param future completed with the raw value
     */
    void requestRead(SensorModel sensor, SimFuture<Double> future) {
        Queue<PendingRead> q = reads;
        if (q == null) {
            READS.compareAndSet(this, null, new ConcurrentLinkedQueue<PendingRead>());
            q = reads;
        }
        q.add(new PendingRead(sensor, future));
        readsPending = true;
    }

    private static final java.lang.invoke.VarHandle READS;

    static {
        try {
            READS = java.lang.invoke.MethodHandles.lookup().findVarHandle(SimRobot.class, "reads", Queue.class);
        } catch (ReflectiveOperationException e) {
            throw new ExceptionInInitializerError(e);
        }
    }

    /**
     * Completes queued reads with the current values.
     *
     * @param world the world, for floor patches
     */
    void completeReads(SimWorld world) {
        if (!readsPending) {
            return;
        }
        readsPending = false;
        for (PendingRead r; (r = reads.poll()) != null; ) {
            SimFuture<Double> f = r.future();
            try {
                double si = siValue(r.sensor(), world);
                SensorModel.Kind kind = r.sensor().kind();
                double raw = r.sensor().spec().conversion().invert(kind == SensorModel.Kind.JOINT || kind == SensorModel.Kind.TACHO
                        ? Math.toDegrees(si) : si);
                world.lockstep().defer(() -> f.complete(raw));
            } catch (Throwable e) {
                if (!io.robomw.api.spi.FailurePolicy.survivable(e)) {
                    throw e; // no thread survives it: the world's thread dies of it, and halts the world
                }
                world.lockstep().defer(() -> f.completeExceptionally(e)); // the read's failure is its reader's
            }
        }
    }

    /**
     * @param sensor one of its sensors
     * @param world  the world
     * @return the true value in the quantity's SI unit
     */
    double siValue(SensorModel sensor, SimWorld world) {
        return switch (sensor.kind()) {
            case RANGE -> vehicle != null && sensor.spec().position() == io.robomw.api.Position.BOTTOM
                    ? Math.min(sensor.maxRange(), vehicle.snapshot().z()) : latest(sensor);
            case CONTACT -> touching(sensor) ? 1.0 : 0.0;
            case FLOOR -> world.floorAt(sensorX(sensor), sensorY(sensor), sensor.spec().type() == io.robomw.api.SensorType.COLOR);
            case HEADING -> states.heading[index];
            case TURNED -> states.turned[index];
            case SILENCE -> 0.0;
            case TACHO -> Math.toRadians(motorDegrees(sensor.spec().port()));
            case ACCELERATION -> accel[switch (sensor.axis()) {
                case 'y' -> 1;
                case 'z' -> 2;
                default -> 0;
            }];
            case JOINT -> {
                Quadruped.Joint j = quadruped == null ? null : quadruped.joint(sensor.spec().port());
                yield j == null ? 0.0 : Math.toRadians(j.angle());
            }
            case VEHICLE -> vehicleValue(sensor.spec().type(), world);
        };
    }

    /** A vehicle's reported quantity, in SI: altitude m, battery 0..1, latitude and longitude in radians. */
    private double vehicleValue(io.robomw.api.SensorType type, SimWorld world) {
        if (vehicle == null) {
            return 0;
        }
        io.robomw.sim.vehicle.SimVehicle.Snapshot s = vehicle.snapshot();
        io.robomw.sim.world.WorldDescription.GeoOrigin home = world.description().surroundings().home();
        double radius = 6_378_137;
        return switch (type) {
            case ALTITUDE -> s.z();
            case BATTERY -> s.battery();
            case LATITUDE -> Math.toRadians(home.latitude()) + s.y() / radius;
            case LONGITUDE -> Math.toRadians(home.longitude()) + s.x() / (radius * Math.cos(Math.toRadians(home.latitude())));
            default -> 0;
        };
    }

    private boolean touching(SensorModel sensor) {
        if (quadruped != null) {
            int quadrant = switch (sensor.spec().position()) {
                case FRONT_LEFT -> FRONT_LEFT_QUADRANT;
                case FRONT_RIGHT -> FRONT_RIGHT_QUADRANT;
                case BACK_LEFT -> BACK_LEFT_QUADRANT;
                case BACK_RIGHT -> BACK_RIGHT_QUADRANT;
                default -> 0;
            };
            if (quadrant != 0) {
                return (contactQuadrants & quadrant) != 0;
            }
        }
        int mask = switch (sensor.spec().position()) {
            case FRONT -> FRONT;
            case BACK -> BACK;
            case LEFT -> LEFT;
            case RIGHT -> RIGHT;
            case FRONT_LEFT -> FRONT | LEFT;
            case FRONT_RIGHT -> FRONT | RIGHT;
            case BACK_LEFT -> BACK | LEFT;
            case BACK_RIGHT -> BACK | RIGHT;
            case TOP, BOTTOM, CENTER -> FRONT | BACK | LEFT | RIGHT;
        };
        return (contactSides & mask) != 0;
    }

    private double sensorX(SensorModel s) {
        double h = states.heading[index];
        return states.x[index] + s.mountX() * Math.cos(h) - s.mountY() * Math.sin(h);
    }

    private double sensorY(SensorModel s) {
        double h = states.heading[index];
        return states.y[index] + s.mountX() * Math.sin(h) + s.mountY() * Math.cos(h);
    }
}
