package io.robomw.sim.vehicle;

import io.robomw.api.Clock;
import io.robomw.api.RobotException;
import io.robomw.api.spi.HighLevelCommand;
import io.robomw.config.description.VehicleDrive;
import io.robomw.platform.command.HighLevelCommandPlatform;

import java.util.Locale;

/**
 * The simulator's platform for a vehicle's high-level commands (those of the Configuration
 * Layer's vehicle drive: {@code takeoff}, {@code land}, {@code move}, {@code turn}, {@code arc},
 * {@code drive}, {@code climb}, with the arguments {@code platform: mavlink} takes), flown on the
 * simulated vehicle directly as its autopilot would ({@link Guidance}), without MAVLink in between.
 * The motions mean what they mean on the real driver: a move is a target ahead along the heading
 * reached within the acceptance radius, a multirotor keeps its altitude, a boat or rover cannot take
 * off, land or climb. Between commands the vehicle holds where it is (a multirotor hovers, a boat
 * keeps its place against the current, a rover stops). A boat or rover arms at its first motion; a
 * multirotor at its take-off, and it disarms when it has landed.
 *
 * <p>Threads: the world's thread for this robot: its execution action thread (start, refresh,
 * stop) and its controller ({@link #control}, every step) both run there.
 */
public final class VehicleSimPlatform extends HighLevelCommandPlatform {

    private static final double ALTITUDE_TOLERANCE = 0.05;
    private static final double YAW_TOLERANCE = Math.toRadians(1);
    private static final double LAND_SPEED = 0.5;

    private final SimVehicle vehicle;
    private final VehicleDrive drive;
    private final boolean air;
    private Maneuver current;
    private Run running;
    private double holdX;
    private double holdY;
    private double holdZ;
    private double holdHeading;
    private double lastHeading;
    private double time;

    /**
     * @param robot   the robot's name
     * @param clock   the world's clock
     * @param vehicle its simulated vehicle
     * @param drive   its vehicle drive (limits)
     */
    public VehicleSimPlatform(String robot, Clock clock, SimVehicle vehicle, VehicleDrive drive) {
        super(robot, clock);
        this.vehicle = vehicle;
        this.drive = drive;
        this.air = drive.medium() == VehicleDrive.Medium.AIR;
        holdHere(vehicle.snapshot());
    }

    private void holdHere(SimVehicle.Snapshot s) {
        holdX = s.x();
        holdY = s.y();
        holdZ = s.z();
        holdHeading = s.heading();
    }

    @Override
    protected void start(Run run) {
        HighLevelCommand c = run.command();
        SimVehicle.Snapshot s = vehicle.snapshot();
        String refusal = refusal(c, s);
        if (refusal != null) {
            failed(run, refusal);
            return;
        }
        if (!s.armed() && (!air || c.name().equals("takeoff"))) {
            vehicle.arm();
        }
        current = new Maneuver(c, s);
        running = run;
        lastHeading = s.heading();
    }

    private String refusal(HighLevelCommand c, SimVehicle.Snapshot s) {
        boolean flyingVerb = c.name().equals("takeoff") || c.name().equals("land") || c.name().equals("climb");
        if (flyingVerb && !air) {
            return "robot '" + robot() + "' is a " + drive.medium().yamlName() + " vehicle: it cannot " + c.name();
        }
        if (air && !flyingVerb && (s.landed() || !s.armed())) {
            return "robot '" + robot() + "' is on the ground: take off first";
        }
        return switch (c.name()) {
            case "takeoff", "land", "move", "turn", "arc", "drive", "climb" -> null;
            default -> "the simulated vehicle has no command '" + c.name() + "'";
        };
    }

    @Override
    protected void refresh(Run run) {
        if (current != null && current.command.continuous()) {
            current = new Maneuver(run.command(), vehicle.snapshot());
        }
    }

