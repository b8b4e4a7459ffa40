package io.robomw.config.robot;

import io.robomw.api.Capability;
import io.robomw.api.Futures;
import io.robomw.api.Pose;
import io.robomw.api.Position;
import io.robomw.api.ReturnType;
import io.robomw.api.Robot;
import io.robomw.api.SensorInfo;
import io.robomw.api.SensorType;
import io.robomw.api.UnsupportedActionException;
import io.robomw.api.spi.AgencyComponent;
import io.robomw.api.spi.CommandPriority;
import io.robomw.api.spi.MessagingComponent;
import io.robomw.api.spi.RobotComponents;
import io.robomw.api.spi.MotorCommand;
import io.robomw.api.spi.MotorTarget;
import io.robomw.api.spi.RobotPlatform;
import io.robomw.config.description.ActuatorSpec;
import io.robomw.config.description.DifferentialDrive;
import io.robomw.config.description.RobotDescription;
import io.robomw.config.description.SensorSpec;
import io.robomw.config.kinematics.DifferentialKinematics;
import io.robomw.config.kinematics.Odometry;
import io.robomw.config.kinematics.WheelMotion;
import io.robomw.config.legged.LeggedControl;
import io.robomw.config.sensing.SensorConverter;

import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.Locale;
import java.util.Objects;
import java.util.Set;
import java.util.concurrent.CompletableFuture;
import java.util.function.Supplier;
import java.util.stream.Collectors;

/**
 * The Configuration Layer's robot: checks each instruction against the robot's description,
 * turns it into motor rotations or sensor reads with the description's geometry and conversions,
 * and hands it to the platform. Every call reads the description in force at that moment, so a
 * reload applies to the next command.
 *
 * <p>A robot whose description has a legged drive moves by its firmware's own commands instead
 * ({@link LeggedControl}, the paper's second Configuration Layer implementation): its motions,
 * its high-level actions and its pose go there.
 *
 * <p>The paper's four components are linked here: motion and perception go to the platform,
 * messaging and agents to the robot's communication component and agency, which the providers
 * found through the SPI open ({@link RobotComponents}: {@code mw-agents} provides both; without
 * it those calls throw {@link UnsupportedActionException} saying what to add). The robot closes
 * them with itself.
 *
 * <p>Thread-safe. Odometry is updated under a lock whenever a motion starts or ends, on
 * {@link #drive}, and on {@link #pose()}.
 */
public final class ConfiguredRobot implements Robot {

    private final Supplier<RobotDescription> description;
    private final RobotPlatform platform;
    private final MessagingComponent messaging;
    private final AgencyComponent agency;
    private final AutoCloseable onClose;
    private final Object odometryLock = new Object();
    private Odometry odometry;
    private DifferentialDrive odometryDrive;
    private volatile boolean closed;
    private volatile DifferentialKinematics kinematics;
    /** Whether the drive last asked about has encoders on both wheels. */
    private volatile Encoders encoders;
    /** What {@link #drive} needs of the description last in force. */
    private volatile DrivePlan drivePlan;
    private final LeggedControl legged;

    /**
     * @param description the description in force (read on every call)
     * @param platform    the opened platform
     * @param messaging   the communication component
     * @param agency      the agency
     * @param onClose     closed after the platform (a description watcher), or {@code null}
     */
    public ConfiguredRobot(Supplier<RobotDescription> description, RobotPlatform platform,
                           MessagingComponent messaging, AgencyComponent agency, AutoCloseable onClose) {
        this.description = description;
        this.platform = platform;
        this.messaging = Objects.requireNonNull(messaging, "messaging");
        this.agency = Objects.requireNonNull(agency, "agency");
        this.onClose = onClose;
        this.legged = new LeggedControl(description, platform);
    }

