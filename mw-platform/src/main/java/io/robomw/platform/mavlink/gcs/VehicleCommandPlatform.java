package io.robomw.platform.mavlink.gcs;

import io.robomw.api.Clock;
import io.robomw.api.RobotException;
import io.robomw.api.RobotLinkException;
import io.robomw.api.spi.HighLevelCommand;
import io.robomw.platform.command.HighLevelCommandPlatform;
import io.robomw.platform.mavlink.wire.LandedState;
import io.robomw.platform.mavlink.wire.MavCmd;
import io.robomw.platform.mavlink.wire.Messages;
import io.robomw.platform.mavlink.wire.ParamType;
import io.robomw.platform.mavlink.wire.Payload;

import java.util.Locale;
import java.util.Map;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.ConcurrentHashMap;

/**
 * The MAVLink driver's command platform: each high-level command of the vehicle drive becomes the
 * vehicle's own targets, streamed while it runs, and finishes when the vehicle's telemetry says it
 * is done.
 *
 * <pre>
 * command  arguments (SI)                          on the wire                                   done when
 * takeoff  altitude                                ArduPilot: DO_SET_MODE GUIDED, arm,           relative altitude within 0.15 m
 *                                                  NAV_TAKEOFF(p7 = altitude); PX4: PARAM_SET
 *                                                  MIS_TAKEOFF_ALT, arm, NAV_TAKEOFF(NaN...)
 * land     -                                       NAV_LAND                                      on the ground
 * move     distance, speed, acceptance_radius      a LOCAL_NED position moving ahead at speed    within the acceptance radius of the
 *                                                  (a "carrot"; a boat or rover backing up:      end point (backing up: that far from
 *                                                  BODY_NED velocity)                            the start)
 * turn     angle, speed                            flyer: LOCAL_NED position + yaw moving at     yaw within 2° of the target
 *                                                  speed; boat, rover: BODY_NED yaw rate          (boat, rover: turned that far)
 * arc      radius, angle, speed                    BODY_NED velocity and yaw rate                turned that far
 * drive    linear, angular (continuous)            BODY_NED velocity and yaw rate                (replaced, stopped, watchdog)
 * climb    height, speed                           LOCAL_NED position, altitude moving at speed  altitude within 0.15 m
 * </pre>
 * Setpoints stream at 20 Hz (the link's tick). Before one streams, the vehicle is put in its
 * guided mode: ArduPilot's GUIDED (4, or 15 on rovers and boats) at once; PX4's OFFBOARD only
 * after the stream has run for more than a second, as PX4 requires. A boat or rover is armed
 * before its first motion; a multirotor must have taken off ({@code takeoff}). On PX4 the last
 * position is streamed on between commands, so the vehicle stays in OFFBOARD and holds there
 * (without a stream PX4 would fail safe after COM_OF_LOSS_T); on ArduPilot a position target
 * persists by itself.
 *
 * <p>A command that ends early (interrupted, its watchdog, a stop) brakes: a zero velocity, and
 * the vehicle holds where it is. A lost link fails every running command
 * ({@link io.robomw.platform.command.HighLevelRobotPlatform#linkFailed}).
 *
 * <p>Threads: {@link #start}, {@link #refresh} and {@link #stop} on the execution action thread
 * (they send at once: a UDP send does not block); {@link #tick} on the link's thread. A run's
 * maneuver is shared through a concurrent map and synchronised on itself.
 */
final class VehicleCommandPlatform extends HighLevelCommandPlatform implements GroundStation.Listener {

    /** How close a climb or take-off must come to its altitude, metres. */
    static final double ALTITUDE_TOLERANCE = 0.15;
    /** How close a turn must come to its yaw, radians (2°). */
    static final double YAW_TOLERANCE = Math.toRadians(2);
    /** How long PX4 must see the stream before OFFBOARD is asked for, seconds. */
    static final double OFFBOARD_AFTER_SECONDS = 1.1;
    /**
     * How many times OFFBOARD is asked for again, each after another {@link #OFFBOARD_AFTER_SECONDS} of
     * the stream, when PX4 answers TEMPORARILY_REJECTED (it saw a gap in the stream: a busy machine
     * that delayed the ground station's sender); then the maneuver fails with PX4's answer.
     */
    static final int OFFBOARD_RETRIES = 3;

