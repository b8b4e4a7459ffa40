package io.robomw.api.spi;

import io.robomw.api.Clock;

import java.time.Duration;
import java.util.List;
import java.util.Objects;

/**
 * What a platform is told about the robot it opens.
 *
 * @param robotName       the robot's name, for thread names and error messages
 * @param platformName    the {@code platform:} value
 * @param connection      the {@code connection:} block
 * @param motors          every motor the description uses: wheels first, then actuators
 * @param sensors         the sensors
 * @param cyclePeriod     period of the execution action thread
 * @param watchdogTimeout default timeout of continuous commands; {@link Duration#ZERO} is off
 * @param clock           the source of time
 * @param services        services the program handed over (a simulated world...)
 * @param cycling         who runs the platform's cycles: its own threads, or its owner (a simulation)
 * @param failures        where its owner threads report what they catch (one policy per process)
 */
public record PlatformConfig(String robotName, String platformName, ConnectionSettings connection,
                             List<MotorChannel> motors, List<SensorChannel> sensors,
                             Duration cyclePeriod, Duration watchdogTimeout, Clock clock,
                             PlatformServices services, Cycling cycling, FailurePolicy failures) {

    /** Checks and copies. */
    public PlatformConfig {
        Objects.requireNonNull(robotName, "robotName");
        Objects.requireNonNull(platformName, "platformName");
        Objects.requireNonNull(connection, "connection");
        motors = List.copyOf(motors);
        sensors = List.copyOf(sensors);
        Objects.requireNonNull(cyclePeriod, "cyclePeriod");
        Objects.requireNonNull(watchdogTimeout, "watchdogTimeout");
        Objects.requireNonNull(clock, "clock");
        Objects.requireNonNull(services, "services");
        Objects.requireNonNull(cycling, "cycling");
        Objects.requireNonNull(failures, "failures");
        if (cyclePeriod.isZero() || cyclePeriod.isNegative()) {
            throw new IllegalArgumentException(robotName + ": cyclePeriod must be > 0, got " + cyclePeriod);
        }
        for (int i = 0; i < motors.size(); i++) {
            for (int j = i + 1; j < motors.size(); j++) {
                if (motors.get(i).port().equals(motors.get(j).port())) {
                    throw new IllegalArgumentException(connection.source() + ": motor port " + motors.get(i).port()
                            + " is used twice (as " + motors.get(i).role() + " and " + motors.get(j).role() + "); give each motor its own port");
                }
            }
        }
    }

    /**
     * @param other another connection block (a command line's override)
     * @return this configuration with that connection
     */
    public PlatformConfig withConnection(ConnectionSettings other) {
        return new PlatformConfig(robotName, platformName, other, motors, sensors, cyclePeriod, watchdogTimeout, clock, services,
                cycling, failures);
    }

    /** @return the ports of every motor, in the order of {@link #motors()} */
    public List<String> motorPorts() {
        return motors.stream().map(MotorChannel::port).toList();
    }

    /** @return the drive's wheel motors, left then right; empty when the robot has no drive */
    public List<MotorChannel> wheels() {
        return motors.stream().filter(m -> m.role().wheel()).toList();
    }

    /** @return where the configuration came from (the description file), for error messages */
    public String source() {
        return connection.source();
    }

    /**
     * @param name a sensor name
     * @return the sensor
     * @throws IllegalArgumentException if there is none of that name
     */
    public SensorChannel sensor(String name) {
        return sensors.stream().filter(s -> s.name().equals(name)).findFirst()
                .orElseThrow(() -> new IllegalArgumentException(robotName + " has no sensor named '" + name + "'"));
    }
}
