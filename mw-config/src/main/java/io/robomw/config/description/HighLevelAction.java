package io.robomw.config.description;

import java.util.List;
import java.util.Objects;
import java.util.Set;

/**
 * A named action a robot's firmware performs by itself ({@code sit}, {@code kick},
 * {@code head.pan}), run with {@code perform(name, args...)} as one high-level command rendered from
 * its template.
 *
 * @param name            the name {@code perform} takes, unique within the robot
 * @param command         its template; placeholders: its {@code arguments} and {@code duration}
 * @param arguments       the names of the values {@code perform} passes, in order, SI units
 *                        (an angle in radians)
 * @param durationSeconds how long the firmware takes to do it, &gt; 0
 * @param uses            the actuator groups it drives ({@code legs}, {@code head}, {@code tail}):
 *                        it interrupts, and is interrupted by, commands on any of them
 */
public record HighLevelAction(String name, CommandTemplate command, List<String> arguments, double durationSeconds, Set<String> uses) {

    /** Checks and copies. */
    public HighLevelAction {
        Objects.requireNonNull(name, "name");
        Objects.requireNonNull(command, "command");
        arguments = List.copyOf(arguments);
        uses = Set.copyOf(uses);
        if (!(durationSeconds > 0) || !Double.isFinite(durationSeconds)) {
            throw new IllegalArgumentException("action " + name + ": duration must be a number > 0 seconds, got " + durationSeconds);
        }
        if (uses.isEmpty()) {
            throw new IllegalArgumentException("action " + name + ": uses must name at least one actuator group (legs, head, tail...)");
        }
    }
}
