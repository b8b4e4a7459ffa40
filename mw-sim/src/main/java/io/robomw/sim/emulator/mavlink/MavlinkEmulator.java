package io.robomw.sim.emulator.mavlink;

import io.robomw.api.spi.FailurePolicy;
import io.robomw.api.spi.OwnerThread;
import io.robomw.config.description.VehicleDrive;
import io.robomw.platform.ThrottledWarnings;
import io.robomw.platform.mavlink.link.MavlinkLink;
import io.robomw.platform.mavlink.link.UdpMavlinkLink;
import io.robomw.platform.mavlink.wire.CoordinateFrame;
import io.robomw.platform.mavlink.wire.Frame;
import io.robomw.platform.mavlink.wire.FrameEncoder;
import io.robomw.platform.mavlink.wire.MavCmd;
import io.robomw.platform.mavlink.wire.MavResult;
import io.robomw.platform.mavlink.wire.Messages;
import io.robomw.platform.mavlink.wire.ModeFlag;
import io.robomw.platform.mavlink.wire.Payload;
import io.robomw.platform.mavlink.wire.Severity;
import io.robomw.platform.mavlink.wire.SignatureCheck;
import io.robomw.platform.mavlink.wire.Signer;
import io.robomw.platform.mavlink.wire.SigningKey;
import io.robomw.platform.mavlink.wire.TypeMask;
import io.robomw.sim.SimRobot;
import io.robomw.sim.Simulation;
import io.robomw.sim.emulator.Emulator;
import io.robomw.sim.vehicle.SimVehicle;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.io.IOException;
import java.net.InetSocketAddress;
import java.net.SocketAddress;
import java.time.Duration;
import java.time.InstantSource;
import java.util.List;
import java.util.Optional;
import java.util.concurrent.ArrayBlockingQueue;
import java.util.concurrent.BlockingQueue;
import java.util.concurrent.CopyOnWriteArrayList;
import java.util.concurrent.atomic.AtomicLong;

/**
 * A MAVLink vehicle for one vehicle of a simulated world, as ArduPilot (ArduCopter, Rover) or PX4
 * documents it: ground stations (QGroundControl, MAVProxy, MAVSDK, pymavlink, RoboMW's own
 * {@code platform: mavlink}) connect over UDP and fly the simulated multirotor, boat or rover.
 *
 * <h2>Links</h2>
 * {@link #listen} answers whoever sends to its port; {@link #sendTo} sends to a ground station's
 * address as SITL's {@code --out} does (and hears what comes back); both may run at once. Every
 * frame goes out on every link, from system 1, component 1 (MAV_COMP_ID_AUTOPILOT1).
 *
 * <h2>What it does</h2>
 * Its {@link Autopilot} holds the mode, arming, guided targets and mission; {@link Telemetry}
 * streams what clients read; {@link MissionTransfer} uploads and downloads missions;
 * {@link ParameterTable} answers PARAM_REQUEST_LIST, PARAM_REQUEST_READ and PARAM_SET. Commands
 * (COMMAND_LONG, COMMAND_INT) are answered with COMMAND_ACK addressed to their sender's system and
 * component; unset parameters may be NaN (as MAVSDK sends them to PX4). Messages addressed to
 * another system are ignored.
 *
 * <h2>Signing</h2>
 * With a key ({@link #signing}, or SETUP_SIGNING from a ground station while none is set), every
 * frame it sends is signed, and every frame it receives must be signed with that key and new:
 * unsigned frames, wrong signatures and replays are dropped and counted ({@link #refused()}), as
 * ArduPilot does (but RADIO_STATUS, which radios send unsigned). A signed SETUP_SIGNING with an
 * all-zero key and timestamp turns signing off.
 *
 * <h2>Threads</h2>
 * One reader thread per link ({@code emulator-mavlink-<robot>-<n>}) cuts frames, checks
 * signatures and queues them; the simulation's thread, after every world step, handles the queue,
 * steps the autopilot and sends what is due, so every decision is taken on simulated time. Bad
 * bytes are skipped by the decoder; a message the autopilot cannot use is ignored; nothing a client
 * sends stops the emulator.
 */
public final class MavlinkEmulator implements Emulator {