    @Override
    protected void stop(Run run) {
        planned = null;
        if (running == run) {
            current = null;
            running = null;
            SimVehicle.Snapshot s = vehicle.snapshot();
            holdHere(s);
            if (air && !s.landed()) {
                holdZ = Double.isNaN(targetZ) ? s.z() : targetZ;
            }
        }
    }

    private double targetZ = Double.NaN;
    /** Where the last move or turn meant the vehicle to be (x, y, heading), or {@code null}: the next one starts from there. */
    private double[] planned;

    /**
     * One step of the autopilot: the current command's targets, or holding; ends the command when
     * it is done. Called by the world every step, for this robot.
     *
     * @param dt the step, seconds
     */
    public void control(double dt) {
        time += dt;
        SimVehicle.Snapshot s = vehicle.snapshot();
        Maneuver m = current;
        if (m == null) {
            vehicle.target(hold(s));
            return;
        }
        double turned = Guidance.normalize(s.heading() - lastHeading);
        lastHeading = s.heading();
        m.turned += turned;
        VehicleTarget t = m.step(s, dt);
        if (t == null) {
            Run r = running;
            current = null;
            running = null;
            holdHere(s);
            if (air && !Double.isNaN(targetZ)) {
                holdZ = targetZ;
            }
            vehicle.target(hold(s));
            finished(r);
            return;
        }
        vehicle.target(t);
    }

    private VehicleTarget hold(SimVehicle.Snapshot s) {
        if (!s.armed() || (air && s.landed())) {
            return VehicleTarget.HOLD;
        }
        if (drive.medium() == VehicleDrive.Medium.GROUND) {
            return new VehicleTarget(0, 0, 0, 0);
        }
        double rate = air ? Guidance.yawRateTo(s, holdHeading, drive.maxTurnRate()) : Double.NaN;
        return Guidance.goTo(s, drive.medium(), drive.maxSpeed(), drive.maxClimbRate(), drive.maxTurnRate(), holdX, holdY, holdZ,
                drive.acceptanceRadius() * 2, rate);
    }

    /** One command as it runs on the vehicle. */
    private final class Maneuver {
        final HighLevelCommand command;
        final double x0;
        final double y0;
        final double z0;
        final double h0;
        final double began;
        double turned;

        Maneuver(HighLevelCommand command, SimVehicle.Snapshot s) {
            this.command = command;
            this.z0 = air && !Double.isNaN(targetZ) ? targetZ : s.z();
            this.began = time;
            // as a waypoint autopilot chains its legs: a move or turn starts where the last one aimed,
            // when the vehicle is within twice the acceptance radius of it (a boat also from the course
            // it aimed for, whatever its heading: in a current it points into the current to hold on)
            double[] p = planned;
            boolean chain = p != null && (command.name().equals("move") || command.name().equals("turn"))
                    && Math.hypot(p[0] - s.x(), p[1] - s.y()) <= 2 * Math.max(drive.acceptanceRadius(), 0.25)
                    && (Math.abs(Guidance.normalize(p[2] - s.heading())) <= Math.toRadians(10) || drive.medium() == VehicleDrive.Medium.WATER);
            this.x0 = chain ? p[0] : s.x();
            this.y0 = chain ? p[1] : s.y();
            this.h0 = chain ? p[2] : s.heading();
            this.turned = chain ? Guidance.normalize(s.heading() - h0) : 0;
            planned = switch (command.name()) {
                case "move" -> new double[]{x0 + command.argument("distance") * Math.cos(h0), y0 + command.argument("distance") * Math.sin(h0), h0};
                case "turn" -> new double[]{x0, y0, Guidance.normalize(h0 + command.argument("angle"))};
                case "climb" -> planned;
                default -> null;
            };
        }

        double arg(String key) {
            return command.argument(key);
        }