    /**
     * A robot with every component: its messaging and agency come from the providers on the class
     * path, set up as its description's {@code messaging:} and {@code agency:} sections say.
     *
     * @param description the description in force (read on every call; the sections are read now)
     * @param platform    the opened platform
     * @param onClose     closed after the platform, or {@code null}
     * @return the robot
     */
    public static ConfiguredRobot withComponents(Supplier<RobotDescription> description, RobotPlatform platform, AutoCloseable onClose) {
        RobotDescription d = description.get();
        MessagingComponent messaging = RobotComponents.messaging(d.name(), d.messaging());
        try {
            return new ConfiguredRobot(description, platform, messaging, RobotComponents.agency(d.name(), d.agency()), onClose);
        } catch (RuntimeException e) {
            messaging.close();
            throw e;
        }
    }

    /** @return its communication component: where it receives, once started */
    @Override
    public MessagingComponent messaging() {
        return messaging;
    }

    /** @return its agency */
    @Override
    public AgencyComponent agency() {
        return agency;
    }

    @Override
    public String name() {
        return description.get().name();
    }

    @Override
    public Set<Capability> capabilities() {
        return description.get().capabilities();
    }

    @Override
    public List<SensorInfo> sensors() {
        return description.get().sensors().stream().map(s -> new SensorInfo(s.name(), s.type(), s.position())).toList();
    }

    @Override
    public List<String> actions() {
        List<String> out = new ArrayList<>();
        for (ActuatorSpec a : description.get().actuators()) {
            a.actions().keySet().stream().sorted().forEach(action -> out.add(a.name() + "." + action));
        }
        description.get().highLevelActions().forEach(a -> out.add(a.name()));
        return out;
    }

    /** @return the platform this robot drives, for tools that need the raw level */
    public RobotPlatform platform() {
        return platform;
    }

    // ---- Motion ----

    @Override
    public CompletableFuture<Void> moveAsync(double distance, double speed) {
        if (legged()) {
            return legged.move(distance, speed);
        }
        String action = String.format(Locale.ROOT, "move(%.3f, %.3f)", distance, speed);
        DifferentialKinematics k = groundDrive(action);
        requireFinite(action, distance, "distance");
        requireSpeed(action, speed, speed, k);
        return runWheels(action, k, k.move(distance, speed));
    }

    @Override
    public CompletableFuture<Void> turnAsync(double radians, double speed) {
        if (legged()) {
            return legged.turn(radians, speed);
        }
        String action = String.format(Locale.ROOT, "turn(%.4f, %.4f)", radians, speed);
        DifferentialKinematics k = groundDrive(action);
        requireFinite(action, radians, "angle");
        requirePositive(action, speed, "angular speed");
        requireSpeed(action, speed * k.drive().trackWidth() / 2, speed, k);
        return runWheels(action, k, k.turn(radians, speed));
    }

    @Override
    public CompletableFuture<Void> arcAsync(double radius, double angle, double speed) {
        if (legged()) {
            return legged.arc(radius, angle, speed);
        }
        String action = String.format(Locale.ROOT, "arc(%.3f, %.4f, %.3f)", radius, angle, speed);
        DifferentialKinematics k = groundDrive(action);
        requireFinite(action, radius, "radius");
        requireFinite(action, angle, "angle");
        requirePositive(action, speed, "speed");
        WheelMotion m = k.arc(radius, angle, speed);
        double fastest = Math.max(m.leftDegreesPerSecond(), m.rightDegreesPerSecond()) / k.motorDegreesPerMetre();
        requireSpeed(action, fastest, speed, k);
        return runWheels(action, k, m);
    }

    @Override
    public void drive(double linearSpeed, double angularSpeed) {
        RobotDescription d = description.get();
        DrivePlan plan = drivePlan;
        if (plan == null || plan.description() != d) {
            plan = drivePlan(d);
            drivePlan = plan;
        }
        if (plan.legged()) {
            legged.drive(linearSpeed, angularSpeed);
            return;
        }
        String action = "drive";
        DifferentialKinematics k = plan.kinematics();
        if (k == null) {
            k = groundDrive(d, action); // throws, saying why it cannot drive
        }
        requireFinite(action, linearSpeed, "linear speed");
        requireFinite(action, angularSpeed, "angular speed");
        WheelMotion m = k.velocity(linearSpeed, angularSpeed);
        double fastest = Math.max(Math.abs(m.leftDegreesPerSecond()), Math.abs(m.rightDegreesPerSecond())) / k.motorDegreesPerMetre();
        requireWithinMaxSpeed(action, fastest, k);
        if (plan.encoders()) {
            integrateOdometry(k.drive());
        }
        // Nobody waits for a drive's completion: the platform need not make a future for it.
        platform.runDetached(new MotorCommand(action, List.of(
                MotorTarget.run(plan.left(), m.leftDegreesPerSecond()),
                MotorTarget.run(plan.right(), m.rightDegreesPerSecond())),
                CommandPriority.NORMAL, plan.watchdog()));
    }

