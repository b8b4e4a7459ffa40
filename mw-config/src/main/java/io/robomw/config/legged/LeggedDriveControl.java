package io.robomw.config.legged;

import io.robomw.api.Capability;
import io.robomw.api.Pose;
import io.robomw.api.spi.CommandPriority;
import io.robomw.api.spi.HighLevelCommand;
import io.robomw.api.spi.HighLevelPlatform;
import io.robomw.api.spi.RobotPlatform;
import io.robomw.config.description.CommandTemplate;
import io.robomw.config.description.LeggedDrive;
import io.robomw.config.description.RobotDescription;
import io.robomw.config.drive.Call;
import io.robomw.config.drive.DriveControl;
import io.robomw.config.drive.Movement;

import java.time.Duration;
import java.util.LinkedHashMap;
import java.util.Map;
import java.util.Set;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.atomic.AtomicLong;

/**
 * The Configuration Layer's second implementation (the paper's, for the Sony Aibo): a robot with a
 * legged drive moves by its firmware's own walking commands. Each motion is checked against the
 * gait's limits, rendered from the description's template with its values, and handed to the
 * platform as one {@link HighLevelCommand}; no leg or joint motion is computed here.
 *
 * <p>Every check happens before anything is sent, and a failed check is an
 * {@link io.robomw.api.UnsupportedActionException} naming the robot, the call and the limit. The
 * pose is dead reckoning from the commanded gait ({@link DeadReckoning}, which listens to the
 * motions this drive reports), kept across reloads.
 *
 * <p>Thread-safe.
 */
public final class LeggedDriveControl implements DriveControl {

    private final RobotDescription description;
    private final LeggedDrive drive;
    private final RobotPlatform platform;
    /** Why it cannot walk at all (not a ground robot, no high-level commands), or {@code null}. */
    private final String cannotWalk;
    private final String stopText;
    /** The pose, or {@code null} when the platform takes no high-level commands (nothing moves). */
    private final DeadReckoning reckoning;
    /** Numbers the motions, across reloads. */
    private final AtomicLong movements;

    /**
     * @param description the description in force
     * @param drive       its legged drive
     * @param platform    the opened platform; it must implement {@link HighLevelPlatform} for
     *                    anything to move
     * @param previous    the drive chosen for the description before (a reload), whose pose
     *                    carries over, or {@code null}
     */
    public LeggedDriveControl(RobotDescription description, LeggedDrive drive, RobotPlatform platform, LeggedDriveControl previous) {
        this.description = description;
        this.drive = drive;
        this.platform = platform;
        this.stopText = stopText(drive);
        if (!description.capabilities().contains(Capability.GROUND)) {
            this.cannotWalk = "it is a " + description.capabilities() + " robot, not a GROUND one";
        } else if (!(platform instanceof HighLevelPlatform)) {
            this.cannotWalk = noHighLevelCommands(description);
        } else {
            this.cannotWalk = null;
        }
        this.reckoning = previous != null && previous.reckoning != null ? previous.reckoning
                : platform instanceof HighLevelPlatform hl ? new DeadReckoning(hl.clock()) : null;
        this.movements = previous != null ? previous.movements : new AtomicLong();
    }

    @Override
    public RobotDescription description() {
        return description;
    }

    @Override
    public CompletableFuture<Void> move(double distance, double speed) {
        Call call = call("move(%.3f, %.3f)", distance, speed);
        call.finite(distance, "distance");
        call.positiveAtMost(speed, drive.maxSpeed(), "speed", "m/s", "drive.max_speed");
        double seconds = Math.abs(distance) / speed;
        Map<String, Double> values = values("distance", distance, "speed", speed, "duration", seconds);
        return walk(call, "move", drive.move(), values, seconds, Math.signum(distance) * speed, 0);
    }

    @Override
    public CompletableFuture<Void> turn(double radians, double speed) {
        Call call = call("turn(%.4f, %.4f)", radians, speed);
        call.finite(radians, "angle");
        call.positiveAtMost(speed, drive.maxTurnRate(), "angular speed", "rad/s", "drive.max_turn_rate");
        double seconds = Math.abs(radians) / speed;
        Map<String, Double> values = values("angle", radians, "speed", speed, "duration", seconds);
        return walk(call, "turn", drive.turn(), values, seconds, 0, Math.signum(radians) * speed);
    }

