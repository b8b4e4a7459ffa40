package io.robomw.sim;

import io.robomw.api.Pose;
import io.robomw.config.description.Body;
import io.robomw.config.description.DifferentialDrive;
import io.robomw.config.description.RobotDescription;
import io.robomw.config.description.SensorSpec;
import io.robomw.config.kinematics.DifferentialKinematics;
import io.robomw.sim.lockstep.SimFuture;
import org.dyn4j.dynamics.contact.ContactConstraint;
import org.dyn4j.dynamics.contact.SolvedContact;
import org.dyn4j.geometry.Vector2;

import java.util.ArrayList;
import java.util.HashMap;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Map;
import java.util.Queue;
import java.util.concurrent.ConcurrentLinkedQueue;

/**
 * One robot's body in the simulated world: a dyn4j rigid body driven as a differential drive, its
 * motors' encoders computed from how the body actually moved, and its sensors.
 *
 * <p>Driving: the two wheel speeds commanded through the Platform Layer, limited to the
 * description's {@code max_speed}, set the body's forward and angular velocity before each step;
 * dyn4j then resolves collisions (with the description's mass and friction), so a robot that
 * drives into a wall stops at it. Encoders follow the body's real motion (wheels do not slip), so
 * a blocked robot's encoders stand still, as a stalled motor's do.
 *
 * <p>Touched only by the simulation thread, except {@link #pose()} and the trajectory, which
 * viewers read.
 */
public final class SimRobot {

    private final int index;
    private final String name;
    private final RobotDescription description;
    private final org.dyn4j.dynamics.Body body;
    private final DifferentialKinematics kinematics;
    private final Map<String, Integer> portIndex = new HashMap<>();
    private final double[] commanded;
    private final double[] motorDegrees;
    private final int leftIndex;
    private final int rightIndex;
    private final int[] actuatorIndex;
    private final Map<String, SensorModel> sensors = new LinkedHashMap<>();
    private final List<SensorModel> rangeSensors = new ArrayList<>();
    private final Queue<PendingRead> reads = new ConcurrentLinkedQueue<>();
    private final Trajectory trajectory = new Trajectory();
    private final boolean hasTouch;
    private double lastX;
    private double lastY;
    private double lastHeading;
    private double turned;
    private int contactSides;
    private volatile Pose pose;

    /** A read waiting for the robot's next cycle. */
    private record PendingRead(SensorModel sensor, SimFuture<Double> future) {
    }

