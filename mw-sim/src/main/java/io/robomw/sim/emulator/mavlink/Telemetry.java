package io.robomw.sim.emulator.mavlink;

import io.robomw.config.description.VehicleDrive;
import io.robomw.platform.mavlink.wire.DistanceSensorType;
import io.robomw.platform.mavlink.wire.LandedState;
import io.robomw.platform.mavlink.wire.MavState;
import io.robomw.platform.mavlink.wire.MavType;
import io.robomw.platform.mavlink.wire.Messages;
import io.robomw.platform.mavlink.wire.ModeFlag;
import io.robomw.platform.mavlink.wire.Payload;
import io.robomw.platform.mavlink.wire.SensorOrientation;
import io.robomw.sim.SensorModel;
import io.robomw.sim.SimRobot;
import io.robomw.sim.vehicle.SimVehicle;

import java.util.ArrayList;
import java.util.HashMap;
import java.util.List;
import java.util.Map;

/**
 * What the emulated autopilot streams, and when: the messages a ground station and MAVSDK read,
 * built from the simulated vehicle at the moment they are sent.
 *
 * <pre>
 * message               rate   from
 * HEARTBEAT             1 Hz   type (quadrotor 2, rover 10, boat 11), autopilot, mode, armed
 * SYS_STATUS            1 Hz   sensors present/enabled/healthy (gyro, accel, mag, GPS, battery, pre-arm), battery
 * EXTENDED_SYS_STATE    1 Hz   landed state (multirotors)
 * GPS_RAW_INT           5 Hz   3D fix, 12 satellites, position
 * HOME_POSITION         1 Hz   the local origin on Earth
 * BATTERY_STATUS        1 Hz   cell voltages, current, charge used, remaining
 * MISSION_CURRENT       1 Hz   (and on change) the current item
 * GLOBAL_POSITION_INT  10 Hz   latitude, longitude (1e7 deg), altitude (mm), velocity (cm/s), heading (cdeg)
 * LOCAL_POSITION_NED   10 Hz   north, east, down from the local origin
 * ATTITUDE             10 Hz   roll and pitch from the acceleration, yaw
 * VFR_HUD               4 Hz   speeds, heading, climb
 * DISTANCE_SENSOR      10 Hz   each range finder: downward (the altitude over the ground) and forward
 * </pre>
 * SET_MESSAGE_INTERVAL changes a rate (-1 stops a message, 0 restores its default); REQUEST_MESSAGE
 * sends one at once.
 *
 * <p>Not thread-safe: the simulation's thread.
 */
final class Telemetry {

    /** MAV_SYS_STATUS_SENSOR bits reported present, enabled and healthy. */
    static final long SENSORS = 0x1 | 0x2 | 0x4 | 0x20 | 0x2000000 | 0x10000000;
    /** MAV_PROTOCOL_CAPABILITY: mission float and int, param float, command int, local setpoints, global setpoints, MAVLink 2. */
    static final long CAPABILITIES = 1 | 2 | 4 | 8 | 128 | 256 | 8192;
    /** MAV_PROTOCOL_CAPABILITY_PARAM_ENCODE_BYTEWISE: PX4 sends an integer parameter's bits as they are. */
    static final long PARAM_ENCODE_BYTEWISE = 16;
    /** MAV_PROTOCOL_CAPABILITY_PARAM_ENCODE_C_CAST: ArduPilot casts an integer parameter to float. */
    static final long PARAM_ENCODE_C_CAST = 1 << 17;

    private static final Map<Integer, Double> DEFAULT_RATES = Map.ofEntries(
            Map.entry(Messages.Heartbeat.MESSAGE.id(), 1.0),
            Map.entry(Messages.SysStatus.MESSAGE.id(), 1.0),
            Map.entry(Messages.ExtendedSysState.MESSAGE.id(), 1.0),
            Map.entry(Messages.GpsRawInt.MESSAGE.id(), 5.0),
            Map.entry(Messages.HomePosition.MESSAGE.id(), 1.0),
            Map.entry(Messages.BatteryStatus.MESSAGE.id(), 1.0),
            Map.entry(Messages.MissionCurrent.MESSAGE.id(), 1.0),
            Map.entry(Messages.GlobalPositionInt.MESSAGE.id(), 10.0),
            Map.entry(Messages.LocalPositionNed.MESSAGE.id(), 10.0),
            Map.entry(Messages.Attitude.MESSAGE.id(), 10.0),
            Map.entry(Messages.VfrHud.MESSAGE.id(), 4.0),
            Map.entry(Messages.DistanceSensor.MESSAGE.id(), 10.0));

