package io.robomw.config.description;

import io.robomw.api.Capability;
import io.robomw.api.spi.AgencyConfig;
import io.robomw.api.spi.ConnectionSettings;
import io.robomw.api.spi.MessagingConfig;
import io.robomw.api.spi.MotorChannel;

import java.time.Duration;
import java.util.List;
import java.util.Objects;
import java.util.Optional;
import java.util.Set;
import java.util.stream.Stream;

/**
 * A robot's physical description, as read from its YAML file: what hardware it is, how its
 * wheels are laid out, what sensors and actuators it has. Immutable; a reload makes a new one.
 *
 * @param name            the robot's name
 * @param platform        the {@code platform:} value that picks the driver
 * @param connection      the {@code connection:} block
 * @param cyclePeriod     the execution action thread's period
 * @param watchdogTimeout continuous commands stop unless repeated within this; zero = off
 * @param capabilities    ground, air, water
 * @param drive           the differential drive, if the robot drives on two wheels
 * @param body            size and mass, for the simulator
 * @param sensors         the sensors
 * @param actuators       extra actuators with named actions
 * @param leggedDrive     the legged drive, if the robot walks by its firmware's own commands
 *                        (then {@code drive} is empty)
 * @param highLevelActions named actions the firmware performs by itself (sit, kick, head.pan)
 * @param messaging       how its communication component starts (the {@code messaging:} section, or defaults)
 * @param agency          how its agency starts (the {@code agency:} section, or defaults)
 * @param source          the file it was read from, for messages
 * @param vehicleDrive    the vehicle drive, if the robot is a drone, boat or rover moved by its
 *                        autopilot (then {@code drive} and {@code leggedDrive} are empty)
 */
public record RobotDescription(String name, String platform, ConnectionSettings connection,
                               Duration cyclePeriod, Duration watchdogTimeout,
                               Set<Capability> capabilities, Optional<DifferentialDrive> drive,
                               Body body, List<SensorSpec> sensors, List<ActuatorSpec> actuators,
                               Optional<LeggedDrive> leggedDrive, List<HighLevelAction> highLevelActions,
                               MessagingConfig messaging, AgencyConfig agency, String source,
                               Optional<VehicleDrive> vehicleDrive) {

    /** Copies collections. */
    public RobotDescription {
        Objects.requireNonNull(vehicleDrive, "vehicleDrive");
        Objects.requireNonNull(name, "name");
        Objects.requireNonNull(platform, "platform");
        capabilities = Set.copyOf(capabilities);
        sensors = List.copyOf(sensors);
        actuators = List.copyOf(actuators);
        Objects.requireNonNull(leggedDrive, "leggedDrive");
        highLevelActions = List.copyOf(highLevelActions);
        Objects.requireNonNull(messaging, "messaging");
        Objects.requireNonNull(agency, "agency");
    }

    /**
     * A description without a vehicle drive.
     *
     * @param name             the robot's name
     * @param platform         the {@code platform:} value
     * @param connection       the {@code connection:} block
     * @param cyclePeriod      the execution action thread's period
     * @param watchdogTimeout  the continuous commands' watchdog
     * @param capabilities     ground, air, water
     * @param drive            the differential drive, if any
     * @param body             size and mass
     * @param sensors          the sensors
     * @param actuators        extra actuators
     * @param leggedDrive      the legged drive, if any
     * @param highLevelActions named actions of the firmware
     * @param messaging        the messaging section
     * @param agency           the agency section
     * @param source           the file it was read from
     */
    public RobotDescription(String name, String platform, ConnectionSettings connection, Duration cyclePeriod, Duration watchdogTimeout,
                            Set<Capability> capabilities, Optional<DifferentialDrive> drive, Body body, List<SensorSpec> sensors,
                            List<ActuatorSpec> actuators, Optional<LeggedDrive> leggedDrive, List<HighLevelAction> highLevelActions,
                            MessagingConfig messaging, AgencyConfig agency, String source) {
        this(name, platform, connection, cyclePeriod, watchdogTimeout, capabilities, drive, body, sensors, actuators, leggedDrive,
                highLevelActions, messaging, agency, source, Optional.empty());
    }

    /**
     * @return its drive section, whatever its kind ({@link #drive()}, {@link #leggedDrive()} or
     *         {@link #vehicleDrive()}), if it has one
     */
    public Optional<DriveSpec> driveSpec() {
        return drive.<DriveSpec>map(d -> d).or(() -> leggedDrive.map(d -> d)).or(() -> vehicleDrive.map(d -> d));
    }

    /** @return the kind of its drive, if it has one */
    public Optional<DriveKind> driveKind() {
        return driveSpec().map(DriveSpec::kind);
    }

    /** @return every motor port the description uses: wheels first, then actuators */
    public List<String> motorPorts() {
        Stream<String> wheels = drive.stream().flatMap(d -> Stream.of(d.left().port(), d.right().port()));
        return Stream.concat(wheels, actuators.stream().map(ActuatorSpec::port)).toList();
    }

    /** @return every motor as its platform is told of it: wheels first (with their encoders and counters), then actuators */
    public List<MotorChannel> motors() {
        Stream<MotorChannel> wheels = drive.stream().flatMap(d -> Stream.of(
                new MotorChannel(d.left().port(), MotorChannel.Role.LEFT_WHEEL, d.encoderTicksPerRevolution(), d.left().counter()),
                new MotorChannel(d.right().port(), MotorChannel.Role.RIGHT_WHEEL, d.encoderTicksPerRevolution(), d.right().counter())));
        return Stream.concat(wheels, actuators.stream().map(a -> MotorChannel.actuator(a.port()))).toList();
    }

    /**
     * @param actionName a name {@code perform} was given
     * @return the high-level action of that name, if the description has one
     */
    public Optional<HighLevelAction> highLevelAction(String actionName) {
        return highLevelActions.stream().filter(a -> a.name().equals(actionName)).findFirst();
    }

    /**
     * @param sensorName a sensor name
     * @return that sensor, if present
     */
    public Optional<SensorSpec> sensor(String sensorName) {
        return sensors.stream().filter(s -> s.name().equals(sensorName)).findFirst();
    }
}