    SimRobot(int index, String name, RobotDescription description, org.dyn4j.dynamics.Body body, long seed) {
        this.index = index;
        this.name = name;
        this.description = description;
        this.body = body;
        this.kinematics = description.drive().map(DifferentialKinematics::new).orElse(null);
        List<String> ports = description.motorPorts();
        for (int p = 0; p < ports.size(); p++) {
            portIndex.put(ports.get(p), p);
        }
        commanded = new double[ports.size()];
        motorDegrees = new double[ports.size()];
        leftIndex = description.drive().map(d -> portIndex.get(d.left().port())).orElse(-1);
        rightIndex = description.drive().map(d -> portIndex.get(d.right().port())).orElse(-1);
        actuatorIndex = description.actuators().stream().mapToInt(a -> portIndex.get(a.port())).toArray();
        int i = 0;
        boolean touch = false;
        for (SensorSpec s : description.sensors()) {
            SensorModel m = new SensorModel(s, description.body(), seed * 0x9E3779B97F4A7C15L + index * 1_000_003L + i++);
            sensors.put(s.name(), m);
            if (m.kind() == SensorModel.Kind.RANGE) {
                rangeSensors.add(m);
            }
            touch |= m.kind() == SensorModel.Kind.CONTACT;
        }
        this.hasTouch = touch;
        readPose();
        lastX = body.getTransform().getTranslationX();
        lastY = body.getTransform().getTranslationY();
        lastHeading = pose.heading();
        trajectory.add(lastX, lastY);
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

    /** @return where it is now (true pose, not odometry) */
    public Pose pose() {
        return pose;
    }

    /** @return the path it has driven, sampled */
    public Trajectory trajectory() {
        return trajectory;
    }

    /** @return its sensors' models, by name */
    public Map<String, SensorModel> sensors() {
        return sensors;
    }

    /** @return its range sensors */
    public List<SensorModel> rangeSensors() {
        return rangeSensors;
    }

    org.dyn4j.dynamics.Body body() {
        return body;
    }

    // ---- motors, as the sim motor platform drives them ----

    /**
     * @param port             a motor port
     * @param degreesPerSecond the commanded motor speed
     */
    void command(String port, double degreesPerSecond) {
        Integer i = portIndex.get(port);
        if (i == null) {
            throw new IllegalArgumentException("simulated robot '" + name + "' has no motor on port " + port);
        }
        commanded[i] = degreesPerSecond;
    }

    /**
     * @param port a motor port
     * @return its encoder, degrees
     */
    double motorDegrees(String port) {
        Integer i = portIndex.get(port);
        return i == null ? 0.0 : motorDegrees[i];
    }

    /** Sets the body's velocities from the commanded wheel speeds. */
    void applyDrive() {
        if (kinematics == null) {
            return;
        }
        DifferentialDrive d = kinematics.drive();
        double max = d.maxSpeed();
        double vl = clamp(kinematics.wheelMetres(commanded[leftIndex], d.left().reversed()), max);
        double vr = clamp(kinematics.wheelMetres(commanded[rightIndex], d.right().reversed()), max);
        double v = (vl + vr) / 2;
        double w = (vr - vl) / d.trackWidth();
        if (v == 0 && w == 0 && body.isAtRest()) {
            return;
        }
        org.dyn4j.geometry.Transform t = body.getTransform();
        body.setLinearVelocity(v * t.getCost(), v * t.getSint());
        body.setAngularVelocity(w);
        if (v != 0 || w != 0) {
            body.setAtRest(false);
        }
    }

    private static double clamp(double v, double max) {
        return Math.max(-max, Math.min(max, v));
    }

    /**
     * After a physics step: encoders from the actual motion, contacts, trajectory.
     *
     * @param world the physics world (for contacts)
     * @param dt    the step, seconds
     * @param recordTrajectory whether to add the pose to the trajectory this step
     */
    void afterStep(org.dyn4j.world.World<org.dyn4j.dynamics.Body> world, double dt, boolean recordTrajectory) {
        if (body.isAtRest() && !hasTouch) {
            if (recordTrajectory) {
                trajectory.add(lastX, lastY);
            }
            return;
        }
        readPose();
        double x = pose.x();
        double y = pose.y();
        double heading = pose.heading();
        double dTheta = Pose.normalize(heading - lastHeading);
        turned += dTheta;
        if (kinematics != null) {
            DifferentialDrive d = kinematics.drive();
            double mid = lastHeading + dTheta / 2;
            double ds = (x - lastX) * Math.cos(mid) + (y - lastY) * Math.sin(mid);
            double left = ds - dTheta * d.trackWidth() / 2;
            double right = ds + dTheta * d.trackWidth() / 2;
            double dpm = kinematics.motorDegreesPerMetre();
            motorDegrees[leftIndex] += (d.left().reversed() ? -left : left) * dpm;
            motorDegrees[rightIndex] += (d.right().reversed() ? -right : right) * dpm;
        }
        for (int a : actuatorIndex) {
            motorDegrees[a] += commanded[a] * dt;
        }
        lastX = x;
        lastY = y;
        lastHeading = heading;
        if (hasTouch) {
            contactSides = contacts(world);
        }
        if (recordTrajectory) {
            trajectory.add(x, y);
        }
    }

    private void readPose() {
        org.dyn4j.geometry.Transform t = body.getTransform();
        pose = new Pose(t.getTranslationX(), t.getTranslationY(), Math.atan2(t.getSint(), t.getCost()));
    }

    private static final int FRONT = 1;
    private static final int BACK = 2;
    private static final int LEFT = 4;
    private static final int RIGHT = 8;

    /** @return a bit set of the sides of the body touching something */
    private int contacts(org.dyn4j.world.World<org.dyn4j.dynamics.Body> world) {
        int sides = 0;
        Body b = description.body();
        for (ContactConstraint<org.dyn4j.dynamics.Body> c : world.getContacts(body)) {
            if (!c.isEnabled() || c.isSensor()) {
                continue;
            }
            for (SolvedContact contact : c.getContacts()) {
                Vector2 local = body.getTransform().getInverseTransformed(contact.getPoint());
                sides |= local.x >= b.length() / 4 ? FRONT : 0;
                sides |= local.x <= -b.length() / 4 ? BACK : 0;
                sides |= local.y >= b.width() / 4 ? LEFT : 0;
                sides |= local.y <= -b.width() / 4 ? RIGHT : 0;
            }
        }
        return sides;
    }

    // ---- sensors ----

    /**
     * Queues a read, completed at the robot's next cycle (a brick takes a round trip too).
     *
     * @param sensor the sensor
     * @param future completed with the raw value
     */
    void requestRead(SensorModel sensor, SimFuture<Double> future) {
        reads.add(new PendingRead(sensor, future));
    }

    /**
     * Completes queued reads with the current values.
     *
     * @param world the world, for floor patches
     */
    void completeReads(SimWorld world) {
        for (PendingRead r; (r = reads.poll()) != null; ) {
            SimFuture<Double> f = r.future();
            try {
                double raw = r.sensor().spec().conversion().invert(siValue(r.sensor(), world));
                world.lockstep().defer(() -> f.complete(raw));
            } catch (RuntimeException e) {
                world.lockstep().defer(() -> f.completeExceptionally(e));
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
            case RANGE -> sensor.latest();
            case CONTACT -> touching(sensor) ? 1.0 : 0.0;
            case FLOOR -> world.floorAt(sensorX(sensor), sensorY(sensor), sensor.spec().type() == io.robomw.api.SensorType.COLOR);
            case HEADING -> pose.heading();
            case TURNED -> turned;
            case SILENCE -> 0.0;
            case TACHO -> Math.toRadians(motorDegrees(sensor.spec().port()));
        };
    }

    private boolean touching(SensorModel sensor) {
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
        return pose.x() + s.mountX() * Math.cos(pose.heading()) - s.mountY() * Math.sin(pose.heading());
    }

    private double sensorY(SensorModel s) {
        return pose.y() + s.mountX() * Math.sin(pose.heading()) + s.mountY() * Math.cos(pose.heading());
    }
}