    private static final Logger LOG = LoggerFactory.getLogger(MavlinkEmulator.class);
    /** The system id of the emulated vehicle. */
    public static final int SYSTEM_ID = 1;
    /** Its component id: MAV_COMP_ID_AUTOPILOT1. */
    public static final int COMPONENT_ID = 1;
    /** Messages that may wait for the next world step. */
    static final int QUEUE = 4096;
    /** The magic number of a forced arm or disarm (param2 of COMPONENT_ARM_DISARM). */
    static final int FORCE = 21196;
    private static final Duration RECEIVE_SLICE = Duration.ofMillis(100);

    private final Simulation simulation;
    private final SimRobot robot;
    private final SimVehicle vehicle;
    private final Dialect dialect;
    private final Autopilot autopilot;
    private final Telemetry telemetry;
    private final MissionTransfer missions;
    private final ParameterTable params;
    private final FrameEncoder encoder = new FrameEncoder(SYSTEM_ID, COMPONENT_ID);
    private final BlockingQueue<Received> inbox = new ArrayBlockingQueue<>(QUEUE);
    private final List<MavlinkLink> links = new CopyOnWriteArrayList<>();
    private final List<OwnerThread> readers = new CopyOnWriteArrayList<>();
    private final Runnable stepListener = this::onStep;
    private final double startTime;
    private final FailurePolicy failures;
    private final ThrottledWarnings warnings = new ThrottledWarnings(LOG, Duration.ofSeconds(5), io.robomw.api.Clock.system());
    private final AtomicLong refused = new AtomicLong();
    private final AtomicLong handled = new AtomicLong();
    private volatile SignatureCheck check;
    private volatile boolean closed;
    private boolean unbound;

    /** A frame waiting for the simulation's thread. */
    private record Received(Frame frame, SocketAddress from) {
    }

    private MavlinkEmulator(Simulation simulation, SimRobot robot, VehicleDrive drive, Dialect dialect, FailurePolicy failures) {
        this.simulation = simulation;
        this.robot = robot;
        this.vehicle = robot.vehicle();
        this.dialect = dialect;
        this.failures = failures;
        this.startTime = simulation.world().time();
        SimVehicle.Snapshot s = vehicle.snapshot();
        LocalFrame frame = new LocalFrame(simulation.world().description().surroundings().home(), s.x(), s.y());
        this.params = new ParameterTable(dialect, drive);
        this.autopilot = new Autopilot(vehicle, drive, dialect, frame, params, this::statusText);
        this.telemetry = new Telemetry(robot, autopilot, dialect);
        this.missions = new MissionTransfer(autopilot, this::send);
    }

    /**
     * Binds an emulator to a vehicle of a simulation and steps it with the world.
     *
     * @param simulation the simulation (the robot should be one it emulates: {@code Simulation.load(world, names)})
     * @param robotName  the vehicle
     * @param autopilot  the dialect; empty for the robot file's
     * @param failures   where the reader threads report what they catch
     * @return the emulator, not yet on a link: call {@link #listen} or {@link #sendTo}
     * @throws IllegalArgumentException if the world has no such robot or it is not a vehicle
     */
    public static MavlinkEmulator bind(Simulation simulation, String robotName, Optional<VehicleDrive.Autopilot> autopilot,
                                       FailurePolicy failures) {
        SimRobot r = simulation.world().robot(robotName);
        if (r == null) {
            throw new IllegalArgumentException("world '" + simulation.world().description().name() + "' has no robot '" + robotName + "'");
        }
        VehicleDrive drive = r.description().vehicleDrive().orElseThrow(() -> new IllegalArgumentException("robot '" + robotName + "' ("
                + r.description().source() + ") is not a vehicle (drive: {type: vehicle, medium: air|water|ground}); the MAVLink emulator"
                + " flies a simulated multirotor, boat or rover"));
        MavlinkEmulator e = new MavlinkEmulator(simulation, r, drive, Dialect.of(autopilot.orElse(drive.autopilot())), failures);
        simulation.addStepListener(e.stepListener);
        return e;
    }

    /**
     * Signs everything from now on, and accepts only frames signed with this key.
     *
     * @param key the key (a passphrase's SHA-256, {@link SigningKey#fromPassphrase})
     * @return this
     */
    public MavlinkEmulator signing(SigningKey key) {
        encoder.signWith(new Signer(key, 0, InstantSource.system()));
        check = new SignatureCheck(key, InstantSource.system());
        return this;
    }

