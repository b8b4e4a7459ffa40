package io.robomw.sim.emulator.mavlink;

import io.robomw.config.description.VehicleDrive;
import io.robomw.platform.mavlink.wire.MavCmd;
import io.robomw.platform.mavlink.wire.MavResult;
import io.robomw.platform.mavlink.wire.Severity;
import io.robomw.sim.vehicle.SimVehicle;
import io.robomw.sim.vehicle.VehicleTarget;

import java.util.ArrayDeque;
import java.util.ArrayList;
import java.util.Deque;
import java.util.List;
import java.util.Optional;
import java.util.function.BiConsumer;

/**
 * The emulated autopilot's behaviour (what ArduPilot and PX4 document, mavlink.md §1.4-1.5): its
 * mode, arming, the targets a ground station gives, and the guidance that turns them into the
 * simulated vehicle's velocity targets at every world step.
 *
 * <h2>Rules</h2>
 * <ul>
 *   <li><b>Arming</b>: allowed on the ground in any mode; disarming in flight is refused unless
 *   forced. A multirotor armed on the ground that does not take off within DISARM_DELAY (10 s)
 *   disarms itself; one that lands disarms.</li>
 *   <li><b>Take-off</b> (multirotors only; a boat or rover answers UNSUPPORTED, as Rover does):
 *   ArduPilot needs GUIDED and armed, and climbs to param7 (MAVSDK's 2 m by default); PX4 needs
 *   armed, climbs to param7 or, when it is NaN, to MIS_TAKEOFF_ALT in AUTO.TAKEOFF, then holds in
 *   AUTO.LOITER.</li>
 *   <li><b>Guided targets</b>: a position target stays until replaced; a velocity target lives
 *   for the guided timeout (ArduPilot 3 s, then the vehicle stops; a boat loiters where it is,
 *   saying "target not received last 3.0 secs, stopping").</li>
 *   <li><b>PX4 OFFBOARD</b>: entered only after setpoints have come for more than a second (at
 *   2 Hz or more); left for AUTO.LOITER when they stop for COM_OF_LOSS_T (1 s).</li>
 *   <li><b>Land</b> descends at LAND_SPEED (0.5 m/s) or MPC_LAND_SPEED (0.7 m/s) and disarms on
 *   the ground; <b>RTL</b> climbs to its altitude, goes home and lands (a boat or rover goes home
 *   and holds).</li>
 *   <li><b>AUTO</b> flies the mission: waypoints (reached within WPNAV_RADIUS, WP_RADIUS or
 *   NAV_ACC_RAD, each reported with MISSION_ITEM_REACHED), take-off, land, return to launch and
 *   loiter items; at its end the vehicle holds.</li>
 * </ul>
 *
 * <h2>Guidance</h2>
 * To a position as {@link io.robomw.sim.vehicle.Guidance} says; a multirotor turns to a yaw target
 * at {@code 2/s · yaw error} and keeps its yaw otherwise.
 *
 * <p>Not thread-safe: the simulation's thread only.
 */
final class Autopilot {

    /** Receives STATUSTEXTs: severity and text. */
    interface Announcer extends BiConsumer<Severity, String> {
    }

    private static final double POSITION_GAIN = io.robomw.sim.vehicle.Guidance.POSITION_GAIN;
    private static final double YAW_GAIN = io.robomw.sim.vehicle.Guidance.YAW_GAIN;
    private static final double TAKEOFF_REACHED = 0.1;
    private static final double OFFBOARD_STREAM_SECONDS = 1.0;
    private static final double OFFBOARD_MAX_GAP = 0.5;
    private static final double ARDUPILOT_LAND_SPEED = 0.5;

    private final SimVehicle vehicle;
    private final VehicleDrive drive;
    private final Dialect dialect;
    private final LocalFrame frame;
    private final ParameterTable params;
    private final Announcer announce;
    private final boolean air;