    /**
     * What {@link #drive} needs of a description, worked out once for each description in force
     * (descriptions are immutable; a reload brings a new one): a controller calls {@code drive}
     * ten times a second, and reading the description's optional parts, capabilities and the
     * platform's encoders each time costs more than the command itself.
     *
     * @param description the description it was worked out for
     * @param legged      whether it has a legged drive
     * @param kinematics  its wheels' kinematics, or {@code null} if it cannot drive on the ground
     * @param encoders    whether both wheel motors have encoders (odometry is tracked)
     * @param left        the left wheel's port
     * @param right       the right wheel's port
     * @param watchdog    the watchdog timeout of continuous commands
     */
    private record DrivePlan(RobotDescription description, boolean legged, DifferentialKinematics kinematics, boolean encoders,
                             String left, String right, Duration watchdog) {
    }

    private DrivePlan drivePlan(RobotDescription d) {
        if (d.leggedDrive().isPresent()) {
            return new DrivePlan(d, true, null, false, null, null, d.watchdogTimeout());
        }
        DifferentialKinematics k;
        try {
            k = groundDrive(d, "drive");
        } catch (UnsupportedActionException e) {
            return new DrivePlan(d, false, null, false, null, null, d.watchdogTimeout());
        }
        DifferentialDrive drive = k.drive();
        boolean encoders = platform.hasEncoder(drive.left().port()) && platform.hasEncoder(drive.right().port());
        return new DrivePlan(d, false, k, encoders, drive.left().port(), drive.right().port(), d.watchdogTimeout());
    }

    @Override
    public void stop() {
        try {
            Futures.await(platform.stopAll(), STOP_TIMEOUT, "stop() of robot '" + name() + "'");
        } finally {
            legged.halted();
            trackOdometry();
        }
    }

    /** How long {@link #stop()} waits for the stop to be handed to the hardware. */
    static final Duration STOP_TIMEOUT = Duration.ofSeconds(5);

    @Override
    public CompletableFuture<Void> changeAltitudeAsync(double metres, double speed) {
        String action = String.format(Locale.ROOT, "changeAltitude(%.3f, %.3f)", metres, speed);
        if (!can(Capability.AIR)) {
            throw new UnsupportedActionException(name(), action, "it is a " + capabilities() + " robot, not an AIR one");
        }
        throw new UnsupportedActionException(name(), action, "platform '" + description.get().platform() + "' has no altitude control");
    }

    @Override
    public CompletableFuture<Void> performAsync(String action, double... args) {
        if (description.get().highLevelAction(action).isPresent()) {
            return legged.perform(action, args);
        }
        String call = "perform(\"" + action + "\")";
        int dot = action.indexOf('.');
        String actuatorName = dot < 0 ? action : action.substring(0, dot);
        ActuatorSpec actuator = description.get().actuators().stream().filter(a -> a.name().equals(actuatorName)).findFirst()
                .orElseThrow(() -> new UnsupportedActionException(name(), call, "it has no actuator '" + actuatorName + "'; its actions are " + actions()));
        ActuatorSpec.Action spec = dot < 0 ? null : actuator.actions().get(action.substring(dot + 1));
        if (spec == null) {
            throw new UnsupportedActionException(name(), call, "its actions are " + actions());
        }
        double degrees;
        if (spec.degrees().isPresent()) {
            if (args.length != 0) {
                throw new UnsupportedActionException(name(), call, "this action takes no arguments, got " + args.length);
            }
            degrees = spec.degrees().getAsDouble();
        } else {
            if (args.length != 1 || !Double.isFinite(args[0])) {
                throw new UnsupportedActionException(name(), call, "this action takes one angle in radians");
            }
            degrees = Math.toDegrees(args[0]);
        }
        return platform.run(MotorCommand.of(call, List.of(MotorTarget.rotate(actuator.port(), degrees, spec.degreesPerSecond()))));
    }