        /** @return the targets now, or {@code null} when it is done */
        VehicleTarget step(SimVehicle.Snapshot s, double dt) {
            double t = time - began;
            return switch (command.name()) {
                case "takeoff" -> {
                    double alt = arg("altitude");
                    if (s.z() >= alt - ALTITUDE_TOLERANCE) {
                        targetZ = alt;
                        yield null;
                    }
                    yield new VehicleTarget(Guidance.POSITION_GAIN * (x0 - s.x()), Guidance.POSITION_GAIN * (y0 - s.y()), drive.maxClimbRate(), 0);
                }
                case "land" -> {
                    if (s.landed()) {
                        vehicle.disarm();
                        targetZ = Double.NaN;
                        yield null;
                    }
                    yield new VehicleTarget(Guidance.POSITION_GAIN * (x0 - s.x()), Guidance.POSITION_GAIN * (y0 - s.y()), -LAND_SPEED, 0);
                }
                case "climb" -> {
                    double goal = z0 + arg("height");
                    if (Math.abs(s.z() - goal) <= ALTITUDE_TOLERANCE) {
                        targetZ = goal;
                        yield null;
                    }
                    double carrot = z0 + Math.signum(arg("height")) * Math.min(Math.abs(arg("height")), arg("speed") * t + ALTITUDE_TOLERANCE);
                    yield Guidance.goTo(s, drive.medium(), drive.maxSpeed(), arg("speed"), drive.maxTurnRate(), x0, y0, carrot, 0, 0);
                }
                case "move" -> {
                    double d = arg("distance");
                    double r = arg("acceptance_radius");
                    double ex = x0 + d * Math.cos(h0);
                    double ey = y0 + d * Math.sin(h0);
                    if (d < 0 && !air) {
                        if (Math.hypot(s.x() - x0, s.y() - y0) >= Math.abs(d) - r) {
                            yield null;
                        }
                        yield new VehicleTarget(-arg("speed") * Math.cos(s.heading()), -arg("speed") * Math.sin(s.heading()), 0, 0);
                    }
                    if (Math.hypot(ex - s.x(), ey - s.y()) <= r) {
                        yield null;
                    }
                    double along = Math.signum(d) * Math.min(Math.abs(d), arg("speed") * t + r);
                    double rate = air ? Guidance.yawRateTo(s, h0, drive.maxTurnRate()) : Double.NaN;
                    yield Guidance.goTo(s, drive.medium(), arg("speed"), drive.maxClimbRate(), drive.maxTurnRate(),
                            x0 + along * Math.cos(h0), y0 + along * Math.sin(h0), z0, r, rate);
                }
                case "turn" -> {
                    double a = arg("angle");
                    if (Math.abs(a - turned) <= YAW_TOLERANCE) {
                        yield null;
                    }
                    double rate = Math.signum(a - turned) * Math.min(arg("speed"), Math.max(0.1, Guidance.YAW_GAIN * Math.abs(a - turned)));
                    if (air) {
                        yield Guidance.goTo(s, drive.medium(), drive.maxSpeed(), drive.maxClimbRate(), drive.maxTurnRate(), x0, y0, z0, 0, rate);
                    }
                    yield new VehicleTarget(0, 0, 0, rate);
                }
                case "arc" -> {
                    double a = arg("angle");
                    if (Math.abs(turned) >= Math.abs(a) - YAW_TOLERANCE) {
                        yield null;
                    }
                    double v = Math.signum(a) * arg("speed");
                    double w = v / arg("radius");
                    yield body(s, v, w);
                }
                case "drive" -> body(s, arg("linear"), arg("angular"));
                default -> throw new RobotException("robot '" + robot() + "': no command " + command.name().toLowerCase(Locale.ROOT));
            };
        }

        private VehicleTarget body(SimVehicle.Snapshot s, double v, double w) {
            double vz = air ? Guidance.clamp(Guidance.CLIMB_GAIN * (z0 - s.z()), drive.maxClimbRate()) : 0;
            return new VehicleTarget(v * Math.cos(s.heading()), v * Math.sin(s.heading()), vz, w);
        }
    }
}