    private FlightMode mode;
    /** The custom mode HEARTBEAT reports: the one asked for (a mode held under another name keeps its number). */
    private long customMode;
    private double now;
    // guided targets, in the world's frame; NaN when absent
    private double[] position;
    private double[] velocity;
    private double surge = Double.NaN;
    private double yaw = Double.NaN;
    private double yawRate = Double.NaN;
    private double targetAt = Double.NEGATIVE_INFINITY;
    private boolean velocityExpired;
    private final double[] hold = new double[3];
    private double takeoffAltitude = Double.NaN;
    private double landedSince;
    private final Deque<Double> setpointTimes = new ArrayDeque<>();
    // the mission
    private final List<MissionItem> mission = new ArrayList<>();
    private int currentItem;
    private boolean missionChanged;
    private final List<Integer> reached = new ArrayList<>();

    /**
     * @param vehicle  the simulated vehicle
     * @param drive    its limits
     * @param dialect  ArduPilot or PX4
     * @param frame    its local frame
     * @param params   its parameters
     * @param announce where STATUSTEXTs go
     */
    Autopilot(SimVehicle vehicle, VehicleDrive drive, Dialect dialect, LocalFrame frame, ParameterTable params, Announcer announce) {
        this.vehicle = vehicle;
        this.drive = drive;
        this.dialect = dialect;
        this.frame = frame;
        this.params = params;
        this.announce = announce;
        this.air = drive.medium() == VehicleDrive.Medium.AIR;
        this.mode = dialect == Dialect.PX4 || !air ? FlightMode.HOLD : FlightMode.MANUAL;
        this.customMode = dialect.customMode(mode, drive.medium()).orElse(0L);
        SimVehicle.Snapshot s = vehicle.snapshot();
        holdHere(s);
    }

    // ---- state, for telemetry ----

    /** @return the flight mode */
    FlightMode mode() {
        return mode;
    }

    /** @return the custom mode HEARTBEAT reports */
    long customMode() {
        return customMode;
    }

    /** @return whether armed */
    boolean armed() {
        return vehicle.snapshot().armed();
    }

    /** @return the vehicle's medium */
    VehicleDrive.Medium medium() {
        return drive.medium();
    }

    /** @return the mission */
    List<MissionItem> mission() {
        return List.copyOf(mission);
    }

    /** @return the current mission item's seq */
    int currentItem() {
        return currentItem;
    }

    /** @return mission items reached since the last call (for MISSION_ITEM_REACHED), cleared */
    List<Integer> drainReached() {
        List<Integer> r = List.copyOf(reached);
        reached.clear();
        return r;
    }

    /** @return whether the current item changed since the last call (for MISSION_CURRENT), cleared */
    boolean drainMissionChanged() {
        boolean c = missionChanged;
        missionChanged = false;
        return c;
    }

    /** @return the local frame */
    LocalFrame frame() {
        return frame;
    }

    private void holdHere(SimVehicle.Snapshot s) {
        hold[0] = s.x();
        hold[1] = s.y();
        hold[2] = s.z();
    }

    // ---- commands: each returns the MAV_RESULT a COMMAND_ACK carries ----

    /**
     * @param arm   true to arm, false to disarm
     * @param force whether the command said 21196 (force)
     * @return the result
     */
    MavResult arm(boolean arm, boolean force) {
        SimVehicle.Snapshot s = vehicle.snapshot();
        if (arm) {
            if (!s.armed()) {
                vehicle.arm();
                landedSince = now;
                holdHere(s);
                announce.accept(Severity.INFO, dialect == Dialect.PX4 ? "Armed by external command" : "Arming motors");
            }
            return MavResult.ACCEPTED;
        }
        if (air && !s.landed() && !force) {
            announce.accept(Severity.CRITICAL, dialect == Dialect.PX4 ? "Disarming denied: not landed" : "Disarm: not landed");
            return MavResult.DENIED;
        }
        disarm();
        return MavResult.ACCEPTED;
    }

