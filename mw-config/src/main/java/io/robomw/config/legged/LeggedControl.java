package io.robomw.config.legged;

import io.robomw.api.Capability;
import io.robomw.api.Pose;
import io.robomw.api.UnsupportedActionException;
import io.robomw.api.spi.CommandPriority;
import io.robomw.api.spi.HighLevelCommand;
import io.robomw.api.spi.HighLevelPlatform;
import io.robomw.api.spi.RobotPlatform;
import io.robomw.config.description.CommandTemplate;
import io.robomw.config.description.HighLevelAction;
import io.robomw.config.description.LeggedDrive;
import io.robomw.config.description.RobotDescription;

import java.time.Duration;
import java.util.LinkedHashMap;
import java.util.Locale;
import java.util.Map;
import java.util.Set;
import java.util.concurrent.CompletableFuture;
import java.util.function.Supplier;

/**
 * The Configuration Layer's second implementation (the paper's, for the Sony Aibo): a robot with a
 * legged drive moves by its firmware's own walking commands. Each motion is checked against the
 * gait's limits, rendered from the description's template with its values, and handed to the
 * platform as one {@link HighLevelCommand}; no leg or joint motion is computed here. Named actions
 * ({@code sit}, {@code head.pan}) go the same way.
 *
 * <p>Every check happens before anything is sent, and a failed check is an
 * {@link UnsupportedActionException} naming the robot, the call and the limit. The pose is dead
 * reckoning from the commanded gait ({@link DeadReckoning}).
 *
 * <p>Thread-safe; reads the description in force on every call.
 */
public final class LeggedControl {

    private final Supplier<RobotDescription> description;
    private final RobotPlatform platform;
    private volatile DeadReckoning deadReckoning;

    /**
     * @param description the description in force
     * @param platform    the opened platform; it must implement {@link HighLevelPlatform} for
     *                    anything to move
     */
    public LeggedControl(Supplier<RobotDescription> description, RobotPlatform platform) {
        this.description = description;
        this.platform = platform;
    }

    /**
     * @param distance metres, negative backwards
     * @param speed    metres per second, &gt; 0 and at most {@code drive.max_speed}
     * @return completes when the platform reports the walk done
     */
    public CompletableFuture<Void> move(double distance, double speed) {
        String call = String.format(Locale.ROOT, "move(%.3f, %.3f)", distance, speed);
        LeggedDrive d = drive(call);
        requireFinite(call, distance, "distance");
        requireWithin(call, speed, d.maxSpeed(), "speed", "m/s", "drive.max_speed");
        double seconds = Math.abs(distance) / speed;
        Map<String, Double> values = values("distance", distance, "speed", speed, "duration", seconds);
        return walk(call, "move", d.move(), values, seconds, Math.signum(distance) * speed, 0, d);
    }

    /**
     * @param radians positive turns left
     * @param speed   radians per second, &gt; 0 and at most {@code drive.max_turn_rate}
     * @return completes when the platform reports the turn done
     */
    public CompletableFuture<Void> turn(double radians, double speed) {
        String call = String.format(Locale.ROOT, "turn(%.4f, %.4f)", radians, speed);
        LeggedDrive d = drive(call);
        requireFinite(call, radians, "angle");
        requireWithin(call, speed, d.maxTurnRate(), "angular speed", "rad/s", "drive.max_turn_rate");
        double seconds = Math.abs(radians) / speed;
        Map<String, Double> values = values("angle", radians, "speed", speed, "duration", seconds);
        return walk(call, "turn", d.turn(), values, seconds, 0, Math.signum(radians) * speed, d);
    }

