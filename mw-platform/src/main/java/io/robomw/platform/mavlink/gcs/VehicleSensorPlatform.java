package io.robomw.platform.mavlink.gcs;

import io.robomw.api.RobotLinkException;
import io.robomw.api.spi.SensorChannel;
import io.robomw.platform.mavlink.wire.SensorOrientation;
import io.robomw.platform.sensor.Sensor;
import io.robomw.platform.sensor.SensorPlatform;

import java.util.LinkedHashMap;
import java.util.List;
import java.util.Map;
import java.util.Optional;
import java.util.OptionalDouble;
import java.util.concurrent.CompletableFuture;
import java.util.function.Function;

/**
 * A vehicle's sensors, read from what it streams ({@link Telemetry}): a read returns the latest
 * value at once, in SI units, never waiting on the link. The robot file names each sensor's
 * {@code port}:
 *
 * <pre>
 * port               value (SI, as the sensor types want it)          from                                       type
 * distance:forward   metres to what the forward range finder sees      DISTANCE_SENSOR, orientation NONE (0)      laser, sonar, range...
 * distance:down      metres to the ground or water below (altimeter)   DISTANCE_SENSOR, orientation PITCH_270 (25)
 * distance:backward, distance:left, distance:right, distance:up        orientations YAW_180, YAW_270, YAW_90, PITCH_90
 * altitude           metres above home                                GLOBAL_POSITION_INT.relative_alt           altitude
 * battery:remaining  the charge left, 0 to 1                          SYS_STATUS.battery_remaining (percent)     battery
 * battery:volts      volts                                             SYS_STATUS.voltage_battery                 (read raw)
 * gps:latitude       radians                                           GLOBAL_POSITION_INT.lat                    latitude
 * gps:longitude      radians                                           GLOBAL_POSITION_INT.lon                    longitude
 * heading            radians anti-clockwise from east (a compass's)    ATTITUDE.yaw                               compass
 * </pre>
 * A value the vehicle has not reported yet, or a lost link, fails the read with
 * {@link RobotLinkException} naming the robot and what is missing.
 */
final class VehicleSensorPlatform extends SensorPlatform {

    /** The ports, each with how its value is read. */
    static final Map<String, Function<Telemetry, OptionalDouble>> PORTS = ports();

    private final String robot;
    private final GroundStation gcs;

    VehicleSensorPlatform(String robot, GroundStation gcs) {
        this.robot = robot;
        this.gcs = gcs;
    }

    private static Map<String, Function<Telemetry, OptionalDouble>> ports() {
        Map<String, Function<Telemetry, OptionalDouble>> m = new LinkedHashMap<>();
        for (var e : Map.of("forward", SensorOrientation.NONE, "down", SensorOrientation.PITCH_270, "backward", SensorOrientation.YAW_180,
                "left", SensorOrientation.YAW_270, "right", SensorOrientation.YAW_90, "up", SensorOrientation.PITCH_90).entrySet()) {
            m.put("distance:" + e.getKey(), t -> optional(t.distance(e.getValue())));
        }
        m.put("altitude", t -> finite(t.relativeAltitude()));
        m.put("battery:volts", t -> finite(t.batteryVolts()));
        m.put("battery:remaining", t -> finite(t.batteryRemaining() / 100));
        m.put("gps:latitude", t -> finite(Math.toRadians(t.latitude())));
        m.put("gps:longitude", t -> finite(Math.toRadians(t.longitude())));
        m.put("heading", t -> t.local().map(l -> finite(Math.PI / 2 - l.yaw())).orElse(OptionalDouble.empty()));
        return Map.copyOf(m);
    }

    private static OptionalDouble optional(Optional<Double> v) {
        return v.map(OptionalDouble::of).orElse(OptionalDouble.empty());
    }

    private static OptionalDouble finite(double v) {
        return Double.isFinite(v) ? OptionalDouble.of(v) : OptionalDouble.empty();
    }

    /**
     * @param channels a description's sensors
     * @return one problem per unknown port
     */
    static List<String> check(List<SensorChannel> channels, String source) {
        return channels.stream().filter(c -> !PORTS.containsKey(c.port()))
                .map(c -> source + ": sensor '" + c.name() + "' has port '" + c.port() + "'; a MAVLink vehicle's ports are "
                        + PORTS.keySet().stream().sorted().toList())
                .toList();
    }

    @Override
    public Sensor createSensor(SensorChannel channel) {
        Function<Telemetry, OptionalDouble> read = PORTS.get(channel.port());
        if (read == null) {
            throw new IllegalArgumentException(check(List.of(channel), robot).get(0));
        }
        return () -> {
            if (gcs.isLost()) {
                return CompletableFuture.failedFuture(new RobotLinkException("robot '" + robot + "': its link is lost; sensor '"
                        + channel.name() + "' cannot be read", null));
            }
            OptionalDouble v = read.apply(gcs.telemetry());
            return v.isPresent() ? CompletableFuture.completedFuture(v.getAsDouble())
                    : CompletableFuture.failedFuture(new RobotLinkException("robot '" + robot + "': the vehicle has not reported "
                    + channel.port() + " (sensor '" + channel.name() + "') yet", null));
        };
    }
}
