package io.robomw.config.vehicle;

import io.robomw.api.Capability;
import io.robomw.api.Pose;
import io.robomw.api.spi.CommandPriority;
import io.robomw.api.spi.HighLevelCommand;
import io.robomw.api.spi.HighLevelPlatform;
import io.robomw.api.spi.PoseSource;
import io.robomw.api.spi.RobotPlatform;
import io.robomw.config.description.RobotDescription;
import io.robomw.config.description.VehicleDrive;
import io.robomw.config.drive.Call;
import io.robomw.config.drive.DriveControl;

import java.time.Duration;
import java.util.LinkedHashMap;
import java.util.Locale;
import java.util.Map;
import java.util.Set;
import java.util.concurrent.CompletableFuture;

/**
 * The Configuration Layer's third implementation: a vehicle (a multirotor, a surface boat, a
 * ground rover) moved by its autopilot. Each Instruction Layer verb, checked against the vehicle
 * drive's limits, becomes one {@link HighLevelCommand} in the vehicle's own vocabulary, which the
 * platform ({@code platform: mavlink}, or the simulator) turns into the autopilot's targets; no
 * motor's motion is computed here, as the legged drive computes no leg's.
 *
 * <pre>
 * verb                       command   arguments (SI)                        the platform does
 * move(d, v)                 move      distance, speed, acceptance_radius    a position target d ahead in the body frame, done within the radius
 * turn(a, w)                 turn      angle, speed                          a yaw target a to the left
 * arc(r, a, v)               arc       radius, angle, speed                  velocity v and yaw rate v / r until the heading changed by a
 * drive(v, w)                drive     linear, angular (continuous)          velocity and yaw-rate targets, under the watchdog
 * changeAltitude(h, v)       climb     height, speed                         an altitude target h above (air only)
 * takeOff(h)                 takeoff   altitude                              arm, take off, climb to h (air only)
 * land()                     land      -                                     land and disarm (air only)
 * </pre>
 * A multirotor keeps its altitude while it moves, turns and drives. A boat or rover cannot take off,
 * land or climb: those verbs are an {@link io.robomw.api.UnsupportedActionException} before
 * anything is sent. Every motion drives the actuator group {@value VehicleDrive#VEHICLE}, so a
 * newer one interrupts the one before (the vehicle brakes and holds).
 *
 * <h2>Pose</h2>
 * The vehicle reports where it is ({@link PoseSource}); the pose is that report, relative to where
 * the robot was when it was opened (or last reset; or first reported, if it had not reported yet
 * when it was opened): x ahead as it then faced, y to its left, heading anti-clockwise, and z its
 * altitude above its home's ground (not reset). No dead reckoning: a vehicle pushed by wind or
 * current is where it says it is.
 *
 * <p>Thread-safe.
 */
public final class VehicleDriveControl implements DriveControl {

    /** Added to every motion's expected duration: the autopilot's mode switch (PX4 asks for a second of setpoints first) and settling. */
    static final double SETTLE_SECONDS = 2.0;
    /** The highest take-off or climb, metres. */
    static final double MAX_ALTITUDE = 1000;

    private final RobotDescription description;
    private final VehicleDrive drive;
    private final RobotPlatform platform;
    private final String cannotMove;
    private final Object poseLock = new Object();
    /** The reported pose that maps to {@link #origin}; {@code null} until the first report. */
    private Pose reference;
    private Pose origin = Pose.ORIGIN;

    /**
     * @param description the description in force
     * @param drive       its vehicle drive
     * @param platform    the opened platform; it must take high-level commands for anything to move
     * @param previous    the drive chosen for the description before (a reload), whose pose frame
     *                    carries over, or {@code null}
     */
    public VehicleDriveControl(RobotDescription description, VehicleDrive drive, RobotPlatform platform, VehicleDriveControl previous) {
        this.description = description;
        this.drive = drive;
        this.platform = platform;
        this.cannotMove = platform instanceof HighLevelPlatform ? null
                : "platform '" + description.platform() + "' does not take a vehicle's high-level commands (platform: mavlink does)";
        if (previous != null) {
            synchronized (previous.poseLock) {
                this.reference = previous.reference;
                this.origin = previous.origin;
            }
        } else {
            // where the robot is when it is opened is its pose's origin (a vehicle reports it by then)
            this.reference = reported().orElse(null);
        }
    }