    private final GroundStation gcs;
    private final Map<Run, Maneuver> running = new ConcurrentHashMap<>();
    private volatile Payload keep;
    /** The altitude last commanded (down, metres; NaN when none): moves and turns hold it, climbs start from it. */
    private volatile double commandedDown = Double.NaN;
    /** Where the last motion meant the vehicle to be (north, east, yaw), or {@code null}: the next one starts from there. */
    private volatile double[] planned;
    private volatile long streamSince = Long.MIN_VALUE;
    private volatile boolean offboardAsked;
    /** OFFBOARD requests PX4 answered TEMPORARILY_REJECTED in a row. */
    private volatile int offboardRefusals;

    VehicleCommandPlatform(String robot, Clock clock, GroundStation gcs) {
        super(robot, clock);
        this.gcs = gcs;
    }

    private Telemetry t() {
        return gcs.telemetry();
    }

    private long timeBootMs() {
        return gcs.now() / 1_000_000L;
    }

    @Override
    protected void start(Run run) {
        Maneuver m;
        try {
            m = maneuver(run);
        } catch (RobotException e) {
            failed(run, e.getMessage());
            return;
        }
        running.put(run, m);
        m.begin();
    }

    @Override
    protected void refresh(Run run) {
        Maneuver m = running.get(run);
        if (m instanceof Drive d) {
            d.values(run.command());
            d.stream();
        }
    }

    @Override
    protected void stop(Run run) {
        planned = null;
        Maneuver m = running.remove(run);
        if (m != null) {
            m.brake();
        }
    }

    @Override
    public void tick(long now) {
        for (Map.Entry<Run, Maneuver> e : running.entrySet()) {
            Maneuver m = e.getValue();
            String failure = m.failure;
            if (failure != null) {
                running.remove(e.getKey(), m);
                failed(e.getKey(), failure);
                continue;
            }
            if (m.tick(now)) {
                running.remove(e.getKey(), m);
                finished(e.getKey());
            }
        }
        Payload k = keep;
        if (running.isEmpty() && k != null && !gcs.kind().ardupilot() && armed()) {
            gcs.send(k);
        }
    }

    @Override
    public void lost(RobotLinkException cause) {
        for (Map.Entry<Run, Maneuver> e : running.entrySet()) {
            e.getValue().failure = cause.getMessage();
        }
    }

    @Override
    public void restored() {
        // commands sent from now on run; the vehicle's own failsafe decided what it did meanwhile
    }

    private boolean armed() {
        return t().heartbeat().map(Telemetry.Heartbeat::armed).orElse(false);
    }

    private boolean inGuidedMode() {
        return t().heartbeat().map(h -> h.customMode() == gcs.kind().guidedMode()).orElse(false);
    }

    private Telemetry.Local here() {
        return t().local().orElseThrow(() -> new RobotException("robot '" + robot() + "': the vehicle has not reported its position"
                + " (LOCAL_POSITION_NED) yet; is it streaming, and has it a position fix?"));
    }

    /**
     * Where a motion starts: where the vehicle is, but, as a waypoint autopilot chains its legs, at
     * the point and yaw the last motion aimed for when the vehicle is within twice the acceptance
     * radius of it (so a square of short moves does not shrink by a radius per leg; a boat also at the
     * course it aimed for, whatever its heading: in a current it points into the current to hold its
     * place), and at the altitude last commanded (a flyer holds that, not where it has sagged to).
     */
    private Telemetry.Local held(Telemetry.Local l, double radius) {
        double down = flyer() && !Double.isNaN(commandedDown) ? commandedDown : l.down();
        double[] p = planned;
        if (p != null && Math.hypot(p[0] - l.north(), p[1] - l.east()) <= 2 * radius
                && (Math.abs(normalize(p[2] - l.yaw())) <= Math.toRadians(10) || gcs.kind().medium() == VehicleKind.Medium.WATER)) {
            return new Telemetry.Local(p[0], p[1], down, l.vn(), l.ve(), l.vd(), p[2], l.atNanos());
        }
        return new Telemetry.Local(l.north(), l.east(), down, l.vn(), l.ve(), l.vd(), l.yaw(), l.atNanos());
    }

    private Telemetry.Local held(Telemetry.Local l) {
        return held(l, 0);
    }

    private boolean flyer() {
        return gcs.kind().medium() == VehicleKind.Medium.AIR;
    }

    private Maneuver maneuver(Run run) {
        HighLevelCommand c = run.command();
        return switch (c.name()) {
            case "takeoff" -> new TakeOff(c.argument("altitude"));
            case "land" -> new Land();
            case "move" -> new Move(c.argument("distance"), c.argument("speed"), c.argument("acceptance_radius"));
            case "turn" -> new Turn(c.argument("angle"), c.argument("speed"));
            case "arc" -> new Arc(c.argument("radius"), c.argument("angle"), c.argument("speed"));
            case "drive" -> new Drive(c);
            case "climb" -> new Climb(c.argument("height"), c.argument("speed"));
            default -> throw new RobotException("robot '" + robot() + "': the MAVLink platform has no command '" + c.name()
                    + "'; it takes takeoff, land, move, turn, arc, drive and climb");
        };
    }