    private final SimRobot robot;
    private final SimVehicle vehicle;
    private final Autopilot autopilot;
    private final Dialect dialect;
    private final Map<Integer, Double> intervals = new HashMap<>();
    private final Map<Integer, Double> next = new HashMap<>();
    private double lastVx;
    private double lastVy;
    private double lastTime;

    Telemetry(SimRobot robot, Autopilot autopilot, Dialect dialect) {
        this.robot = robot;
        this.vehicle = robot.vehicle();
        this.autopilot = autopilot;
        this.dialect = dialect;
        DEFAULT_RATES.forEach((id, hz) -> intervals.put(id, 1 / hz));
    }

    /**
     * @param messageId a message id
     * @param microseconds the interval asked for: -1 stops it, 0 restores its default
     * @return whether this emulator streams that message
     */
    boolean interval(int messageId, double microseconds) {
        if (!DEFAULT_RATES.containsKey(messageId)) {
            return false;
        }
        if (microseconds == 0) {
            intervals.put(messageId, 1 / DEFAULT_RATES.get(messageId));
        } else if (microseconds < 0) {
            intervals.put(messageId, Double.POSITIVE_INFINITY);
        } else {
            intervals.put(messageId, microseconds / 1e6);
        }
        next.put(messageId, 0.0);
        return true;
    }

    /**
     * @param time simulated seconds since the emulator started
     * @return the messages due now
     */
    List<Payload> due(double time) {
        List<Payload> out = new ArrayList<>();
        for (Map.Entry<Integer, Double> e : intervals.entrySet()) {
            double at = next.getOrDefault(e.getKey(), 0.0);
            if (time + 1e-9 >= at && Double.isFinite(e.getValue())) {
                out.addAll(message(e.getKey(), time));
                next.put(e.getKey(), Math.max(at + e.getValue(), time));
            }
        }
        if (autopilot.drainMissionChanged() && next.getOrDefault(Messages.MissionCurrent.MESSAGE.id(), 0.0) > time) {
            out.add(missionCurrent());
        }
        for (int seq : autopilot.drainReached()) {
            out.add(Payload.of(Messages.MissionItemReached.MESSAGE).set(Messages.MissionItemReached.SEQ, seq));
        }
        return out;
    }