    // ---- Perception ----

    @Override
    public CompletableFuture<Double> getValueAsync(Position position, SensorType type, ReturnType returnType) {
        RobotDescription d = description.get();
        SensorSpec sensor = d.sensors().stream().filter(s -> s.position() == position && type.matches(s.type())).findFirst()
                .orElseThrow(() -> new UnsupportedActionException(name(), "getValue(" + position + ", " + type + ", " + returnType + ")",
                        "it has no " + type + " sensor at " + position + "; its sensors are " + describeSensors(d)));
        return read(sensor, returnType);
    }

    @Override
    public CompletableFuture<Double> getValueAsync(String sensorName, ReturnType returnType) {
        RobotDescription d = description.get();
        SensorSpec sensor = d.sensor(sensorName).orElseThrow(() -> new UnsupportedActionException(name(),
                "getValue(\"" + sensorName + "\", " + returnType + ")", "it has no sensor named '" + sensorName + "'; its sensors are " + describeSensors(d)));
        return read(sensor, returnType);
    }

    private CompletableFuture<Double> read(SensorSpec sensor, ReturnType returnType) {
        String robot = name();
        SensorConverter.check(robot, sensor, returnType);
        return platform.readRaw(sensor.name()).thenApply(raw -> SensorConverter.convert(robot, sensor, raw, returnType));
    }

    @Override
    public Pose pose() {
        if (legged()) {
            return legged.pose();
        }
        return updateOdometry();
    }

    @Override
    public void resetPose(Pose pose) {
        if (legged()) {
            legged.resetPose(pose);
            return;
        }
        synchronized (odometryLock) {
            updateOdometry();
            odometry.reset(pose);
        }
    }

    @Override
    public void close() {
        if (closed) {
            return;
        }
        closed = true;
        try {
            platform.close();
        } finally {
            closeQuietly(agency);
            closeQuietly(messaging);
            closeQuietly(onClose);
        }
    }

    @Override
    public String toString() {
        return "Robot[" + name() + " on " + description.get().platform() + "]";
    }

    // ---- helpers ----

    /** @return whether the description in force has a legged drive, whose motions go through {@link LeggedControl} */
    private boolean legged() {
        return description.get().leggedDrive().isPresent();
    }

    private DifferentialKinematics groundDrive(String action) {
        return groundDrive(description.get(), action);
    }

    private DifferentialKinematics groundDrive(RobotDescription d, String action) {
        if (!d.capabilities().contains(Capability.GROUND)) {
            throw new UnsupportedActionException(d.name(), action, "it is a " + d.capabilities() + " robot, not a GROUND one");
        }
        DifferentialDrive drive = d.drive().orElseThrow(() -> new UnsupportedActionException(d.name(), action, "its description has no drive"));
        DifferentialKinematics k = kinematics;
        if (k == null || (k.drive() != drive && !k.drive().equals(drive))) {
            k = new DifferentialKinematics(drive);
            kinematics = k;
        }
        return k;
    }

    private CompletableFuture<Void> runWheels(String action, DifferentialKinematics k, WheelMotion m) {
        DifferentialDrive d = k.drive();
        trackOdometry();
        CompletableFuture<Void> done = platform.run(MotorCommand.of(action, List.of(
                MotorTarget.rotate(d.left().port(), m.leftDegrees(), m.leftDegreesPerSecond()),
                MotorTarget.rotate(d.right().port(), m.rightDegrees(), m.rightDegreesPerSecond()))));
        return done.whenComplete((v, e) -> trackOdometry());
    }

