package io.robomw.api.spi;

import java.time.Duration;
import java.util.List;
import java.util.Objects;

/**
 * One command for the platform: several motors, started together, finished when all reach their
 * targets.
 *
 * @param name            a name for logs and errors, for example {@code move(0.5, 0.2)}
 * @param targets         one target per motor; no motor twice
 * @param priority        the clash rule class
 * @param watchdogTimeout for continuous commands: stop the motors unless the command is repeated
 *                        within this time; {@link Duration#ZERO} turns the watchdog off
 */
public record MotorCommand(String name, List<MotorTarget> targets, CommandPriority priority, Duration watchdogTimeout) {

    /** Checks the values and copies the list. */
    public MotorCommand {
        Objects.requireNonNull(name, "name");
        Objects.requireNonNull(priority, "priority");
        Objects.requireNonNull(watchdogTimeout, "watchdogTimeout");
        targets = List.copyOf(targets);
        if (targets.isEmpty()) {
            throw new IllegalArgumentException("command '" + name + "' has no motor targets");
        }
        for (int i = 0; i < targets.size(); i++) {
            for (int j = i + 1; j < targets.size(); j++) {
                String a = targets.get(i).port();
                String b = targets.get(j).port();
                if (a.hashCode() == b.hashCode() && a.equals(b)) { // the hash (kept in the string) first: no characters read

                    throw new IllegalArgumentException("command '" + name + "' names motor " + targets.get(i).port() + " twice: " + targets);
                }
            }
        }
        if (watchdogTimeout.isNegative()) {
            throw new IllegalArgumentException("command '" + name + "': watchdogTimeout must be >= 0, got " + watchdogTimeout);
        }
    }

    /**
     * @param name    the command's name
     * @param targets the motor targets
     * @return a normal-priority command without watchdog
     */
    public static MotorCommand of(String name, List<MotorTarget> targets) {
        return new MotorCommand(name, targets, CommandPriority.NORMAL, Duration.ZERO);
    }
}