    private void disarm() {
        if (vehicle.snapshot().armed()) {
            vehicle.disarm();
            announce.accept(Severity.INFO, dialect == Dialect.PX4 ? "Disarmed by external command" : "Disarming motors");
        }
        takeoffAltitude = Double.NaN;
    }

    /**
     * @param requested the mode asked for
     * @return the result: DENIED for a mode this vehicle does not have, TEMPORARILY_REJECTED for
     *         PX4 OFFBOARD without a setpoint stream, AUTO without a mission
     */
    MavResult setMode(FlightMode requested) {
        return setMode(requested, dialect.customMode(requested, drive.medium()).orElse(-1L));
    }

    /**
     * @param requested the mode asked for
     * @param number    the custom mode number that asked for it (HEARTBEAT reports it)
     * @return as {@link #setMode(FlightMode)}
     */
    MavResult setMode(FlightMode requested, long number) {
        if (dialect.customMode(requested, drive.medium()).isEmpty() || number < 0) {
            return MavResult.DENIED;
        }
        if (requested == mode) {
            customMode = number;
            return MavResult.ACCEPTED;
        }
        SimVehicle.Snapshot s = vehicle.snapshot();
        if (requested == FlightMode.GUIDED && dialect == Dialect.PX4 && !offboardStreamReady()) {
            announce.accept(Severity.CRITICAL, "Switching to Offboard is currently not available: no offboard signal");
            return MavResult.TEMPORARILY_REJECTED;
        }
        if (requested == FlightMode.AUTO && navigationItems() == 0) {
            announce.accept(Severity.CRITICAL, dialect == Dialect.PX4 ? "Mission rejected: no mission" : "Mode change to AUTO failed: no mission");
            return MavResult.TEMPORARILY_REJECTED;
        }
        if ((requested == FlightMode.TAKEOFF || requested == FlightMode.LAND) && !air) {
            return MavResult.DENIED;
        }
        enter(requested, s);
        customMode = number;
        return MavResult.ACCEPTED;
    }

    private void enter(FlightMode m, SimVehicle.Snapshot s) {
        mode = m;
        customMode = dialect.customMode(m, drive.medium()).orElse(customMode);
        holdHere(s);
        position = null;
        velocity = null;
        surge = Double.NaN;
        yaw = Double.NaN;
        yawRate = Double.NaN;
        if (m != FlightMode.TAKEOFF && !(m == FlightMode.GUIDED && !Double.isNaN(takeoffAltitude))) {
            takeoffAltitude = Double.NaN;
        }
        if (m == FlightMode.AUTO) {
            currentItem = firstNavigationItem();
            missionChanged = true;
            startItem(s);
        }
    }

    /**
     * @param altitude param7, metres above home; NaN for the default
     * @return the result
     */
    MavResult takeoff(double altitude) {
        if (!air) {
            return MavResult.UNSUPPORTED;
        }
        SimVehicle.Snapshot s = vehicle.snapshot();
        if (!s.armed()) {
            announce.accept(Severity.CRITICAL, dialect == Dialect.PX4 ? "Takeoff denied: disarmed" : "Takeoff: not armed");
            return dialect == Dialect.PX4 ? MavResult.DENIED : MavResult.FAILED;
        }
        if (!s.landed()) {
            return dialect == Dialect.PX4 ? MavResult.DENIED : MavResult.FAILED;
        }
        double alt;
        if (dialect == Dialect.PX4) {
            alt = Double.isFinite(altitude) && altitude > 0 ? altitude : params.value("MIS_TAKEOFF_ALT");
            enter(FlightMode.TAKEOFF, s);
        } else {
            if (mode != FlightMode.GUIDED) {
                announce.accept(Severity.CRITICAL, "Takeoff: not in GUIDED mode");
                return MavResult.FAILED;
            }
            alt = Double.isFinite(altitude) && altitude > 0 ? altitude : drive.takeoffAltitude();
            holdHere(s);
        }
        takeoffAltitude = alt;
        announce.accept(Severity.INFO, String.format(java.util.Locale.ROOT, "Takeoff to %.1f m", alt));
        return MavResult.ACCEPTED;
    }