    /**
     * @param messageId a message id
     * @param time      now
     * @return the message(s) of that id, now (empty when this emulator does not make it)
     */
    List<Payload> message(int messageId, double time) {
        SimVehicle.Snapshot s = vehicle.snapshot();
        LocalFrame f = autopilot.frame();
        if (messageId == Messages.Heartbeat.MESSAGE.id()) {
            return List.of(heartbeat(s));
        } else if (messageId == Messages.SysStatus.MESSAGE.id()) {
            return List.of(Payload.of(Messages.SysStatus.MESSAGE)
                    .set(Messages.SysStatus.ONBOARD_CONTROL_SENSORS_PRESENT, SENSORS)
                    .set(Messages.SysStatus.ONBOARD_CONTROL_SENSORS_ENABLED, SENSORS)
                    .set(Messages.SysStatus.ONBOARD_CONTROL_SENSORS_HEALTH, SENSORS)
                    .set(Messages.SysStatus.LOAD, 250)
                    .set(Messages.SysStatus.VOLTAGE_BATTERY, Math.round(s.volts() * 1000))
                    .set(Messages.SysStatus.CURRENT_BATTERY, Math.round(s.amps() * 100))
                    .set(Messages.SysStatus.BATTERY_REMAINING, Math.round(s.battery() * 100)));
        } else if (messageId == Messages.ExtendedSysState.MESSAGE.id()) {
            LandedState state = autopilot.medium() != VehicleDrive.Medium.AIR ? LandedState.UNDEFINED
                    : s.landed() ? LandedState.ON_GROUND
                    : autopilot.mode() == FlightMode.LAND ? LandedState.LANDING
                    : autopilot.mode() == FlightMode.TAKEOFF ? LandedState.TAKEOFF : LandedState.IN_AIR;
            return List.of(Payload.of(Messages.ExtendedSysState.MESSAGE).set(Messages.ExtendedSysState.LANDED_STATE, state.code()));
        } else if (messageId == Messages.GpsRawInt.MESSAGE.id()) {
            return List.of(Payload.of(Messages.GpsRawInt.MESSAGE)
                    .set(Messages.GpsRawInt.TIME_USEC, Math.round(time * 1e6))
                    .set(Messages.GpsRawInt.FIX_TYPE, 3)
                    .set(Messages.GpsRawInt.LAT, Math.round(f.latitude(s.y()) * 1e7))
                    .set(Messages.GpsRawInt.LON, Math.round(f.longitude(s.x()) * 1e7))
                    .set(Messages.GpsRawInt.ALT, Math.round(f.amsl(s.z()) * 1000))
                    .set(Messages.GpsRawInt.EPH, 80)
                    .set(Messages.GpsRawInt.EPV, 120)
                    .set(Messages.GpsRawInt.VEL, Math.round(Math.hypot(s.vx(), s.vy()) * 100))
                    .set(Messages.GpsRawInt.COG, cdeg(s.vx(), s.vy()))
                    .set(Messages.GpsRawInt.SATELLITES_VISIBLE, 12));
        } else if (messageId == Messages.HomePosition.MESSAGE.id()) {
            return List.of(Payload.of(Messages.HomePosition.MESSAGE)
                    .set(Messages.HomePosition.LATITUDE, Math.round(f.latitude(f.y0()) * 1e7))
                    .set(Messages.HomePosition.LONGITUDE, Math.round(f.longitude(f.x0()) * 1e7))
                    .set(Messages.HomePosition.ALTITUDE, Math.round(f.amsl(0) * 1000))
                    .set(Messages.HomePosition.Q, 0, 1.0)
                    .set(Messages.HomePosition.TIME_USEC, Math.round(time * 1e6)));
        } else if (messageId == Messages.BatteryStatus.MESSAGE.id()) {
            Payload p = Payload.of(Messages.BatteryStatus.MESSAGE)
                    .set(Messages.BatteryStatus.BATTERY_FUNCTION, 1)
                    .set(Messages.BatteryStatus.TYPE, 1)
                    .set(Messages.BatteryStatus.TEMPERATURE, Short.MAX_VALUE)
                    .set(Messages.BatteryStatus.CURRENT_BATTERY, Math.round(s.amps() * 100))
                    .set(Messages.BatteryStatus.CURRENT_CONSUMED, Math.round(vehicle.battery().usedMah()))
                    .set(Messages.BatteryStatus.ENERGY_CONSUMED, Math.round(vehicle.battery().usedWh() * 36))
                    .set(Messages.BatteryStatus.BATTERY_REMAINING, Math.round(s.battery() * 100))
                    .set(Messages.BatteryStatus.CHARGE_STATE, 1);
            int cells = vehicle.battery().cells();
            for (int i = 0; i < 10; i++) {
                p.set(Messages.BatteryStatus.VOLTAGES, i, i < cells ? Math.round(s.volts() / cells * 1000) : 0xFFFF);
            }
            return List.of(p);
        } else if (messageId == Messages.MissionCurrent.MESSAGE.id()) {
            return List.of(missionCurrent());
        } else if (messageId == Messages.GlobalPositionInt.MESSAGE.id()) {
            return List.of(Payload.of(Messages.GlobalPositionInt.MESSAGE)
                    .set(Messages.GlobalPositionInt.TIME_BOOT_MS, Math.round(time * 1000))
                    .set(Messages.GlobalPositionInt.LAT, Math.round(f.latitude(s.y()) * 1e7))
                    .set(Messages.GlobalPositionInt.LON, Math.round(f.longitude(s.x()) * 1e7))
                    .set(Messages.GlobalPositionInt.ALT, Math.round(f.amsl(s.z()) * 1000))
                    .set(Messages.GlobalPositionInt.RELATIVE_ALT, Math.round(s.z() * 1000))
                    .set(Messages.GlobalPositionInt.VX, Math.round(s.vy() * 100))
                    .set(Messages.GlobalPositionInt.VY, Math.round(s.vx() * 100))
                    .set(Messages.GlobalPositionInt.VZ, Math.round(-s.vz() * 100))
                    .set(Messages.GlobalPositionInt.HDG, Math.round((Math.toDegrees(LocalFrame.yaw(s.heading())) + 360) % 360 * 100) % 36000));
        } else if (messageId == Messages.LocalPositionNed.MESSAGE.id()) {
            return List.of(Payload.of(Messages.LocalPositionNed.MESSAGE)
                    .set(Messages.LocalPositionNed.TIME_BOOT_MS, Math.round(time * 1000))
                    .set(Messages.LocalPositionNed.X, f.north(s.y()))
                    .set(Messages.LocalPositionNed.Y, f.east(s.x()))
                    .set(Messages.LocalPositionNed.Z, -s.z())
                    .set(Messages.LocalPositionNed.VX, s.vy())
                    .set(Messages.LocalPositionNed.VY, s.vx())
                    .set(Messages.LocalPositionNed.VZ, -s.vz()));
        } else if (messageId == Messages.Attitude.MESSAGE.id()) {
            return List.of(attitude(s, time));
        } else if (messageId == Messages.VfrHud.MESSAGE.id()) {
            double speed = Math.hypot(s.vx(), s.vy());
            return List.of(Payload.of(Messages.VfrHud.MESSAGE)
                    .set(Messages.VfrHud.AIRSPEED, speed)
                    .set(Messages.VfrHud.GROUNDSPEED, speed)
                    .set(Messages.VfrHud.HEADING, Math.round((Math.toDegrees(LocalFrame.yaw(s.heading())) + 360) % 360))
                    .set(Messages.VfrHud.THROTTLE, s.armed() ? 50 : 0)
                    .set(Messages.VfrHud.ALT, f.amsl(s.z()))
                    .set(Messages.VfrHud.CLIMB, s.vz()));
        } else if (messageId == Messages.DistanceSensor.MESSAGE.id()) {
            return distanceSensors(s, time);
        }
        return List.of();
    }