    /** One command as it runs: what it sends at its start, each tick, and when it ends early. */
    private abstract class Maneuver {
        volatile String failure;
        long began;

        /** Starts it: the mode, arming, the first setpoint. */
        void begin() {
            began = gcs.now();
        }

        /**
         * @param now the clock
         * @return whether it is done
         */
        abstract boolean tick(long now);

        /** It ended early: stop the vehicle where it is. */
        void brake() {
            if (gcs.kind() == null || gcs.isLost()) {
                return;
            }
            gcs.send(Setpoints.bodyVelocity(gcs.vehicleSystem(), timeBootMs(), 0, 0, 0, 0));
            t().local().ifPresent(l -> keep = Setpoints.position(gcs.vehicleSystem(), timeBootMs(), l.north(), l.east(), l.down(), l.yaw()));
        }

        double seconds(long now) {
            return (now - began) / 1e9;
        }

        void fail(Throwable e) {
            Throwable cause = e instanceof java.util.concurrent.CompletionException && e.getCause() != null ? e.getCause() : e;
            failure = cause.getMessage();
        }

        /** Puts the vehicle in its guided mode, arms a boat or rover, checks a flyer is up. */
        void prepare(boolean needsAir) {
            if (needsAir && flyer() && (t().landed() == LandedState.ON_GROUND || !armed())) {
                failure = "robot '" + robot() + "' is on the ground: take off first";
                return;
            }
            CompletableFuture<Void> ready = CompletableFuture.completedFuture(null);
            if (gcs.kind().ardupilot() && !inGuidedMode()) {
                ready = gcs.setMode(gcs.kind().guidedMode());
            }
            if (!flyer() && !armed()) {
                ready = ready.thenCompose(v -> gcs.command(MavCmd.COMPONENT_ARM_DISARM, 1, 0, 0, 0, 0, 0, 0));
            }
            ready.whenComplete((v, e) -> {
                if (e != null) {
                    fail(e);
                }
            });
        }

        /** Streams a setpoint, and on PX4 asks for OFFBOARD once the stream has run long enough. */
        void stream(Payload p) {
            gcs.send(p);
            keep = null;
            if (gcs.kind().ardupilot()) {
                return;
            }
            long now = gcs.now();
            if (inGuidedMode()) {
                streamSince = Math.min(streamSince, now);
                return;
            }
            if (streamSince == Long.MIN_VALUE || now - streamSince > 3_000_000_000L && !offboardAsked) {
                streamSince = now;
            }
            if ((now - streamSince) / 1e9 >= OFFBOARD_AFTER_SECONDS && !offboardAsked) {
                offboardAsked = true;
                gcs.setMode(gcs.kind().guidedMode()).whenComplete((v, e) -> {
                    Throwable cause = e instanceof java.util.concurrent.CompletionException && e.getCause() != null ? e.getCause() : e;
                    if (cause instanceof CommandRefusedException r && r.temporary() && offboardRefusals < OFFBOARD_RETRIES) {
                        offboardRefusals++;
                        streamSince = Long.MIN_VALUE; // stream on, and ask again once PX4 has seen it long enough
                    } else if (e != null) {
                        offboardRefusals = 0;
                        fail(e);
                    } else {
                        offboardRefusals = 0;
                    }
                    offboardAsked = false;
                });
            }
        }
    }

    private final class TakeOff extends Maneuver {
        private final double altitude;

        TakeOff(double altitude) {
            this.altitude = altitude;
        }