    /** @return the autopilot's dialect: {@code ardupilot} or {@code px4} */
    public String dialect() {
        return dialect.name().toLowerCase(java.util.Locale.ROOT);
    }

    /**
     * Listens on a UDP port and answers whoever sends to it.
     *
     * @param bind the address and port (port 0: any free one)
     * @return the address it listens on
     * @throws IOException if it cannot bind
     */
    public InetSocketAddress listen(InetSocketAddress bind) throws IOException {
        UdpMavlinkLink link = UdpMavlinkLink.listen(bind, System::nanoTime);
        start(link);
        LOG.info("MAVLink emulator ({}) for '{}' listening on {}", dialect(), robot.name(), link.describe());
        return link.localAddress();
    }

    /**
     * Sends to a ground station's address (as ArduPilot SITL's {@code --out}) and hears its answers.
     *
     * @param gcs the ground station's address
     * @return the local address it sends from
     * @throws IOException if no socket can be had
     */
    public InetSocketAddress sendTo(InetSocketAddress gcs) throws IOException {
        UdpMavlinkLink link = UdpMavlinkLink.sendTo(gcs, System::nanoTime);
        start(link);
        LOG.info("MAVLink emulator ({}) for '{}' sending to {}", dialect(), robot.name(), link.describe());
        return link.localAddress();
    }

    /**
     * Serves on a link of the caller's (a pseudo-terminal's master, in tests of a serial driver).
     *
     * @param link the link; closed with the emulator
     */
    public void serve(MavlinkLink link) {
        start(link);
    }

    private synchronized void start(MavlinkLink link) {
        if (closed) {
            link.close();
            throw new IllegalStateException("the MAVLink emulator of '" + robot.name() + "' is closed");
        }
        links.add(link);
        String role = "emulator-mavlink-" + robot.name() + "-" + links.size();
        readers.add(OwnerThread.start(role, Thread.NORM_PRIORITY, () -> link.receive(RECEIVE_SLICE, this::receive), work -> {
        }, failures));
    }

    /** On a reader thread: checks the signature and queues the frame for the next step. */
    private void receive(Frame f, SocketAddress from) {
        SignatureCheck c = check;
        if (c != null) {
            SignatureCheck.Verdict v = c.check(f);
            if (v != SignatureCheck.Verdict.ACCEPTED && !(v == SignatureCheck.Verdict.UNSIGNED && f.is(Messages.RadioStatus.MESSAGE))) {
                refused.incrementAndGet();
                warnings.warn("MAVLink emulator for '{}': dropped {} from {}: {}", robot.name(), f, from, v);
                return;
            }
        }
        if (!inbox.offer(new Received(f, from))) {
            warnings.warn("MAVLink emulator for '{}': {} messages wait for the simulation; dropped {}", robot.name(), QUEUE, f);
        }
    }

    /** @return frames dropped for their signature (unsigned, wrong, replayed) since it started */
    public long refused() {
        return refused.get();
    }

    /** @return frames handled since it started */
    public long handled() {
        return handled.get();
    }

    private double now() {
        return simulation.world().time() - startTime;
    }

    /** After every world step, on the simulation's thread. */
    private void onStep() {
        if (closed) {
            if (!unbound) {
                unbound = true;
                vehicle.target(io.robomw.sim.vehicle.VehicleTarget.HOLD);
                simulation.removeStepListener(stepListener);
            }
            return;
        }
        double t = now();
        for (Received r; (r = inbox.poll()) != null; ) {
            try {
                handle(r.frame(), t);
                handled.incrementAndGet();
            } catch (RuntimeException e) {
                // A message the autopilot cannot use (a value out of any range) is ignored, as the firmware does.
                warnings.warn("MAVLink emulator for '{}': ignored {}: {}", robot.name(), r.frame(), e.toString());
            }
        }
        autopilot.step(t);
        missions.step(t);
        for (Payload p : telemetry.due(t)) {
            send(p);
        }
    }

    private void send(Payload p) {
        byte[] frame = encoder.encode(p);
        for (MavlinkLink link : links) {
            try {
                link.send(frame);
            } catch (IOException e) {
                if (!closed) {
                    warnings.warn("MAVLink emulator for '{}': sending on {} failed: {}", robot.name(), link.describe(), e.getMessage());
                }
            }
        }
    }