    /**
     * @return HEARTBEAT: the vehicle's type, the dialect's autopilot, the mode flags and custom mode,
     *         STANDBY or ACTIVE
     */
    Payload heartbeat(SimVehicle.Snapshot s) {
        MavType type = switch (autopilot.medium()) {
            case AIR -> MavType.QUADROTOR;
            case WATER -> MavType.SURFACE_BOAT;
            case GROUND -> MavType.GROUND_ROVER;
        };
        FlightMode m = autopilot.mode();
        long base = ModeFlag.CUSTOM_MODE_ENABLED.code() | ModeFlag.STABILIZE_ENABLED.code()
                | (s.armed() ? ModeFlag.SAFETY_ARMED.code() : 0)
                | (m == FlightMode.GUIDED ? ModeFlag.GUIDED_ENABLED.code() : 0)
                | (m == FlightMode.AUTO || m == FlightMode.RTL || m == FlightMode.LAND || m == FlightMode.TAKEOFF || m == FlightMode.HOLD
                ? ModeFlag.AUTO_ENABLED.code() | ModeFlag.GUIDED_ENABLED.code() : 0);
        return Payload.of(Messages.Heartbeat.MESSAGE)
                .set(Messages.Heartbeat.TYPE, type.code())
                .set(Messages.Heartbeat.AUTOPILOT, dialect.autopilot().code())
                .set(Messages.Heartbeat.BASE_MODE, base)
                .set(Messages.Heartbeat.CUSTOM_MODE, autopilot.customMode())
                .set(Messages.Heartbeat.SYSTEM_STATUS, (s.armed() ? MavState.ACTIVE : MavState.STANDBY).code())
                .set(Messages.Heartbeat.MAVLINK_VERSION, 3);
    }