        @Override
        void begin() {
            super.begin();
            planned = null;
            if (!flyer()) {
                failure = "robot '" + robot() + "' is a " + gcs.kind().medium().name().toLowerCase(Locale.ROOT) + " vehicle: it cannot take off";
                return;
            }
            CompletableFuture<Void> f;
            if (gcs.kind().ardupilot()) {
                f = (inGuidedMode() ? CompletableFuture.<Void>completedFuture(null) : gcs.setMode(gcs.kind().guidedMode()))
                        .thenCompose(v -> gcs.command(MavCmd.COMPONENT_ARM_DISARM, 1, 0, 0, 0, 0, 0, 0))
                        .thenCompose(v -> gcs.command(MavCmd.NAV_TAKEOFF, 0, 0, 0, 0, 0, 0, altitude));
            } else {
                gcs.send(Payload.of(Messages.ParamSet.MESSAGE)
                        .set(Messages.ParamSet.TARGET_SYSTEM, gcs.vehicleSystem())
                        .set(Messages.ParamSet.TARGET_COMPONENT, GroundStation.AUTOPILOT_COMPONENT)
                        .setText(Messages.ParamSet.PARAM_ID, "MIS_TAKEOFF_ALT")
                        .set(Messages.ParamSet.PARAM_VALUE, altitude)
                        .set(Messages.ParamSet.PARAM_TYPE, ParamType.REAL32.code()));
                double nan = Double.NaN;
                f = gcs.command(MavCmd.COMPONENT_ARM_DISARM, 1, nan, nan, nan, nan, nan, nan)
                        .thenCompose(v -> gcs.command(MavCmd.NAV_TAKEOFF, nan, nan, nan, nan, nan, nan, nan));
            }
            f.whenComplete((v, e) -> {
                if (e != null) {
                    fail(e);
                }
            });
        }

        @Override
        boolean tick(long now) {
            if (t().relativeAltitude() >= altitude - ALTITUDE_TOLERANCE && t().landed() != LandedState.ON_GROUND) {
                // the local origin is home, on the ground: down = -altitude
                commandedDown = -altitude;
                return true;
            }
            return false;
        }
    }

    private final class Land extends Maneuver {
        @Override
        void begin() {
            super.begin();
            if (!flyer()) {
                failure = "robot '" + robot() + "' is a " + gcs.kind().medium().name().toLowerCase(Locale.ROOT) + " vehicle: it cannot land";
                return;
            }
            keep = null;
            planned = null;
            commandedDown = Double.NaN;
            gcs.command(MavCmd.NAV_LAND, 0, 0, 0, Double.NaN, Double.NaN, Double.NaN, Double.NaN).whenComplete((v, e) -> {
                if (e != null) {
                    fail(e);
                }
            });
        }

        @Override
        boolean tick(long now) {
            return seconds(now) > 0.5 && t().landed() == LandedState.ON_GROUND;
        }

        @Override
        void brake() {
            // a landing is not braked: the vehicle goes on landing (its LAND mode)
        }
    }

    private final class Move extends Maneuver {
        private final double distance;
        private final double speed;
        private final double radius;
        private Telemetry.Local start;
        private double endNorth;
        private double endEast;

        Move(double distance, double speed, double radius) {
            this.distance = distance;
            this.speed = speed;
            this.radius = radius;
        }

        @Override
        void begin() {
            super.begin();
            start = held(here(), radius);
            endNorth = start.north() + distance * Math.cos(start.yaw());
            endEast = start.east() + distance * Math.sin(start.yaw());
            planned = new double[]{endNorth, endEast, start.yaw()};
            prepare(true);
            tick(began);
        }

        @Override
        boolean tick(long now) {
            Telemetry.Local l = t().local().orElse(start);
            boolean backing = distance < 0 && !flyer();
            if (backing) {
                double gone = Math.hypot(l.north() - start.north(), l.east() - start.east());
                if (gone >= Math.abs(distance) - radius) {
                    return true;
                }
                stream(Setpoints.bodyVelocity(gcs.vehicleSystem(), timeBootMs(), -speed, 0, 0, 0));
                return false;
            }
            if (Math.hypot(endNorth - l.north(), endEast - l.east()) <= radius) {
                keep = Setpoints.position(gcs.vehicleSystem(), timeBootMs(), endNorth, endEast, start.down(), start.yaw());
                return true;
            }
            double along = Math.min(Math.abs(distance), speed * seconds(now) + radius);
            double sign = Math.signum(distance);
            double n = start.north() + sign * along * Math.cos(start.yaw());
            double e = start.east() + sign * along * Math.sin(start.yaw());
            stream(Setpoints.position(gcs.vehicleSystem(), timeBootMs(), n, e, start.down(), start.yaw()));
            return false;
        }
    }

    private final class Turn extends Maneuver {
        private final double angle;
        private final double rate;
        private Telemetry.Local start;
        private double turned;
        private double lastYaw;

        Turn(double angle, double rate) {
            this.angle = angle;
            this.rate = rate;
        }

        @Override
        void begin() {
            super.begin();
            start = held(here(), 0.5);
            lastYaw = here().yaw();
            turned = normalize(lastYaw - start.yaw());
            planned = new double[]{start.north(), start.east(), normalize(start.yaw() - angle)};
            prepare(true);
            tick(began);
        }