    /** @return the result of NAV_LAND: LAND mode (UNSUPPORTED on a boat or rover) */
    MavResult land() {
        if (!air) {
            return MavResult.UNSUPPORTED;
        }
        enter(FlightMode.LAND, vehicle.snapshot());
        return MavResult.ACCEPTED;
    }

    /** @return the result of NAV_RETURN_TO_LAUNCH */
    MavResult returnToLaunch() {
        enter(FlightMode.RTL, vehicle.snapshot());
        return MavResult.ACCEPTED;
    }

    /** @return the result of MISSION_START */
    MavResult startMission() {
        return setMode(FlightMode.AUTO);
    }

    /**
     * CONDITION_YAW.
     *
     * @param degrees  the angle
     * @param direction -1 anti-clockwise, 1 clockwise, 0 shortest
     * @param relative whether the angle is relative to the current yaw
     * @return the result (GUIDED only, as ArduPilot)
     */
    MavResult conditionYaw(double degrees, double direction, boolean relative) {
        if (mode != FlightMode.GUIDED || !Double.isFinite(degrees)) {
            return mode != FlightMode.GUIDED ? MavResult.TEMPORARILY_REJECTED : MavResult.DENIED;
        }
        double heading = vehicle.snapshot().heading();
        double mavYaw = relative ? LocalFrame.yaw(heading) + Math.toRadians(degrees) * (direction < 0 ? -1 : 1) : Math.toRadians(degrees);
        yaw = LocalFrame.heading(mavYaw);
        yawRate = Double.NaN;
        targetAt = now;
        return MavResult.ACCEPTED;
    }

    /**
     * A setpoint (SET_POSITION_TARGET_LOCAL_NED), already in the world's frame: a position (with
     * NaN z for "keep the altitude"), or a velocity, with a yaw or yaw rate.
     *
     * @param pos    world x, y, z, or {@code null}
     * @param vel    world vx, vy, vz, or {@code null}
     * @param bodySurge for a boat or rover given a yaw rate: the speed along its heading (NaN otherwise)
     * @param yawTarget world heading, or NaN
     * @param rate   yaw rate (anti-clockwise), or NaN
     */
    void setpoint(double[] pos, double[] vel, double bodySurge, double yawTarget, double rate) {
        setpointTimes.addLast(now);
        while (setpointTimes.size() > 200 || (setpointTimes.size() > 1 && now - setpointTimes.peekFirst() > 3)) {
            setpointTimes.removeFirst();
        }
        if (mode != FlightMode.GUIDED) {
            return; // PX4 streams before OFFBOARD; ArduPilot ignores targets outside GUIDED
        }
        if (pos != null) {
            position = pos.clone();
            if (Double.isNaN(position[2])) {
                position[2] = vehicle.snapshot().z();
            }
            velocity = null;
            surge = Double.NaN;
        } else if (vel != null) {
            velocity = vel.clone();
            surge = bodySurge;
            position = null;
            velocityExpired = false;
        }
        yaw = yawTarget;
        yawRate = rate;
        targetAt = now;
        takeoffAltitude = pos == null && vel == null ? takeoffAltitude : Double.NaN;
    }

    private boolean offboardStreamReady() {
        if (setpointTimes.isEmpty() || now - setpointTimes.peekLast() > OFFBOARD_MAX_GAP) {
            return false;
        }
        double previous = setpointTimes.peekLast();
        java.util.Iterator<Double> it = setpointTimes.descendingIterator();
        double first = previous;
        while (it.hasNext()) {
            double t = it.next();
            if (previous - t > OFFBOARD_MAX_GAP) {
                break;
            }
            first = t;
            previous = t;
        }
        return now - first >= OFFBOARD_STREAM_SECONDS;
    }

    // ---- the mission ----