    @Override
    public CompletableFuture<Void> arc(double radius, double angle, double speed) {
        Call call = call("arc(%.3f, %.4f, %.3f)", radius, angle, speed);
        CommandTemplate template = drive.arc().orElseThrow(() -> call.refused(
                "its legged drive gives no arc command (drive.commands.arc); walk it as turns and moves"));
        call.finite(radius, "radius");
        call.finite(angle, "angle");
        if (radius == 0) {
            throw call.refused("a legged robot turns on the spot with turn(angle, speed); an arc needs a radius other than 0");
        }
        call.positiveAtMost(speed, drive.maxSpeed(), "speed", "m/s", "drive.max_speed");
        call.atMost(speed / Math.abs(radius), drive.maxTurnRate(), "turn rate on this arc (speed / |radius|)", "rad/s", "drive.max_turn_rate");
        double seconds = Math.abs(radius * angle) / speed;
        double linear = Math.signum(angle) * speed;
        Map<String, Double> values = values("radius", radius, "angle", angle, "speed", speed, "duration", seconds);
        return walk(call, "arc", template, values, seconds, linear, linear / radius);
    }

    @Override
    public void drive(double linearSpeed, double angularSpeed) {
        Call call = call("drive");
        CommandTemplate template = drive.drive().orElseThrow(() -> call.refused("its legged drive gives no drive command (drive.commands.drive)"));
        call.finite(linearSpeed, "linear speed");
        call.finite(angularSpeed, "angular speed");
        call.atMost(linearSpeed, drive.maxSpeed(), "linear speed", "m/s", "drive.max_speed");
        call.atMost(angularSpeed, drive.maxTurnRate(), "angular speed", "rad/s", "drive.max_turn_rate");
        Map<String, Double> values = values("linear", linearSpeed, "angular", angularSpeed);
        HighLevelCommand command = new HighLevelCommand("drive", render(call, template, values), values, Set.of(LeggedDrive.LEGS),
                Duration.ZERO, true, CommandPriority.NORMAL, description.watchdogTimeout(), stopText);
        Movement movement = new Movement(movements.incrementAndGet(), linearSpeed, angularSpeed, Double.POSITIVE_INFINITY);
        reckoning.motionStarted(movement);
        reckoning.endOf(((HighLevelPlatform) platform).execute(command), movement);
    }

    /** The legs stopped now (a stop, or a named action on the legs such as sit): the current walk ends. */
    @Override
    public void halted() {
        if (reckoning != null) {
            reckoning.halted();
        }
    }

    /**
     * The pose by dead reckoning from the commanded gait, relative to where the robot was opened
     * or last reset.
     */
    @Override
    public Pose pose() {
        return reckoning(new Call(description.name(), "pose()")).pose();
    }

    @Override
    public void resetPose(Pose pose) {
        reckoning(new Call(description.name(), "resetPose()")).reset(pose);
    }

    /**
     * @param d a description
     * @return why a robot of that description cannot walk or perform high-level actions on a
     *         platform that takes no high-level commands
     */
    public static String noHighLevelCommands(RobotDescription d) {
        return "platform '" + d.platform() + "' does not take high-level commands, which a legged drive or a high-level action needs";
    }

    /**
     * @param d a legged drive
     * @return its stop command, rendered, or empty if it has none
     */
    public static String stopText(LeggedDrive d) {
        return d.stop().map(t -> t.render(Map.of())).orElse("");
    }

    // ---- helpers ----

    private CompletableFuture<Void> walk(Call call, String verb, CommandTemplate template, Map<String, Double> values, double seconds,
                                         double linear, double angular) {
        HighLevelCommand command = new HighLevelCommand(verb, render(call, template, values), values, Set.of(LeggedDrive.LEGS),
                seconds(seconds), false, CommandPriority.NORMAL, Duration.ZERO, stopText);
        Movement movement = new Movement(movements.incrementAndGet(), linear, angular, seconds);
        reckoning.motionStarted(movement);
        return reckoning.endOf(((HighLevelPlatform) platform).execute(command), movement);
    }

    private Call call(String format, Object... args) {
        Call call = args.length == 0 ? new Call(description.name(), format) : Call.of(description.name(), format, args);
        if (cannotWalk != null) {
            throw call.refused(cannotWalk);
        }
        return call;
    }

    private DeadReckoning reckoning(Call call) {
        if (reckoning == null) {
            throw call.refused(noHighLevelCommands(description));
        }
        return reckoning;
    }

    private static String render(Call call, CommandTemplate template, Map<String, Double> values) {
        try {
            return template.render(values);
        } catch (IllegalArgumentException e) {
            throw call.refused(e.getMessage());
        }
    }

    private static Duration seconds(double s) {
        return Duration.ofNanos(Math.round(s * 1e9));
    }

    private static Map<String, Double> values(Object... keysAndValues) {
        Map<String, Double> m = new LinkedHashMap<>();
        for (int i = 0; i < keysAndValues.length; i += 2) {
            m.put((String) keysAndValues[i], (Double) keysAndValues[i + 1]);
        }
        return m;
    }
}