        @Override
        boolean tick(long now) {
            Telemetry.Local l = t().local().orElse(start);
            turned += normalize(l.yaw() - lastYaw);
            lastYaw = l.yaw();
            // a positive angle turns left: anti-clockwise, the MAVLink yaw decreases
            double wanted = -angle;
            if (Math.abs(wanted - turned) <= YAW_TOLERANCE) {
                if (flyer()) {
                    keep = Setpoints.position(gcs.vehicleSystem(), timeBootMs(), start.north(), start.east(), start.down(), l.yaw());
                } else {
                    gcs.send(Setpoints.bodyVelocity(gcs.vehicleSystem(), timeBootMs(), 0, 0, 0, 0));
                }
                return true;
            }
            if (flyer()) {
                double progress = Math.min(Math.abs(wanted), rate * seconds(now) + YAW_TOLERANCE);
                double yaw = normalize(start.yaw() + Math.signum(wanted) * progress);
                stream(Setpoints.position(gcs.vehicleSystem(), timeBootMs(), start.north(), start.east(), start.down(), yaw));
            } else {
                double left = wanted - turned;
                double r = Math.signum(left) * Math.min(rate, Math.max(0.15, 2 * Math.abs(left)));
                stream(Setpoints.bodyVelocity(gcs.vehicleSystem(), timeBootMs(), 0, 0, 0, r));
            }
            return false;
        }
    }

    private final class Arc extends Maneuver {
        private final double linear;
        private final double yawRate;
        private final double angle;
        private double turned;
        private double lastYaw;

        Arc(double radius, double angle, double speed) {
            this.linear = Math.signum(angle) * speed;
            this.yawRate = -linear / radius;
            this.angle = angle;
        }

        @Override
        void begin() {
            super.begin();
            planned = null;
            lastYaw = here().yaw();
            prepare(true);
            tick(began);
        }

        @Override
        boolean tick(long now) {
            Telemetry.Local l = t().local().orElseThrow();
            turned += normalize(l.yaw() - lastYaw);
            lastYaw = l.yaw();
            // an arc of `angle` radians turns the heading by as much
            if (Math.abs(turned) >= Math.abs(angle) - YAW_TOLERANCE) {
                brake();
                return true;
            }
            stream(Setpoints.bodyVelocity(gcs.vehicleSystem(), timeBootMs(), linear, 0, 0, yawRate));
            return false;
        }
    }

    private final class Drive extends Maneuver {
        private volatile double linear;
        private volatile double angular;

        Drive(HighLevelCommand c) {
            values(c);
        }

        void values(HighLevelCommand c) {
            linear = c.argument("linear");
            angular = c.argument("angular");
        }

        @Override
        void begin() {
            super.begin();
            planned = null;
            prepare(true);
            stream();
        }

        void stream() {
            stream(Setpoints.bodyVelocity(gcs.vehicleSystem(), timeBootMs(), linear, 0, 0, -angular));
        }

        @Override
        boolean tick(long now) {
            stream();
            return false;
        }
    }

    private final class Climb extends Maneuver {
        private final double height;
        private final double speed;
        private Telemetry.Local start;

        Climb(double height, double speed) {
            this.height = height;
            this.speed = speed;
        }

        @Override
        void begin() {
            super.begin();
            if (!flyer()) {
                failure = "robot '" + robot() + "' is a " + gcs.kind().medium().name().toLowerCase(Locale.ROOT) + " vehicle: it cannot climb";
                return;
            }
            start = held(here());
            commandedDown = start.down() - height;
            prepare(true);
            tick(began);
        }

        @Override
        boolean tick(long now) {
            double targetDown = start.down() - height;
            Telemetry.Local l = t().local().orElse(start);
            if (Math.abs(l.down() - targetDown) <= ALTITUDE_TOLERANCE) {
                keep = Setpoints.position(gcs.vehicleSystem(), timeBootMs(), start.north(), start.east(), targetDown, start.yaw());
                return true;
            }
            double progress = Math.min(Math.abs(height), speed * seconds(now) + ALTITUDE_TOLERANCE);
            double down = start.down() - Math.signum(height) * progress;
            stream(Setpoints.position(gcs.vehicleSystem(), timeBootMs(), start.north(), start.east(), down, start.yaw()));
            return false;
        }
    }

    private static double normalize(double a) {
        double r = Math.IEEEremainder(a, 2 * Math.PI);
        return r <= -Math.PI ? r + 2 * Math.PI : r;
    }
}