    /**
     * @param items a mission just uploaded
     */
    void mission(List<MissionItem> items) {
        mission.clear();
        mission.addAll(items);
        currentItem = firstNavigationItem();
        missionChanged = true;
        if (mode == FlightMode.AUTO) {
            enter(FlightMode.HOLD, vehicle.snapshot());
        }
    }

    /**
     * @param seq the item to go on from
     * @return whether there is such an item
     */
    boolean setCurrentItem(int seq) {
        if (seq < 0 || seq >= mission.size()) {
            return false;
        }
        currentItem = seq;
        missionChanged = true;
        if (mode == FlightMode.AUTO) {
            startItem(vehicle.snapshot());
        }
        return true;
    }

    private int firstNavigationItem() {
        // ArduPilot keeps home at item 0
        return dialect == Dialect.ARDUPILOT && !mission.isEmpty() ? Math.min(1, mission.size() - 1) : 0;
    }

    private int navigationItems() {
        return Math.max(0, mission.size() - (dialect == Dialect.ARDUPILOT ? 1 : 0));
    }

    private void startItem(SimVehicle.Snapshot s) {
        if (currentItem >= mission.size()) {
            return;
        }
        MissionItem item = mission.get(currentItem);
        if (item.command() == MavCmd.NAV_TAKEOFF.code() && air) {
            takeoffAltitude = item.z() > 0 ? item.z() : drive.takeoffAltitude();
            holdHere(s);
        }
    }

    // ---- every step ----

    /**
     * Advances the autopilot to a time and sets the vehicle's targets.
     *
     * @param time simulated seconds since the emulator started
     */
    void step(double time) {
        now = time;
        SimVehicle.Snapshot s = vehicle.snapshot();
        if (!s.armed()) {
            vehicle.target(VehicleTarget.HOLD);
            return;
        }
        if (air && s.landed()) {
            boolean climbing = (mode == FlightMode.TAKEOFF || mode == FlightMode.GUIDED || mode == FlightMode.AUTO)
                    && (!Double.isNaN(takeoffAltitude) || (position != null && position[2] > 0.05) || (velocity != null && velocity[2] > 0));
            if (mode == FlightMode.LAND) {
                disarm();
                announce.accept(Severity.INFO, "Landed");
                vehicle.target(VehicleTarget.HOLD);
                return;
            }
            if (!climbing && now - landedSince > params.value(dialect == Dialect.PX4 ? "COM_DISARM_PRFLT" : "DISARM_DELAY")) {
                disarm();
                announce.accept(Severity.INFO, "Disarming: no take-off");
                vehicle.target(VehicleTarget.HOLD);
                return;
            }
        } else {
            landedSince = now;
        }
        vehicle.target(switch (mode) {
            case MANUAL -> air ? new VehicleTarget(0, 0, 0, 0) : VehicleTarget.HOLD;
            case GUIDED -> guided(s);
            case HOLD -> holdAt(s);
            case TAKEOFF -> climbTo(s);
            case LAND -> descend(s);
            case RTL -> returnHome(s);
            case AUTO -> auto(s);
        });
    }

    private VehicleTarget guided(SimVehicle.Snapshot s) {
        if (dialect == Dialect.PX4 && now - targetAt > params.value("COM_OF_LOSS_T") && lastSetpointAge() > params.value("COM_OF_LOSS_T")) {
            announce.accept(Severity.CRITICAL, "Failsafe: offboard control lost, holding position");
            enter(FlightMode.HOLD, s);
            return holdAt(s);
        }
        if (!Double.isNaN(takeoffAltitude)) {
            return climbTo(s);
        }
        if (position != null) {
            return goTo(s, position[0], position[1], position[2], drive.acceptanceRadius());
        }
        if (velocity != null) {
            if (now - targetAt <= dialect.targetTimeoutSeconds()) {
                return fly(s);
            }
            if (!velocityExpired) {
                velocityExpired = true;
                holdHere(s);
                if (!air && dialect == Dialect.ARDUPILOT) {
                    announce.accept(Severity.WARNING, String.format(java.util.Locale.ROOT, "target not received last %.1f secs, stopping",
                            dialect.targetTimeoutSeconds()));
                }
            }
        }
        return holdAt(s);
    }