    private void statusText(Severity severity, String text) {
        send(Payload.of(Messages.Statustext.MESSAGE).set(Messages.Statustext.SEVERITY, severity.code()).setText(Messages.Statustext.TEXT, text));
    }

    private static boolean forUs(long targetSystem, long targetComponent) {
        return (targetSystem == 0 || targetSystem == SYSTEM_ID) && (targetComponent == 0 || targetComponent == COMPONENT_ID);
    }

    private void handle(Frame f, double t) {
        Payload p = f.payload();
        if (f.is(Messages.CommandLong.MESSAGE)) {
            if (forUs(p.getLong(Messages.CommandLong.TARGET_SYSTEM), p.getLong(Messages.CommandLong.TARGET_COMPONENT))) {
                int command = (int) p.getLong(Messages.CommandLong.COMMAND);
                double[] params = {p.getDouble(Messages.CommandLong.PARAM1), p.getDouble(Messages.CommandLong.PARAM2),
                        p.getDouble(Messages.CommandLong.PARAM3), p.getDouble(Messages.CommandLong.PARAM4),
                        p.getDouble(Messages.CommandLong.PARAM5), p.getDouble(Messages.CommandLong.PARAM6),
                        p.getDouble(Messages.CommandLong.PARAM7)};
                ack(f, command, command(command, params, t));
            }
        } else if (f.is(Messages.CommandInt.MESSAGE)) {
            if (forUs(p.getLong(Messages.CommandInt.TARGET_SYSTEM), p.getLong(Messages.CommandInt.TARGET_COMPONENT))) {
                int command = (int) p.getLong(Messages.CommandInt.COMMAND);
                double[] params = {p.getDouble(Messages.CommandInt.PARAM1), p.getDouble(Messages.CommandInt.PARAM2),
                        p.getDouble(Messages.CommandInt.PARAM3), p.getDouble(Messages.CommandInt.PARAM4),
                        p.getLong(Messages.CommandInt.X), p.getLong(Messages.CommandInt.Y), p.getDouble(Messages.CommandInt.Z)};
                ack(f, command, command(command, params, t));
            }
        } else if (f.is(Messages.SetMode.MESSAGE)) {
            if (p.getLong(Messages.SetMode.TARGET_SYSTEM) == SYSTEM_ID) {
                MavResult r = mode(p.getLong(Messages.SetMode.CUSTOM_MODE));
                ack(f, Messages.SetMode.MESSAGE.id(), r);
            }
        } else if (f.is(Messages.SetPositionTargetLocalNed.MESSAGE)) {
            if (forUs(p.getLong(Messages.SetPositionTargetLocalNed.TARGET_SYSTEM), p.getLong(Messages.SetPositionTargetLocalNed.TARGET_COMPONENT))) {
                localSetpoint(p);
            }
        } else if (f.is(Messages.SetPositionTargetGlobalInt.MESSAGE)) {
            if (forUs(p.getLong(Messages.SetPositionTargetGlobalInt.TARGET_SYSTEM), p.getLong(Messages.SetPositionTargetGlobalInt.TARGET_COMPONENT))) {
                globalSetpoint(p);
            }
        } else if (f.is(Messages.ParamRequestList.MESSAGE)) {
            if (p.getLong(Messages.ParamRequestList.TARGET_SYSTEM) == SYSTEM_ID) {
                for (int i = 0; i < params.count(); i++) {
                    send(paramValue(params.at(i).orElseThrow()));
                }
            }
        } else if (f.is(Messages.ParamRequestRead.MESSAGE)) {
            if (p.getLong(Messages.ParamRequestRead.TARGET_SYSTEM) == SYSTEM_ID) {
                long index = p.getLong(Messages.ParamRequestRead.PARAM_INDEX);
                Optional<ParameterTable.Parameter> param = index >= 0 ? params.at((int) index)
                        : params.named(p.getText(Messages.ParamRequestRead.PARAM_ID));
                param.ifPresent(q -> send(paramValue(q)));
            }
        } else if (f.is(Messages.ParamSet.MESSAGE)) {
            if (p.getLong(Messages.ParamSet.TARGET_SYSTEM) == SYSTEM_ID) {
                params.named(p.getText(Messages.ParamSet.PARAM_ID)).ifPresent(q -> {
                    double v = params.decode(q, p.getFloat(Messages.ParamSet.PARAM_VALUE));
                    if (Double.isFinite(v)) {
                        q.value = v;
                    }
                    send(paramValue(q));
                });
            }
        } else if (missions.handle(f, p, t)) {
            return;
        } else if (f.is(Messages.Ping.MESSAGE)) {
            if (p.getLong(Messages.Ping.TARGET_SYSTEM) == 0) {
                send(Payload.of(Messages.Ping.MESSAGE)
                        .set(Messages.Ping.TIME_USEC, p.getLong(Messages.Ping.TIME_USEC))
                        .set(Messages.Ping.SEQ, p.getLong(Messages.Ping.SEQ))
                        .set(Messages.Ping.TARGET_SYSTEM, f.systemId())
                        .set(Messages.Ping.TARGET_COMPONENT, f.componentId()));
            }
        } else if (f.is(Messages.Timesync.MESSAGE)) {
            if (p.getLong(Messages.Timesync.TC1) == 0) {
                send(Payload.of(Messages.Timesync.MESSAGE)
                        .set(Messages.Timesync.TC1, Math.round(t * 1e9))
                        .set(Messages.Timesync.TS1, p.getLong(Messages.Timesync.TS1)));
            }
        } else if (f.is(Messages.SetupSigning.MESSAGE)) {
            if (forUs(p.getLong(Messages.SetupSigning.TARGET_SYSTEM), p.getLong(Messages.SetupSigning.TARGET_COMPONENT))) {
                setupSigning(p);
            }
        }
    }

