package io.robomw.platform.mavlink.gcs;

import io.robomw.platform.mavlink.wire.Frame;
import io.robomw.platform.mavlink.wire.LandedState;
import io.robomw.platform.mavlink.wire.Messages;
import io.robomw.platform.mavlink.wire.ModeFlag;
import io.robomw.platform.mavlink.wire.Payload;
import io.robomw.platform.mavlink.wire.SensorOrientation;

import java.util.Map;
import java.util.Optional;
import java.util.concurrent.ConcurrentHashMap;

/**
 * The latest of what a vehicle reports, cached as it comes (on the link's thread) for readings and
 * the pose (on any thread). Units are SI; frames as MAVLink's: local positions north-east-down from
 * the vehicle's origin, yaw clockwise from north.
 *
 * <p>Thread-safe: each value is an immutable record behind a volatile field.
 */
public final class Telemetry {

    /**
     * The vehicle's local position (LOCAL_POSITION_NED) and attitude (ATTITUDE's yaw).
     *
     * @param north  metres north of its origin
     * @param east   metres east
     * @param down   metres down (negative: above the origin)
     * @param vn     m/s north
     * @param ve     m/s east
     * @param vd     m/s down
     * @param yaw    radians clockwise from north
     * @param atNanos when it came, the ground station's monotonic clock
     */
    public record Local(double north, double east, double down, double vn, double ve, double vd, double yaw, long atNanos) {
    }

    /**
     * HEARTBEAT's state.
     *
     * @param customMode its custom mode
     * @param armed      whether it is armed
     * @param atNanos    when it came
     */
    public record Heartbeat(long customMode, boolean armed, long atNanos) {
    }

    private volatile Local local;
    private volatile double yaw = Double.NaN;
    private volatile Heartbeat heartbeat;
    private volatile LandedState landed = LandedState.UNDEFINED;
    private volatile double latitude = Double.NaN;
    private volatile double longitude = Double.NaN;
    private volatile double relativeAltitude = Double.NaN;
    private volatile double batteryVolts = Double.NaN;
    private volatile double batteryRemaining = Double.NaN;
    private final Map<Integer, Double> distances = new ConcurrentHashMap<>();

    /**
     * Takes what a frame from the vehicle says.
     *
     * @param f       the frame
     * @param atNanos now
     */
    void update(Frame f, long atNanos) {
        Payload p = f.payload();
        if (f.is(Messages.Heartbeat.MESSAGE)) {
            heartbeat = new Heartbeat(p.getLong(Messages.Heartbeat.CUSTOM_MODE), ModeFlag.SAFETY_ARMED.in(p.getLong(Messages.Heartbeat.BASE_MODE)),
                    atNanos);
        } else if (f.is(Messages.LocalPositionNed.MESSAGE)) {
            local = new Local(p.getDouble(Messages.LocalPositionNed.X), p.getDouble(Messages.LocalPositionNed.Y),
                    p.getDouble(Messages.LocalPositionNed.Z), p.getDouble(Messages.LocalPositionNed.VX), p.getDouble(Messages.LocalPositionNed.VY),
                    p.getDouble(Messages.LocalPositionNed.VZ), yaw, atNanos);
        } else if (f.is(Messages.Attitude.MESSAGE)) {
            yaw = p.getDouble(Messages.Attitude.YAW);
            Local l = local;
            if (l != null) {
                local = new Local(l.north(), l.east(), l.down(), l.vn(), l.ve(), l.vd(), yaw, l.atNanos());
            }
        } else if (f.is(Messages.ExtendedSysState.MESSAGE)) {
            landed = LandedState.find(p.getLong(Messages.ExtendedSysState.LANDED_STATE)).orElse(LandedState.UNDEFINED);
        } else if (f.is(Messages.GlobalPositionInt.MESSAGE)) {
            latitude = p.getLong(Messages.GlobalPositionInt.LAT) / 1e7;
            longitude = p.getLong(Messages.GlobalPositionInt.LON) / 1e7;
            relativeAltitude = p.getLong(Messages.GlobalPositionInt.RELATIVE_ALT) / 1000.0;
        } else if (f.is(Messages.SysStatus.MESSAGE)) {
            long mv = p.getLong(Messages.SysStatus.VOLTAGE_BATTERY);
            batteryVolts = mv == 0xFFFF ? Double.NaN : mv / 1000.0;
            long rem = p.getLong(Messages.SysStatus.BATTERY_REMAINING);
            batteryRemaining = rem < 0 ? Double.NaN : rem;
        } else if (f.is(Messages.DistanceSensor.MESSAGE)) {
            distances.put((int) p.getLong(Messages.DistanceSensor.ORIENTATION), p.getLong(Messages.DistanceSensor.CURRENT_DISTANCE) / 100.0);
        }
    }

    /** @return the local position and yaw, once both are reported (LOCAL_POSITION_NED and ATTITUDE) */
    public Optional<Local> local() {
        Local l = local;
        return l == null || Double.isNaN(l.yaw()) ? Optional.empty() : Optional.of(l);
    }

    /** @return the last HEARTBEAT's state, once heard */
    public Optional<Heartbeat> heartbeat() {
        return Optional.ofNullable(heartbeat);
    }

    /** @return whether it is on the ground, in the air, taking off or landing (multirotors) */
    public LandedState landed() {
        return landed;
    }

    /** @return its latitude, degrees (NaN before GLOBAL_POSITION_INT) */
    public double latitude() {
        return latitude;
    }

    /** @return its longitude, degrees */
    public double longitude() {
        return longitude;
    }

    /** @return its altitude above home, metres */
    public double relativeAltitude() {
        return relativeAltitude;
    }

    /** @return its battery's voltage, volts */
    public double batteryVolts() {
        return batteryVolts;
    }

    /** @return its battery's charge left, percent */
    public double batteryRemaining() {
        return batteryRemaining;
    }

    /**
     * @param orientation where a range finder points
     * @return its latest distance, metres, if one reported
     */
    public Optional<Double> distance(SensorOrientation orientation) {
        return Optional.ofNullable(distances.get(orientation.code()));
    }
}