    private double lastSetpointAge() {
        return setpointTimes.isEmpty() ? Double.POSITIVE_INFINITY : now - setpointTimes.peekLast();
    }

    private VehicleTarget fly(SimVehicle.Snapshot s) {
        double rate = turnRate(s);
        if (air) {
            return new VehicleTarget(velocity[0], velocity[1], velocity[2], rate);
        }
        double forward = !Double.isNaN(surge) ? surge : Math.hypot(velocity[0], velocity[1]);
        if (Double.isNaN(surge) && forward > 0.05 && Double.isNaN(yaw) && Double.isNaN(yawRate)) {
            double err = LocalFrame.normalize(Math.atan2(velocity[1], velocity[0]) - s.heading());
            rate = clamp(YAW_GAIN * err, drive.maxTurnRate());
            forward *= Math.max(0, Math.cos(err));
        }
        return new VehicleTarget(forward * Math.cos(s.heading()), forward * Math.sin(s.heading()), 0, rate);
    }

    private double turnRate(SimVehicle.Snapshot s) {
        if (!Double.isNaN(yawRate)) {
            return clamp(yawRate, drive.maxTurnRate());
        }
        if (!Double.isNaN(yaw)) {
            return clamp(YAW_GAIN * LocalFrame.normalize(yaw - s.heading()), drive.maxTurnRate());
        }
        return 0;
    }

    private VehicleTarget holdAt(SimVehicle.Snapshot s) {
        if (!air && drive.medium() == VehicleDrive.Medium.GROUND) {
            return new VehicleTarget(0, 0, 0, turnRate(s));
        }
        double radius = air ? drive.acceptanceRadius() : params.value(dialect == Dialect.PX4 ? "NAV_ACC_RAD" : "LOIT_RADIUS");
        return goTo(s, hold[0], hold[1], hold[2], radius);
    }

    private VehicleTarget climbTo(SimVehicle.Snapshot s) {
        if (s.z() >= takeoffAltitude - TAKEOFF_REACHED) {
            double alt = takeoffAltitude;
            takeoffAltitude = Double.NaN;
            hold[2] = alt;
            if (mode == FlightMode.TAKEOFF) {
                enter(FlightMode.HOLD, s);
                hold[2] = alt;
            } else if (mode == FlightMode.GUIDED) {
                position = new double[]{hold[0], hold[1], alt};
            } else if (mode == FlightMode.AUTO) {
                itemReached(s);
            }
            return goTo(s, hold[0], hold[1], alt, drive.acceptanceRadius());
        }
        return new VehicleTarget(POSITION_GAIN * (hold[0] - s.x()), POSITION_GAIN * (hold[1] - s.y()), drive.maxClimbRate(), turnRate(s));
    }

    private VehicleTarget descend(SimVehicle.Snapshot s) {
        double speed = dialect == Dialect.PX4 ? params.value("MPC_LAND_SPEED") : ARDUPILOT_LAND_SPEED;
        return new VehicleTarget(POSITION_GAIN * (hold[0] - s.x()), POSITION_GAIN * (hold[1] - s.y()), -speed, 0);
    }

    private VehicleTarget returnHome(SimVehicle.Snapshot s) {
        double homeX = frame.x0();
        double homeY = frame.y0();
        if (!air) {
            if (Math.hypot(homeX - s.x(), homeY - s.y()) < drive.acceptanceRadius()) {
                enter(FlightMode.HOLD, s);
            }
            return goTo(s, homeX, homeY, 0, drive.acceptanceRadius());
        }
        double rtlAlt = dialect == Dialect.PX4 ? params.value("RTL_RETURN_ALT") : params.value("RTL_ALT") / 100;
        double alt = Math.max(s.z(), rtlAlt);
        if (s.z() < rtlAlt - 0.2 && Math.hypot(homeX - s.x(), homeY - s.y()) > drive.acceptanceRadius()) {
            return new VehicleTarget(0, 0, drive.maxClimbRate(), 0);
        }
        if (Math.hypot(homeX - s.x(), homeY - s.y()) < drive.acceptanceRadius()) {
            enter(FlightMode.LAND, s);
            return descend(s);
        }
        return goTo(s, homeX, homeY, alt, drive.acceptanceRadius());
    }