    /**
     * @param radius metres from the arc's centre, positive centre on the left; not 0
     * @param angle  radians of arc, positive forwards
     * @param speed  metres per second of the body, &gt; 0
     * @return completes when the platform reports the arc done
     */
    public CompletableFuture<Void> arc(double radius, double angle, double speed) {
        String call = String.format(Locale.ROOT, "arc(%.3f, %.4f, %.3f)", radius, angle, speed);
        LeggedDrive d = drive(call);
        CommandTemplate template = d.arc().orElseThrow(() -> new UnsupportedActionException(name(), call,
                "its legged drive gives no arc command (drive.commands.arc); walk it as turns and moves"));
        requireFinite(call, radius, "radius");
        requireFinite(call, angle, "angle");
        if (radius == 0) {
            throw new UnsupportedActionException(name(), call, "a legged robot turns on the spot with turn(angle, speed); an arc needs a radius other than 0");
        }
        requireWithin(call, speed, d.maxSpeed(), "speed", "m/s", "drive.max_speed");
        double rate = speed / Math.abs(radius);
        requireWithin(call, rate, d.maxTurnRate(), "turn rate on this arc (speed / |radius|)", "rad/s", "drive.max_turn_rate");
        double seconds = Math.abs(radius * angle) / speed;
        double linear = Math.signum(angle) * speed;
        Map<String, Double> values = values("radius", radius, "angle", angle, "speed", speed, "duration", seconds);
        return walk(call, "arc", template, values, seconds, linear, linear / radius, d);
    }

    /**
     * Walks on at velocities: a continuous command, stopped by the platform unless repeated within
     * the description's watchdog timeout. Returns at once.
     *
     * @param linearSpeed  metres per second, negative backwards
     * @param angularSpeed radians per second, positive left
     */
    public void drive(double linearSpeed, double angularSpeed) {
        String call = "drive";
        LeggedDrive d = drive(call);
        CommandTemplate template = d.drive().orElseThrow(() -> new UnsupportedActionException(name(), call,
                "its legged drive gives no drive command (drive.commands.drive)"));
        requireFinite(call, linearSpeed, "linear speed");
        requireFinite(call, angularSpeed, "angular speed");
        if (Math.abs(linearSpeed) > d.maxSpeed() * (1 + 1e-9)) {
            throw new UnsupportedActionException(name(), call, String.format(Locale.ROOT,
                    "linear speed %.3f m/s is above its walking maximum of %.3f m/s (drive.max_speed)", linearSpeed, d.maxSpeed()));
        }
        if (Math.abs(angularSpeed) > d.maxTurnRate() * (1 + 1e-9)) {
            throw new UnsupportedActionException(name(), call, String.format(Locale.ROOT,
                    "angular speed %.3f rad/s is above its maximum of %.3f rad/s (drive.max_turn_rate)", angularSpeed, d.maxTurnRate()));
        }
        HighLevelPlatform hl = highLevel(call);
        Map<String, Double> values = values("linear", linearSpeed, "angular", angularSpeed);
        HighLevelCommand command = new HighLevelCommand(call, render(call, template, values), values, Set.of(LeggedDrive.LEGS),
                Duration.ZERO, true, CommandPriority.NORMAL, description.get().watchdogTimeout(), stopText(d));
        DeadReckoning.Segment segment = reckoning(hl).begin(linearSpeed, angularSpeed, Double.POSITIVE_INFINITY);
        track(hl.execute(command), segment);
    }

    /**
     * @param actionName a high-level action of the description
     * @param args       its arguments, SI units, as many as it lists
     * @return completes when the platform reports it done
     * @throws UnsupportedActionException if the robot has no such action or the arguments do not fit
     */
    public CompletableFuture<Void> perform(String actionName, double... args) {
        String call = "perform(\"" + actionName + "\")";
        RobotDescription rd = description.get();
        HighLevelAction action = rd.highLevelAction(actionName).orElseThrow(() -> new UnsupportedActionException(name(), call,
                "it has no such action"));
        if (args.length != action.arguments().size()) {
            throw new UnsupportedActionException(name(), call, "this action takes " + action.arguments().size() + " argument(s) "
                    + action.arguments() + " (SI units), got " + args.length);
        }
        Map<String, Double> values = new LinkedHashMap<>();
        for (int i = 0; i < args.length; i++) {
            requireFinite(call, args[i], action.arguments().get(i));
            values.put(action.arguments().get(i), args[i]);
        }
        values.put("duration", action.durationSeconds());
        HighLevelPlatform hl = highLevel(call);
        boolean legs = action.uses().contains(LeggedDrive.LEGS);
        String stop = legs ? rd.leggedDrive().map(this::stopText).orElse("") : "";
        HighLevelCommand command = new HighLevelCommand(actionName, render(call, action.command(), values), values, action.uses(),
                seconds(action.durationSeconds()), false, CommandPriority.NORMAL, Duration.ZERO, stop);
        if (legs) {
            reckoning(hl).halt();
        }
        return hl.execute(command);
    }