    private Payload attitude(SimVehicle.Snapshot s, double time) {
        double dt = time - lastTime;
        double ax = dt > 0 ? (s.vx() - lastVx) / dt : 0;
        double ay = dt > 0 ? (s.vy() - lastVy) / dt : 0;
        lastVx = s.vx();
        lastVy = s.vy();
        lastTime = time;
        double forward = ax * Math.cos(s.heading()) + ay * Math.sin(s.heading());
        double left = -ax * Math.sin(s.heading()) + ay * Math.cos(s.heading());
        boolean flying = autopilot.medium() == VehicleDrive.Medium.AIR && !s.landed();
        // a multirotor tilts toward its acceleration: nose down to speed up, right wing down to go right
        double pitch = flying ? -Math.atan(forward / 9.81) : 0;
        double roll = flying ? Math.atan(-left / 9.81) : 0;
        return Payload.of(Messages.Attitude.MESSAGE)
                .set(Messages.Attitude.TIME_BOOT_MS, Math.round(time * 1000))
                .set(Messages.Attitude.ROLL, roll)
                .set(Messages.Attitude.PITCH, pitch)
                .set(Messages.Attitude.YAW, LocalFrame.yaw(s.heading()))
                .set(Messages.Attitude.YAWSPEED, -s.yawRate());
    }

    private List<Payload> distanceSensors(SimVehicle.Snapshot s, double time) {
        List<Payload> out = new ArrayList<>();
        int id = 0;
        if (autopilot.medium() == VehicleDrive.Medium.AIR) {
            out.add(distance(time, id++, SensorOrientation.PITCH_270, DistanceSensorType.LASER, 0.05, 40, s.z()));
        }
        for (SensorModel m : robot.rangeSensors()) {
            if (m.spec().position() == io.robomw.api.Position.BOTTOM) {
                continue;
            }
            DistanceSensorType type = m.spec().type() == io.robomw.api.SensorType.SONAR ? DistanceSensorType.ULTRASOUND
                    : m.spec().type() == io.robomw.api.SensorType.INFRARED ? DistanceSensorType.INFRARED : DistanceSensorType.LASER;
            out.add(distance(time, id++, SensorOrientation.NONE, type, m.minRange(), m.maxRange(), robot.latest(m)));
        }
        return out;
    }

    private static Payload distance(double time, int id, SensorOrientation orientation, DistanceSensorType type, double min, double max,
                                    double metres) {
        double clamped = Math.max(min, Math.min(max, metres));
        return Payload.of(Messages.DistanceSensor.MESSAGE)
                .set(Messages.DistanceSensor.TIME_BOOT_MS, Math.round(time * 1000))
                .set(Messages.DistanceSensor.MIN_DISTANCE, Math.round(min * 100))
                .set(Messages.DistanceSensor.MAX_DISTANCE, Math.round(max * 100))
                .set(Messages.DistanceSensor.CURRENT_DISTANCE, Math.round(clamped * 100))
                .set(Messages.DistanceSensor.TYPE, type.code())
                .set(Messages.DistanceSensor.ID, id)
                .set(Messages.DistanceSensor.ORIENTATION, orientation.code())
                .set(Messages.DistanceSensor.COVARIANCE, 255);
    }

    private Payload missionCurrent() {
        return Payload.of(Messages.MissionCurrent.MESSAGE)
                .set(Messages.MissionCurrent.SEQ, autopilot.currentItem())
                .set(Messages.MissionCurrent.TOTAL, autopilot.mission().size());
    }

    /**
     * @return AUTOPILOT_VERSION: capabilities, the firmware's version (ArduPilot 4.5.7, PX4 1.15.0, official)
     */
    Payload autopilotVersion() {
        long version = dialect == Dialect.PX4 ? (1L << 24 | 15L << 16 | 0 << 8 | 255) : (4L << 24 | 5L << 16 | 7L << 8 | 255);
        long caps = CAPABILITIES | (dialect == Dialect.PX4 ? PARAM_ENCODE_BYTEWISE : PARAM_ENCODE_C_CAST);
        return Payload.of(Messages.AutopilotVersion.MESSAGE)
                .set(Messages.AutopilotVersion.CAPABILITIES, caps)
                .set(Messages.AutopilotVersion.FLIGHT_SW_VERSION, version)
                .set(Messages.AutopilotVersion.VENDOR_ID, 0x1209)
                .set(Messages.AutopilotVersion.PRODUCT_ID, 0x5741)
                .set(Messages.AutopilotVersion.UID, 0x526F626F4D57L + robot.index());
    }

    private static long cdeg(double vx, double vy) {
        if (Math.hypot(vx, vy) < 0.05) {
            return 0;
        }
        return Math.round((Math.toDegrees(Math.atan2(vx, vy)) + 360) % 360 * 100) % 36000;
    }
}