    private MavResult command(int code, double[] p, double t) {
        Optional<MavCmd> cmd = MavCmd.find(code);
        if (cmd.isEmpty()) {
            return MavResult.UNSUPPORTED;
        }
        return switch (cmd.get()) {
            case COMPONENT_ARM_DISARM -> autopilot.arm(p[0] >= 0.5, Math.round(p[1]) == FORCE);
            case DO_SET_MODE -> {
                if (!Double.isFinite(p[0]) || !ModeFlag.CUSTOM_MODE_ENABLED.in((long) p[0]) || !Double.isFinite(p[1])) {
                    yield MavResult.DENIED;
                }
                yield mode(dialect.customModeOfCommand(p[1], p[2]));
            }
            case NAV_TAKEOFF -> autopilot.takeoff(p[6]);
            case NAV_LAND -> autopilot.land();
            case NAV_RETURN_TO_LAUNCH -> autopilot.returnToLaunch();
            case MISSION_START -> autopilot.startMission();
            case CONDITION_YAW -> autopilot.conditionYaw(p[0], p[2], Double.isFinite(p[3]) && p[3] >= 0.5);
            case DO_CHANGE_SPEED -> MavResult.ACCEPTED;
            case NAV_LOITER_UNLIM -> autopilot.setMode(FlightMode.HOLD);
            case REQUEST_AUTOPILOT_CAPABILITIES -> {
                send(telemetry.autopilotVersion());
                yield MavResult.ACCEPTED;
            }
            case REQUEST_MESSAGE -> {
                int id = Double.isFinite(p[0]) ? (int) p[0] : -1;
                List<Payload> m = id == Messages.AutopilotVersion.MESSAGE.id() ? List.of(telemetry.autopilotVersion()) : telemetry.message(id, t);
                m.forEach(this::send);
                yield m.isEmpty() ? MavResult.DENIED : MavResult.ACCEPTED;
            }
            case SET_MESSAGE_INTERVAL -> Double.isFinite(p[0]) && Double.isFinite(p[1]) && telemetry.interval((int) p[0], p[1])
                    ? MavResult.ACCEPTED : MavResult.DENIED;
            default -> MavResult.UNSUPPORTED;
        };
    }

    private MavResult mode(long customMode) {
        Optional<FlightMode> m = dialect.mode(customMode, autopilot.medium());
        if (m.isEmpty()) {
            statusText(Severity.WARNING, "Mode change to " + customMode + " failed: unknown mode");
            return MavResult.DENIED;
        }
        return autopilot.setMode(m.get(), customMode);
    }