    /** The robot was told to stop: the current walk ends now. */
    public void halted() {
        DeadReckoning r = deadReckoning;
        if (r != null) {
            r.halt();
        }
    }

    /**
     * The pose by dead reckoning from the commanded gait, relative to where the robot was opened
     * or last reset.
     *
     * @return the estimate
     */
    public Pose pose() {
        return reckoning(highLevel("pose()")).pose();
    }

    /**
     * @param pose the robot's pose now
     */
    public void resetPose(Pose pose) {
        reckoning(highLevel("resetPose()")).reset(pose);
    }

    // ---- helpers ----

    private CompletableFuture<Void> walk(String call, String verb, CommandTemplate template, Map<String, Double> values, double seconds,
                                         double linear, double angular, LeggedDrive d) {
        HighLevelPlatform hl = highLevel(call);
        HighLevelCommand command = new HighLevelCommand(verb, render(call, template, values), values, Set.of(LeggedDrive.LEGS),
                seconds(seconds), false, CommandPriority.NORMAL, Duration.ZERO, stopText(d));
        DeadReckoning.Segment segment = reckoning(hl).begin(linear, angular, seconds);
        return track(hl.execute(command), segment);
    }

    private CompletableFuture<Void> track(CompletableFuture<Void> done, DeadReckoning.Segment segment) {
        DeadReckoning r = deadReckoning;
        return done.whenComplete((v, e) -> {
            if (e == null) {
                r.completed(segment);
            } else {
                r.ended(segment);
            }
        });
    }

    private String stopText(LeggedDrive d) {
        return d.stop().map(t -> t.render(Map.of())).orElse("");
    }

    private LeggedDrive drive(String call) {
        RobotDescription d = description.get();
        if (!d.capabilities().contains(Capability.GROUND)) {
            throw new UnsupportedActionException(d.name(), call, "it is a " + d.capabilities() + " robot, not a GROUND one");
        }
        return d.leggedDrive().orElseThrow(() -> new UnsupportedActionException(d.name(), call, "its description has no legged drive"));
    }

    private HighLevelPlatform highLevel(String call) {
        if (platform instanceof HighLevelPlatform hl) {
            return hl;
        }
        RobotDescription d = description.get();
        throw new UnsupportedActionException(d.name(), call, "platform '" + d.platform()
                + "' does not take high-level commands, which a legged drive or a high-level action needs");
    }

    private DeadReckoning reckoning(HighLevelPlatform hl) {
        DeadReckoning r = deadReckoning;
        if (r == null) {
            synchronized (this) {
                r = deadReckoning;
                if (r == null) {
                    r = new DeadReckoning(hl.clock());
                    deadReckoning = r;
                }
            }
        }
        return r;
    }

    private String render(String call, CommandTemplate template, Map<String, Double> values) {
        try {
            return template.render(values);
        } catch (IllegalArgumentException e) {
            throw new UnsupportedActionException(name(), call, e.getMessage());
        }
    }

    private void requireWithin(String call, double value, double max, String what, String unit, String key) {
        if (!(value > 0) || !Double.isFinite(value)) {
            throw new UnsupportedActionException(name(), call, what + " must be a number > 0, got " + value);
        }
        if (value > max * (1 + 1e-9)) {
            throw new UnsupportedActionException(name(), call, String.format(Locale.ROOT,
                    "%s %.3f %s is above its maximum of %.3f %s (%s)", what, value, unit, max, unit, key));
        }
    }

    private void requireFinite(String call, double value, String what) {
        if (!Double.isFinite(value)) {
            throw new UnsupportedActionException(name(), call, what + " must be a finite number, got " + value);
        }
    }

    private String name() {
        return description.get().name();
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