    private VehicleTarget auto(SimVehicle.Snapshot s) {
        if (currentItem >= mission.size()) {
            enter(FlightMode.HOLD, s);
            return holdAt(s);
        }
        MissionItem item = mission.get(currentItem);
        MavCmd cmd = MavCmd.find(item.command()).orElse(null);
        if (cmd == null) {
            itemReached(s);
            return holdAt(s);
        }
        return switch (cmd) {
            case NAV_TAKEOFF -> {
                if (!air) {
                    itemReached(s);
                    yield holdAt(s);
                }
                if (Double.isNaN(takeoffAltitude)) {
                    takeoffAltitude = item.z() > 0 ? item.z() : drive.takeoffAltitude();
                }
                yield climbTo(s);
            }
            case NAV_WAYPOINT -> {
                double x = itemX(item);
                double y = itemY(item);
                double z = air ? item.z() : 0;
                double radius = item.param2() > 0 ? item.param2() : waypointRadius();
                if (Math.hypot(x - s.x(), y - s.y()) <= radius && (!air || Math.abs(z - s.z()) < 0.5)) {
                    itemReached(s);
                }
                yield goTo(s, x, y, z, radius);
            }
            case NAV_LAND -> {
                if (air && !s.landed()) {
                    yield descend(s);
                }
                itemReached(s);
                yield holdAt(s);
            }
            case NAV_RETURN_TO_LAUNCH -> {
                enter(FlightMode.RTL, s);
                yield returnHome(s);
            }
            case NAV_LOITER_UNLIM -> holdAt(s);
            default -> {
                itemReached(s);
                yield holdAt(s);
            }
        };
    }

    private double waypointRadius() {
        if (dialect == Dialect.PX4) {
            return params.value("NAV_ACC_RAD");
        }
        return air ? params.value("WPNAV_RADIUS") / 100 : params.value("WP_RADIUS");
    }

    private double itemX(MissionItem item) {
        return isGlobal(item.frame()) ? frame.worldXOf(item.y() / 1e7) : frame.worldX(item.y());
    }

    private double itemY(MissionItem item) {
        return isGlobal(item.frame()) ? frame.worldYOf(item.x() / 1e7) : frame.worldY(item.x());
    }

    private static boolean isGlobal(int frameCode) {
        return frameCode == 0 || frameCode == 3 || frameCode == 5 || frameCode == 6;
    }

    private void itemReached(SimVehicle.Snapshot s) {
        reached.add(currentItem);
        holdHere(s);
        currentItem++;
        missionChanged = true;
        takeoffAltitude = Double.NaN;
        if (currentItem >= mission.size()) {
            announce.accept(Severity.INFO, "Mission complete");
            enter(FlightMode.HOLD, s);
        } else {
            startItem(s);
        }
    }

    /** Guidance to a position ({@link io.robomw.sim.vehicle.Guidance}). */
    private VehicleTarget goTo(SimVehicle.Snapshot s, double x, double y, double z, double radius) {
        return io.robomw.sim.vehicle.Guidance.goTo(s, drive.medium(), drive.maxSpeed(), drive.maxClimbRate(), drive.maxTurnRate(), x, y, z,
                radius, turnRate(s));
    }

    private static double clamp(double v, double max) {
        return Math.max(-max, Math.min(max, v));
    }

    /** @return where it holds or the target it flies to, for POSITION_TARGET-style reports (world frame) */
    Optional<double[]> positionTarget() {
        return Optional.ofNullable(position).map(double[]::clone);
    }
}