    @Override
    public RobotDescription description() {
        return description;
    }

    /** @return the vehicle drive */
    public VehicleDrive vehicleDrive() {
        return drive;
    }

    @Override
    public CompletableFuture<Void> move(double distance, double speed) {
        Call call = call("move(%.3f, %.3f)", distance, speed);
        call.finite(distance, "distance");
        call.positiveAtMost(speed, drive.maxSpeed(), "speed", "m/s", "drive.max_speed");
        return run("move", values("distance", distance, "speed", speed, "acceptance_radius", drive.acceptanceRadius()),
                Math.abs(distance) / speed);
    }

    @Override
    public CompletableFuture<Void> turn(double radians, double speed) {
        Call call = call("turn(%.4f, %.4f)", radians, speed);
        call.finite(radians, "angle");
        call.positiveAtMost(speed, drive.maxTurnRate(), "angular speed", "rad/s", "drive.max_turn_rate");
        return run("turn", values("angle", radians, "speed", speed), Math.abs(radians) / speed);
    }

    @Override
    public CompletableFuture<Void> arc(double radius, double angle, double speed) {
        Call call = call("arc(%.3f, %.4f, %.3f)", radius, angle, speed);
        call.finite(radius, "radius");
        call.finite(angle, "angle");
        if (radius == 0) {
            throw call.refused("a vehicle turns on the spot with turn(angle, speed); an arc needs a radius other than 0");
        }
        call.positiveAtMost(speed, drive.maxSpeed(), "speed", "m/s", "drive.max_speed");
        call.atMost(speed / Math.abs(radius), drive.maxTurnRate(), "turn rate on this arc (speed / |radius|)", "rad/s", "drive.max_turn_rate");
        return run("arc", values("radius", radius, "angle", angle, "speed", speed), Math.abs(radius * angle) / speed);
    }

    @Override
    public void drive(double linearSpeed, double angularSpeed) {
        Call call = call("drive(%.3f, %.3f)", linearSpeed, angularSpeed);
        call.finite(linearSpeed, "linear speed");
        call.finite(angularSpeed, "angular speed");
        call.atMost(Math.abs(linearSpeed), drive.maxSpeed(), "linear speed", "m/s", "drive.max_speed");
        call.atMost(Math.abs(angularSpeed), drive.maxTurnRate(), "angular speed", "rad/s", "drive.max_turn_rate");
        Map<String, Double> v = values("linear", linearSpeed, "angular", angularSpeed);
        ((HighLevelPlatform) platform).execute(new HighLevelCommand("drive", text("drive", v), v, Set.of(VehicleDrive.VEHICLE), Duration.ZERO,
                true, CommandPriority.NORMAL, description.watchdogTimeout(), ""));
    }

    @Override
    public CompletableFuture<Void> changeAltitude(double metres, double speed) {
        Call call = flying("changeAltitude(%.3f, %.3f)", metres, speed);
        call.finite(metres, "height");
        call.atMost(Math.abs(metres), MAX_ALTITUDE, "height", "m", "(the most a climb may be)");
        call.positiveAtMost(speed, drive.maxClimbRate(), "climb speed", "m/s", "drive.max_climb_rate");
        return run("climb", values("height", metres, "speed", speed), Math.abs(metres) / speed);
    }