    private Pose updateOdometry() {
        RobotDescription d = description.get();
        if (d.drive().isEmpty()) {
            throw new UnsupportedActionException(d.name(), "pose()", "its description has no drive to estimate a pose from");
        }
        DifferentialDrive drive = d.drive().get();
        if (!platform.hasEncoder(drive.left().port()) || !platform.hasEncoder(drive.right().port())) {
            throw new UnsupportedActionException(d.name(), "pose()", "its wheel motors have no encoders");
        }
        synchronized (odometryLock) {
            integrateOdometry(drive);
            return odometry.pose();
        }
    }

    /**
     * Moves the odometry on to the encoders' readings now, for a drive known to have encoders. Makes
     * no pose and, for the drive last used, stores no reference (a drive's ten calls a second per
     * robot would otherwise each give the garbage collector a card to refine).
     */
    private void integrateOdometry(DifferentialDrive drive) {
        synchronized (odometryLock) {
            double left = platform.motorDegrees(drive.left().port());
            double right = platform.motorDegrees(drive.right().port());
            if (odometry == null) {
                odometry = new Odometry(new DifferentialKinematics(drive));
                odometryDrive = drive;
            } else if (drive != odometryDrive) {
                if (!drive.equals(odometryDrive)) {
                    odometry = odometry.rebased(new DifferentialKinematics(drive));
                }
                odometryDrive = drive;
            }
            odometry.integrate(left, right);
        }
    }

    /**
     * Keeps odometry up to date around motions, when the robot has what it takes (a drive with
     * encoders); robots without encoders still move, timed, and simply have no pose.
     */
    private void trackOdometry() {
        RobotDescription d = description.get();
        if (d.drive().isPresent()) {
            trackOdometry(d.drive().get());
        }
    }

    /** {@link #trackOdometry()} for the drive in force, whose encoders are asked of the platform once per drive. */
    private void trackOdometry(DifferentialDrive drive) {
        Encoders e = encoders;
        if (e == null || e.drive() != drive) {
            e = new Encoders(drive, platform.hasEncoder(drive.left().port()) && platform.hasEncoder(drive.right().port()));
            encoders = e;
        }
        if (e.both()) {
            integrateOdometry(drive);
        }
    }

    /** Whether both wheel motors of a drive have encoders (a platform's answer does not change). */
    private record Encoders(DifferentialDrive drive, boolean both) {
    }

    private void requireSpeed(String action, double wheelSpeed, double asked, DifferentialKinematics k) {
        requirePositive(action, asked, "speed");
        requireWithinMaxSpeed(action, wheelSpeed, k);
    }

    private void requireWithinMaxSpeed(String action, double wheelSpeed, DifferentialKinematics k) {
        if (wheelSpeed > k.drive().maxSpeed() * (1 + 1e-9)) {
            throw new UnsupportedActionException(name(), action, String.format(Locale.ROOT,
                    "a wheel would need %.3f m/s, above its maximum of %.3f m/s (drive.max_speed)", wheelSpeed, k.drive().maxSpeed()));
        }
    }

    private void requirePositive(String action, double value, String what) {
        if (!(value > 0) || !Double.isFinite(value)) {
            throw new UnsupportedActionException(name(), action, what + " must be a number > 0, got " + value);
        }
    }

    private void requireFinite(String action, double value, String what) {
        if (!Double.isFinite(value)) {
            throw new UnsupportedActionException(name(), action, what + " must be a finite number, got " + value);
        }
    }

    private static String describeSensors(RobotDescription d) {
        return d.sensors().isEmpty() ? "none" : d.sensors().stream()
                .map(s -> s.name() + " (" + s.type() + " at " + s.position() + ")").collect(Collectors.joining(", "));
    }

    private void closeQuietly(AutoCloseable c) {
        if (c == null) {
            return;
        }
        try {
            c.close();
        } catch (Exception e) {
            org.slf4j.LoggerFactory.getLogger(ConfiguredRobot.class).warn("closing {} of {}: {}", c, name(), e.toString());
        }
    }
}
