package io.robomw.config.robot;

import io.robomw.api.Capability;
import io.robomw.api.Pose;
import io.robomw.api.Position;
import io.robomw.api.ReturnType;
import io.robomw.api.Robot;
import io.robomw.api.SensorInfo;
import io.robomw.api.SensorType;
import io.robomw.api.UnsupportedActionException;
import io.robomw.api.spi.AgencyComponent;
import io.robomw.api.spi.MessagingComponent;
import io.robomw.api.spi.RobotComponents;
import io.robomw.api.spi.RobotPlatform;
import io.robomw.config.description.RobotDescription;
import io.robomw.config.drive.DriveControl;
import io.robomw.config.drive.Drives;
import io.robomw.config.sensing.SensorReader;
import org.slf4j.LoggerFactory;

import java.time.Duration;
import java.util.List;
import java.util.Objects;
import java.util.Set;
import java.util.concurrent.CompletableFuture;
import java.util.function.Supplier;

/**
 * The Configuration Layer's robot: the Instruction Layer's verbs, each checked against the robot's
 * description in force and handed to the part that does it:
 * <ul>
 *   <li>motions and the pose to the {@link DriveControl} chosen for the description
 *   ({@link Drives#choose}: wheels, legs...), chosen again when a reload brings a new
 *   description, so the next command follows the reload;</li>
 *   <li>{@code perform} to the {@link NamedActions};</li>
 *   <li>perception to the {@link SensorReader};</li>
 *   <li>messaging and agents to the robot's communication component and agency, which the
 *   providers found through the SPI open ({@link RobotComponents}: {@code mw-agents} provides
 *   both; without it those calls throw {@link UnsupportedActionException} saying what to add).</li>
 * </ul>
 * {@link #stop()} hands the stop to the platform and waits until it is on the way to the hardware.
 * The robot closes its platform, then its components.
 *
 * <p>Thread-safe.
 */
public final class ConfiguredRobot implements Robot {

    /** How long {@link #stop()} waits for the stop to be handed to the hardware. */
    static final Duration STOP_TIMEOUT = Duration.ofSeconds(5);

    private final Supplier<RobotDescription> description;
    private final RobotPlatform platform;
    private final MessagingComponent messaging;
    private final AgencyComponent agency;
    private final AutoCloseable onClose;
    private final NamedActions actions;
    private final SensorReader sensors;
    private final Object choosing = new Object();
    /** The drive chosen for the description last in force, or {@code null} before the first verb. */
    private volatile DriveControl drive;
    private volatile boolean closed;

    /**
     * @param description the description in force (read on every call)
     * @param platform    the opened platform
     * @param messaging   the communication component
     * @param agency      the agency
     * @param onClose     closed after the platform (a description watcher), or {@code null}
     */
    public ConfiguredRobot(Supplier<RobotDescription> description, RobotPlatform platform,
                           MessagingComponent messaging, AgencyComponent agency, AutoCloseable onClose) {
        this.description = Objects.requireNonNull(description, "description");
        this.platform = Objects.requireNonNull(platform, "platform");
        this.messaging = Objects.requireNonNull(messaging, "messaging");
        this.agency = Objects.requireNonNull(agency, "agency");
        this.onClose = onClose;
        this.actions = new NamedActions(platform);
        this.sensors = new SensorReader(platform);
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
        return withComponents(description, platform, onClose, RobotComponents.find());
    }

    /**
     * A robot with every component from providers looked up already: for a caller that opens many
     * robots ({@link RobotComponents#find} once, not twice a robot).
     *
     * @param description the description in force (read on every call; the sections are read now)
     * @param platform    the opened platform
     * @param onClose     closed after the platform, or {@code null}
     * @param components  the providers of messaging and agency
     * @return the robot
     */
    public static ConfiguredRobot withComponents(Supplier<RobotDescription> description, RobotPlatform platform, AutoCloseable onClose,
                                                 RobotComponents components) {
        RobotDescription d = description.get();
        MessagingComponent messaging = components.messagingOf(d.name(), d.messaging());
        try {
            return new ConfiguredRobot(description, platform, messaging, components.agencyOf(d.name(), d.agency()), onClose);
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
        return NamedActions.list(description.get());
    }

    /** @return the platform this robot drives, for tools that need the raw level */
    public RobotPlatform platform() {
        return platform;
    }

    // ---- Motion ----

    @Override
    public CompletableFuture<Void> moveAsync(double distance, double speed) {
        return drive().move(distance, speed);
    }

    @Override
    public CompletableFuture<Void> turnAsync(double radians, double speed) {
        return drive().turn(radians, speed);
    }

    @Override
    public CompletableFuture<Void> arcAsync(double radius, double angle, double speed) {
        return drive().arc(radius, angle, speed);
    }

    @Override
    public void drive(double linearSpeed, double angularSpeed) {
        drive().drive(linearSpeed, angularSpeed);
    }

    @Override
    public CompletableFuture<Void> changeAltitudeAsync(double metres, double speed) {
        return drive().changeAltitude(metres, speed);
    }

    @Override
    public CompletableFuture<Void> takeOffAsync(double altitude) {
        return drive().takeOff(altitude);
    }

    @Override
    public CompletableFuture<Void> landAsync() {
        return drive().land();
    }

    /**
     * Hands the stop to the platform first (safety priority: it ends every command; nothing is
     * read or integrated before) and waits until the platform reports it handed to the hardware,
     * at most {@link #STOP_TIMEOUT}. Then the drive's pose ends the motion under way. Once it
     * returns, the stop no longer holds the motors: the next command is admitted as usual.
     *
     * @throws io.robomw.api.RobotLinkException naming the robot if the stop could not be handed to
     *                                          the hardware in time
     */
    @Override
    public void stop() {
        Stops.awaitHanded(platform.stopAll(), STOP_TIMEOUT, name());
        drive().halted();
    }

    @Override
    public CompletableFuture<Void> performAsync(String action, double... args) {
        return actions.perform(description.get(), drive(), action, args);
    }

    // ---- Perception ----

    @Override
    public CompletableFuture<Double> getValueAsync(Position position, SensorType type, ReturnType returnType) {
        return sensors.read(description.get(), position, type, returnType);
    }

    @Override
    public CompletableFuture<Double> getValueAsync(String sensorName, ReturnType returnType) {
        return sensors.read(description.get(), sensorName, returnType);
    }

    @Override
    public Pose pose() {
        return drive().pose();
    }

    @Override
    public void resetPose(Pose pose) {
        drive().resetPose(pose);
    }

    // ---- lifecycle ----

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

    /**
     * @return the drive for the description in force: the one chosen before while the description
     *         is the same object (descriptions are immutable; a reload brings a new one), else one
     *         chosen now, continuing the previous one's pose
     */
    private DriveControl drive() {
        RobotDescription d = description.get();
        DriveControl current = drive;
        if (current != null && current.description() == d) {
            return current;
        }
        synchronized (choosing) {
            current = drive;
            if (current == null || current.description() != d) {
                current = Drives.choose(d, platform, current);
                drive = current;
            }
            return current;
        }
    }

    private void closeQuietly(AutoCloseable c) {
        if (c == null) {
            return;
        }
        try {
            c.close();
        } catch (Exception e) {
            LoggerFactory.getLogger(ConfiguredRobot.class).warn("closing {} of {}: {}", c, name(), e.toString());
        }
    }
}