    @Override
    public CompletableFuture<Void> takeOff(double altitude) {
        Call call = flying("takeOff(%.3f)", altitude);
        call.positive(altitude, "altitude");
        call.atMost(altitude, MAX_ALTITUDE, "altitude", "m", "(the highest take-off)");
        return run("takeoff", values("altitude", altitude), altitude / drive.maxClimbRate());
    }

    @Override
    public CompletableFuture<Void> land() {
        flying("land()");
        double altitude = reported().map(Pose::z).orElse(MAX_ALTITUDE / 10);
        // ArduCopter lands at 0.5 m/s, PX4 at 0.7 m/s; above 10 m both come down faster first
        return run("land", Map.of(), Math.max(0, altitude) / 0.5);
    }

    /** Nothing to do: the pose is the vehicle's report, not an integration of what was commanded. */
    @Override
    public void halted() {
    }

    @Override
    public Pose pose() {
        Call call = new Call(description.name(), "pose()");
        Pose now = reported().orElseThrow(() -> call.refused("the vehicle has not reported its position yet"));
        synchronized (poseLock) {
            if (reference == null) {
                reference = now;
            }
            return relative(now);
        }
    }

    @Override
    public void resetPose(Pose pose) {
        Call call = new Call(description.name(), "resetPose()");
        Pose now = reported().orElseThrow(() -> call.refused("the vehicle has not reported its position yet"));
        synchronized (poseLock) {
            reference = now;
            origin = pose;
        }
    }

    private Pose relative(Pose now) {
        double dx = now.x() - reference.x();
        double dy = now.y() - reference.y();
        double c = Math.cos(-reference.heading());
        double s = Math.sin(-reference.heading());
        double ax = dx * c - dy * s;
        double ay = dx * s + dy * c;
        double oc = Math.cos(origin.heading());
        double os = Math.sin(origin.heading());
        return new Pose(origin.x() + ax * oc - ay * os, origin.y() + ax * os + ay * oc,
                origin.heading() + now.heading() - reference.heading(), now.z());
    }

    private java.util.Optional<Pose> reported() {
        return platform instanceof PoseSource p ? p.reportedPose() : java.util.Optional.empty();
    }

    // ---- helpers ----

    private Call call(String format, Object... args) {
        Call call = Call.of(description.name(), format, args);
        if (cannotMove != null) {
            throw call.refused(cannotMove);
        }
        return call;
    }

    private Call flying(String format, Object... args) {
        Call call = args.length == 0 ? new Call(description.name(), format) : Call.of(description.name(), format, args);
        if (drive.medium() != VehicleDrive.Medium.AIR || !description.capabilities().contains(Capability.AIR)) {
            throw call.refused("it is a " + drive.medium().yamlName() + " vehicle (" + description.capabilities() + "), not an AIR one");
        }
        if (cannotMove != null) {
            throw call.refused(cannotMove);
        }
        return call;
    }

    private CompletableFuture<Void> run(String verb, Map<String, Double> v, double seconds) {
        HighLevelCommand command = new HighLevelCommand(verb, text(verb, v), v, Set.of(VehicleDrive.VEHICLE),
                Duration.ofNanos(Math.round((seconds + SETTLE_SECONDS) * 1e9)), false, CommandPriority.NORMAL, Duration.ZERO, "");
        return ((HighLevelPlatform) platform).execute(command);
    }

    private static String text(String verb, Map<String, Double> v) {
        StringBuilder b = new StringBuilder(verb).append('(');
        boolean first = true;
        for (Map.Entry<String, Double> e : v.entrySet()) {
            b.append(first ? "" : ", ").append(e.getKey()).append('=').append(String.format(Locale.ROOT, "%.3f", e.getValue()));
            first = false;
        }
        return b.append(')').toString();
    }

    private static Map<String, Double> values(Object... keysAndValues) {
        Map<String, Double> m = new LinkedHashMap<>();
        for (int i = 0; i < keysAndValues.length; i += 2) {
            m.put((String) keysAndValues[i], (Double) keysAndValues[i + 1]);
        }
        return m;
    }
}
