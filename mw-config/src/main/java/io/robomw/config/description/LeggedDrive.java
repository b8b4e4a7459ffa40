package io.robomw.config.description;

import java.util.Objects;
import java.util.Optional;
import java.util.Set;

/**
 * A legged drive: the robot walks by its firmware's own high-level commands, whose templates the
 * description gives, within the gait's speed limits. Nothing here is about legs and joints: the
 * Configuration Layer renders {@code move}, {@code turn}, {@code arc} and {@code drive} into those
 * commands and never computes a leg's motion (the paper's second Configuration Layer
 * implementation, for the Sony Aibo).
 *
 * <p>Every walking command drives the actuator group {@value #LEGS}; a named action that also
 * uses it (sit, kick) interrupts a walk, and a walk interrupts it.
 *
 * @param maxSpeed    metres per second, the fastest walk forwards or backwards
 * @param maxTurnRate radians per second, the fastest turn
 * @param move        walk straight: placeholders {@code distance} (m, negative backwards),
 *                    {@code speed} (m/s, &gt; 0), {@code duration} (s)
 * @param turn        turn on the spot: {@code angle} (rad, positive left), {@code speed} (rad/s,
 *                    &gt; 0), {@code duration} (s)
 * @param arc         walk an arc, if the firmware can: {@code radius} (m, positive centre on the
 *                    left), {@code angle} (rad of arc, positive forwards), {@code speed} (m/s),
 *                    {@code duration} (s)
 * @param drive       walk on at velocities until told otherwise (continuous, refreshed within the
 *                    watchdog), if the firmware can: {@code linear} (m/s), {@code angular} (rad/s)
 * @param stop        sent after ending a walk that was interrupted or failed, if the firmware
 *                    needs it to stand still; no placeholders
 * @param gait        how the simulator models the walk
 */
public record LeggedDrive(double maxSpeed, double maxTurnRate, CommandTemplate move, CommandTemplate turn,
                          Optional<CommandTemplate> arc, Optional<CommandTemplate> drive, Optional<CommandTemplate> stop,
                          Gait gait) implements DriveSpec {

    /** The actuator group every walking command drives. */
    public static final String LEGS = "legs";

    /** The placeholders of {@code move}. */
    public static final Set<String> MOVE_VALUES = Set.of("distance", "speed", "duration");
    /** The placeholders of {@code turn}. */
    public static final Set<String> TURN_VALUES = Set.of("angle", "speed", "duration");
    /** The placeholders of {@code arc}. */
    public static final Set<String> ARC_VALUES = Set.of("radius", "angle", "speed", "duration");
    /** The placeholders of {@code drive}. */
    public static final Set<String> DRIVE_VALUES = Set.of("linear", "angular");

    /** Checks the limits, naming the value and the rule. */
    public LeggedDrive {
        requirePositive("max_speed", maxSpeed);
        requirePositive("max_turn_rate", maxTurnRate);
        Objects.requireNonNull(move, "move");
        Objects.requireNonNull(turn, "turn");
        Objects.requireNonNull(arc, "arc");
        Objects.requireNonNull(drive, "drive");
        Objects.requireNonNull(stop, "stop");
        Objects.requireNonNull(gait, "gait");
    }

    /** @return {@link DriveKind#LEGGED} */
    @Override
    public DriveKind kind() {
        return DriveKind.LEGGED;
    }

    private static void requirePositive(String key, double value) {
        if (!(value > 0) || !Double.isFinite(value)) {
            throw new IllegalArgumentException(key + " must be a number > 0, got " + value);
        }
    }

    /**
     * How the simulator (and the Aibo emulator) models the walk: the body moves at the commanded
     * velocities, each step of the gait a little faster or slower (jitter) and a little short of
     * them (slip), drawn from the world's seeded generator. A real robot ignores these values.
     *
     * @param stepFrequency steps per second of the gait, &gt; 0 (joints swing at this rate)
     * @param jitter        standard deviation of each step's speed, as a fraction of the commanded
     *                      speed, ≥ 0
     * @param slip          fraction of the commanded motion lost to the feet slipping, 0 ≤ slip &lt; 1
     */
    public record Gait(double stepFrequency, double jitter, double slip) {

        /** A gait without imperfections at two steps a second. */
        public static final Gait DEFAULT = new Gait(2.0, 0, 0);

        /** Checks the values. */
        public Gait {
            if (!(stepFrequency > 0) || !Double.isFinite(stepFrequency)) {
                throw new IllegalArgumentException("gait.step_frequency must be a number > 0, got " + stepFrequency);
            }
            if (!(jitter >= 0) || !Double.isFinite(jitter)) {
                throw new IllegalArgumentException("gait.jitter must be a number >= 0, got " + jitter);
            }
            if (!(slip >= 0 && slip < 1)) {
                throw new IllegalArgumentException("gait.slip must be in [0, 1), got " + slip);
            }
        }
    }
}