    private void ack(Frame to, int command, MavResult result) {
        send(Payload.of(Messages.CommandAck.MESSAGE)
                .set(Messages.CommandAck.COMMAND, command)
                .set(Messages.CommandAck.RESULT, result.code())
                .set(Messages.CommandAck.TARGET_SYSTEM, to.systemId())
                .set(Messages.CommandAck.TARGET_COMPONENT, to.componentId()));
    }

    private Payload paramValue(ParameterTable.Parameter q) {
        return Payload.of(Messages.ParamValue.MESSAGE)
                .setText(Messages.ParamValue.PARAM_ID, q.name)
                .set(Messages.ParamValue.PARAM_VALUE, params.encode(q))
                .set(Messages.ParamValue.PARAM_TYPE, q.type.code())
                .set(Messages.ParamValue.PARAM_COUNT, params.count())
                .set(Messages.ParamValue.PARAM_INDEX, params.indexOf(q));
    }

    /**
     * SET_POSITION_TARGET_LOCAL_NED in the frames ArduPilot documents: LOCAL_NED (positions from the
     * origin, velocities north-east-down), LOCAL_OFFSET_NED (positions from the vehicle), BODY_NED
     * (positions from the origin, velocities in the body frame) and BODY_OFFSET_NED (positions and
     * velocities in the body frame, from the vehicle). PX4 takes only LOCAL_NED and BODY_NED; other
     * frames are ignored, as PX4 ignores them.
     */
    private void localSetpoint(Payload p) {
        int mask = (int) p.getLong(Messages.SetPositionTargetLocalNed.TYPE_MASK);
        Optional<CoordinateFrame> frameCode = CoordinateFrame.find(p.getLong(Messages.SetPositionTargetLocalNed.COORDINATE_FRAME));
        if (frameCode.isEmpty()) {
            return;
        }
        CoordinateFrame fr = frameCode.get();
        boolean ardupilotFrame = fr == CoordinateFrame.LOCAL_NED || fr == CoordinateFrame.LOCAL_OFFSET_NED || fr == CoordinateFrame.BODY_NED
                || fr == CoordinateFrame.BODY_OFFSET_NED;
        if (!ardupilotFrame || (dialect == Dialect.PX4 && fr != CoordinateFrame.LOCAL_NED && fr != CoordinateFrame.BODY_NED)) {
            return;
        }
        SimVehicle.Snapshot s = vehicle.snapshot();
        LocalFrame lf = autopilot.frame();
        double c = Math.cos(s.heading());
        double sn = Math.sin(s.heading());
        boolean bodyVelocity = fr == CoordinateFrame.BODY_NED || fr == CoordinateFrame.BODY_OFFSET_NED;
        double[] pos = null;
        double[] vel = null;
        double bodySurge = Double.NaN;
        float x = p.getFloat(Messages.SetPositionTargetLocalNed.X);
        float y = p.getFloat(Messages.SetPositionTargetLocalNed.Y);
        float z = p.getFloat(Messages.SetPositionTargetLocalNed.Z);
        if (TypeMask.uses(mask, TypeMask.X_IGNORE) && TypeMask.uses(mask, TypeMask.Y_IGNORE) && Float.isFinite(x) && Float.isFinite(y)) {
            double alt = TypeMask.uses(mask, TypeMask.Z_IGNORE) && Float.isFinite(z) ? -z : Double.NaN;
            pos = switch (fr) {
                case LOCAL_OFFSET_NED -> new double[]{s.x() + y, s.y() + x, Double.isNaN(alt) ? alt : s.z() + alt};
                case BODY_OFFSET_NED -> new double[]{s.x() + x * c + y * sn, s.y() + x * sn - y * c, Double.isNaN(alt) ? alt : s.z() + alt};
                default -> new double[]{lf.worldX(y), lf.worldY(x), alt};
            };
        } else if (TypeMask.uses(mask, TypeMask.VX_IGNORE) || TypeMask.uses(mask, TypeMask.VY_IGNORE)) {
            double vx = finite(p.getFloat(Messages.SetPositionTargetLocalNed.VX));
            double vy = finite(p.getFloat(Messages.SetPositionTargetLocalNed.VY));
            double vz = TypeMask.uses(mask, TypeMask.VZ_IGNORE) ? finite(p.getFloat(Messages.SetPositionTargetLocalNed.VZ)) : 0;
            if (bodyVelocity) {
                // body frame: x forward, y right
                vel = new double[]{vx * c + vy * sn, vx * sn - vy * c, -vz};
                bodySurge = vx;
            } else {
                vel = new double[]{vy, vx, -vz};
                bodySurge = vx * sn + vy * c;
            }
        }
        double yawTarget = Double.NaN;
        double rate = Double.NaN;
        float yaw = p.getFloat(Messages.SetPositionTargetLocalNed.YAW);
        float yawRate = p.getFloat(Messages.SetPositionTargetLocalNed.YAW_RATE);
        if (TypeMask.uses(mask, TypeMask.YAW_IGNORE) && Float.isFinite(yaw)) {
            yawTarget = LocalFrame.heading(yaw);
        } else if (TypeMask.uses(mask, TypeMask.YAW_RATE_IGNORE) && Float.isFinite(yawRate)) {
            rate = -yawRate;
        }
        autopilot.setpoint(pos, vel, Double.isNaN(rate) ? Double.NaN : bodySurge, yawTarget, rate);
    }

