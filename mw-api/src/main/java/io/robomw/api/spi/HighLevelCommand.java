package io.robomw.api.spi;

import java.time.Duration;
import java.util.Map;
import java.util.Objects;
import java.util.Set;
import java.util.TreeMap;

/**
 * One command in a platform's own high-level vocabulary, for robots that move by commands of their
 * firmware instead of by motor rotations: a legged robot's "walk half a metre", "sit", "pan the
 * head". The Configuration Layer of a robot whose description has a legged drive builds one per
 * motion or named action from the command templates of the description, and hands it to a
 * {@link HighLevelPlatform}; it never computes joint or wheel rotations for it.
 *
 * <p>A platform runs it through its execution action thread under the same rules as motor
 * commands: it needs its {@link #actuators()} exclusively (a newer command on one of them
 * interrupts it, most recent wins), its {@link #priority()} decides clashes across priorities (a
 * safety stop is never pre-empted), and a {@link #continuous()} command is stopped unless it is
 * repeated within its {@link #watchdogTimeout()}.
 *
 * @param name             what the command is, for logs and errors, and for platforms that act on
 *                         its meaning rather than its text (a simulator): a motion verb
 *                         ({@code move}, {@code turn}, {@code arc}, {@code drive}) or the name of
 *                         a named action ({@code sit}, {@code head.pan})
 * @param text             the command in the platform's language, rendered from the description's
 *                         template, for example {@code robot.walk(0.5, 0.15)}
 * @param arguments        the values the text was rendered from, by name, in SI units (metres,
 *                         radians, seconds, metres and radians per second)
 * @param actuators        the actuator groups it drives exclusively ({@code legs}, {@code head},
 *                         {@code tail}): its requirements under the clash rule; at least one
 * @param expectedDuration how long it should take; a platform fails a command that runs far
 *                         longer (three times this, plus two seconds). {@link Duration#ZERO} for a
 *                         continuous command
 * @param continuous       whether it runs until replaced or stopped ({@code drive}); the same
 *                         command repeated on the same actuators refreshes it instead of
 *                         interrupting it
 * @param priority         the clash rule class
 * @param watchdogTimeout  for a continuous command: end it unless it is repeated within this;
 *                         {@link Duration#ZERO} turns the watchdog off
 * @param stopText         what the platform sends, after ending the command itself, when it is
 *                         interrupted, fails or its watchdog expires (for example
 *                         {@code robot.stop()}); empty for nothing more
 */
public record HighLevelCommand(String name, String text, Map<String, Double> arguments, Set<String> actuators,
                               Duration expectedDuration, boolean continuous, CommandPriority priority,
                               Duration watchdogTimeout, String stopText) {

    /** Checks the values, naming the command, and copies the collections. */
    public HighLevelCommand {
        Objects.requireNonNull(name, "name");
        Objects.requireNonNull(text, "text");
        Objects.requireNonNull(priority, "priority");
        Objects.requireNonNull(expectedDuration, "expectedDuration");
        Objects.requireNonNull(watchdogTimeout, "watchdogTimeout");
        Objects.requireNonNull(stopText, "stopText");
        arguments = java.util.Collections.unmodifiableMap(new TreeMap<>(arguments));
        actuators = Set.copyOf(actuators);
        if (text.isBlank()) {
            throw new IllegalArgumentException("command '" + name + "' has no text; a high-level command is sent as text");
        }
        if (actuators.isEmpty()) {
            throw new IllegalArgumentException("command '" + name + "' requires no actuator group; every command must name what it drives");
        }
        for (Map.Entry<String, Double> a : arguments.entrySet()) {
            if (a.getValue() == null || !Double.isFinite(a.getValue())) {
                throw new IllegalArgumentException("command '" + name + "': argument " + a.getKey() + " must be a finite number, got " + a.getValue());
            }
        }
        if (expectedDuration.isNegative()) {
            throw new IllegalArgumentException("command '" + name + "': expectedDuration must be >= 0, got " + expectedDuration);
        }
        if (watchdogTimeout.isNegative()) {
            throw new IllegalArgumentException("command '" + name + "': watchdogTimeout must be >= 0, got " + watchdogTimeout);
        }
        if (continuous && !expectedDuration.isZero()) {
            throw new IllegalArgumentException("command '" + name + "' is continuous, so it has no expected duration; got " + expectedDuration);
        }
    }

    /**
     * @param key an argument's name
     * @return its value
     * @throws IllegalArgumentException if the command has no such argument
     */
    public double argument(String key) {
        Double v = arguments.get(key);
        if (v == null) {
            throw new IllegalArgumentException("command '" + name + "' has no argument '" + key + "'; it has " + arguments.keySet());
        }
        return v;
    }
}
