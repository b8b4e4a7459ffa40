package io.robomw.config.robot;

import io.robomw.api.spi.CommandPriority;
import io.robomw.api.spi.HighLevelCommand;
import io.robomw.api.spi.HighLevelPlatform;
import io.robomw.api.spi.MotorCommand;
import io.robomw.api.spi.MotorTarget;
import io.robomw.api.spi.RobotPlatform;
import io.robomw.config.description.ActuatorSpec;
import io.robomw.config.description.HighLevelAction;
import io.robomw.config.description.LeggedDrive;
import io.robomw.config.description.RobotDescription;
import io.robomw.config.drive.Call;
import io.robomw.config.drive.DriveControl;
import io.robomw.config.legged.LeggedDriveControl;

import java.time.Duration;
import java.util.ArrayList;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Map;
import java.util.concurrent.CompletableFuture;

/**
 * The robot's named actions, as {@code perform} runs them: an extra actuator's action
 * ({@code gripper.open}: its motor turns by the description's angle, or by the one given) or a
 * high-level action of the firmware ({@code sit}, {@code head.pan}: its template rendered with the
 * arguments, handed to a {@link HighLevelPlatform}). Every check happens before anything is sent.
 * An action on the legs ends the walk under way, for the drive's pose. Stateless; thread-safe.
 */
final class NamedActions {

    private final RobotPlatform platform;

    /**
     * @param platform the opened platform
     */
    NamedActions(RobotPlatform platform) {
        this.platform = platform;
    }

    /**
     * @param d the description in force
     * @return its actions: each actuator's as {@code actuator.action} (sorted), then the high-level ones
     */
    static List<String> list(RobotDescription d) {
        List<String> out = new ArrayList<>();
        for (ActuatorSpec a : d.actuators()) {
            a.actions().keySet().stream().sorted().forEach(action -> out.add(a.name() + "." + action));
        }
        d.highLevelActions().forEach(a -> out.add(a.name()));
        return out;
    }

    /**
     * @param d      the description in force
     * @param drive  the drive chosen for it, told when an action takes the legs
     * @param action the action's name
     * @param args   its arguments
     * @return the platform's command future: completes when the action is done; cancelling it
     *         ends the action
     */
    CompletableFuture<Void> perform(RobotDescription d, DriveControl drive, String action, double... args) {
        Call call = new Call(d.name(), "perform(\"" + action + "\")");
        HighLevelAction highLevel = d.highLevelAction(action).orElse(null);
        return highLevel != null ? performHighLevel(d, drive, call, highLevel, args) : performActuator(d, call, action, args);
    }

    private CompletableFuture<Void> performActuator(RobotDescription d, Call call, String action, double... args) {
        int dot = action.indexOf('.');
        String actuatorName = dot < 0 ? action : action.substring(0, dot);
        ActuatorSpec actuator = d.actuators().stream().filter(a -> a.name().equals(actuatorName)).findFirst()
                .orElseThrow(() -> call.refused("it has no actuator '" + actuatorName + "'; its actions are " + list(d)));
        ActuatorSpec.Action spec = dot < 0 ? null : actuator.actions().get(action.substring(dot + 1));
        if (spec == null) {
            throw call.refused("its actions are " + list(d));
        }
        double degrees;
        if (spec.degrees().isPresent()) {
            if (args.length != 0) {
                throw call.refused("this action takes no arguments, got " + args.length);
            }
            degrees = spec.degrees().getAsDouble();
        } else {
            if (args.length != 1 || !Double.isFinite(args[0])) {
                throw call.refused("this action takes one angle in radians");
            }
            degrees = Math.toDegrees(args[0]);
        }
        return platform.run(MotorCommand.of(call.text(), List.of(MotorTarget.rotate(actuator.port(), degrees, spec.degreesPerSecond()))));
    }

    private CompletableFuture<Void> performHighLevel(RobotDescription d, DriveControl drive, Call call, HighLevelAction action, double... args) {
        if (args.length != action.arguments().size()) {
            throw call.refused("this action takes " + action.arguments().size() + " argument(s) " + action.arguments()
                    + " (SI units), got " + args.length);
        }
        Map<String, Double> values = new LinkedHashMap<>();
        for (int i = 0; i < args.length; i++) {
            values.put(action.arguments().get(i), call.finite(args[i], action.arguments().get(i)));
        }
        values.put("duration", action.durationSeconds());
        if (!(platform instanceof HighLevelPlatform hl)) {
            throw call.refused(LeggedDriveControl.noHighLevelCommands(d));
        }
        String text;
        try {
            text = action.command().render(values);
        } catch (IllegalArgumentException e) {
            throw call.refused(e.getMessage());
        }
        boolean legs = action.uses().contains(LeggedDrive.LEGS);
        String stop = legs ? d.leggedDrive().map(LeggedDriveControl::stopText).orElse("") : "";
        HighLevelCommand command = new HighLevelCommand(action.name(), text, values, action.uses(),
                Duration.ofNanos(Math.round(action.durationSeconds() * 1e9)), false, CommandPriority.NORMAL, Duration.ZERO, stop);
        if (legs) {
            drive.halted();
        }
        return hl.execute(command);
    }
}