    private void globalSetpoint(Payload p) {
        int mask = (int) p.getLong(Messages.SetPositionTargetGlobalInt.TYPE_MASK);
        if (!TypeMask.uses(mask, TypeMask.X_IGNORE) || !TypeMask.uses(mask, TypeMask.Y_IGNORE)) {
            return;
        }
        LocalFrame lf = autopilot.frame();
        double lat = p.getLong(Messages.SetPositionTargetGlobalInt.LAT_INT) / 1e7;
        double lon = p.getLong(Messages.SetPositionTargetGlobalInt.LON_INT) / 1e7;
        float alt = p.getFloat(Messages.SetPositionTargetGlobalInt.ALT);
        long frameCode = p.getLong(Messages.SetPositionTargetGlobalInt.COORDINATE_FRAME);
        double z = !TypeMask.uses(mask, TypeMask.Z_IGNORE) || !Float.isFinite(alt) ? Double.NaN
                : frameCode == CoordinateFrame.GLOBAL_INT.code() || frameCode == CoordinateFrame.GLOBAL.code() ? alt - lf.amsl(0) : alt;
        autopilot.setpoint(new double[]{lf.worldXOf(lon), lf.worldYOf(lat), z}, null, Double.NaN, Double.NaN, Double.NaN);
    }

    private static double finite(float v) {
        return Float.isFinite(v) ? v : 0;
    }

    private void setupSigning(Payload p) {
        byte[] key = p.getBytes(Messages.SetupSigning.SECRET_KEY);
        long initial = p.getLong(Messages.SetupSigning.INITIAL_TIMESTAMP);
        SigningKey k = SigningKey.of(key);
        if (k.isZero() && initial == 0) {
            encoder.signWith(null);
            check = null;
            statusText(Severity.INFO, "Signing disabled");
            return;
        }
        encoder.signWith(new Signer(k, 0, InstantSource.system()).startingAt(initial));
        check = new SignatureCheck(k, InstantSource.system());
        statusText(Severity.INFO, "Signing key set");
    }

    /** Serial lines are not served: ArduPilot's SITL and this emulator speak UDP (use {@link #serve} for a test's own link). */
    @Override
    public String startOnPseudoTerminal() throws IOException {
        throw new IOException("the MAVLink emulator serves UDP: use --udp PORT (answers whoever sends to it) or --gcs udp://HOST:PORT");
    }

    /** TCP is not served: ArduPilot's SITL and this emulator speak UDP here. */
    @Override
    public int startOnTcp(String bindAddress, int port) throws IOException {
        throw new IOException("the MAVLink emulator serves UDP: use --udp PORT (answers whoever sends to it) or --gcs udp://HOST:PORT");
    }

    @Override
    public String describe() {
        return "MAVLink emulator (" + dialect() + ") for '" + robot.name() + "' on " + links.stream().map(MavlinkLink::describe).toList();
    }

    /** Stops serving: the reader threads end, the links close; at the next world step the vehicle holds and it unbinds. */
    @Override
    public synchronized void close() {
        closed = true;
        for (OwnerThread t : readers) {
            t.close();
        }
        for (MavlinkLink l : links) {
            l.close();
        }
    }
}
