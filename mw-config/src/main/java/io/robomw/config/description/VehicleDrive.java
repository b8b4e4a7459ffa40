package io.robomw.config.description;

import java.util.Locale;
import java.util.Objects;

/**
 * A vehicle drive: the robot is a drone, a boat or a rover whose autopilot (ArduPilot or PX4,
 * spoken to over MAVLink) moves it to the targets it is given (positions, yaw, velocities). The
 * Configuration Layer never computes a motor's motion for it: it turns {@code move}, {@code turn},
 * {@code arc} and {@code drive} into those targets, within the limits written here.
 *
 * @param medium           where it moves
 * @param autopilot        its autopilot's dialect (mode numbers and quirks differ)
 * @param maxSpeed         metres per second, the fastest it is asked to go horizontally
 * @param maxClimbRate     metres per second, the fastest it is asked to climb or descend (0 for a
 *                         boat or rover)
 * @param maxTurnRate      radians per second, the fastest it is asked to turn
 * @param acceptanceRadius metres: a position target counts as reached within this distance
 * @param takeoffAltitude  metres above home a take-off climbs to when no altitude is given
 */
public record VehicleDrive(Medium medium, Autopilot autopilot, double maxSpeed, double maxClimbRate, double maxTurnRate,
                           double acceptanceRadius, double takeoffAltitude) implements DriveSpec {

    @Override
    public DriveKind kind() {
        return DriveKind.VEHICLE;
    }

    /** The actuator group every motion of a vehicle drives. */
    public static final String VEHICLE = "vehicle";

    /** Where a vehicle moves. */
    public enum Medium {
        /** A multirotor: it takes off, flies at an altitude and lands. */
        AIR,
        /** A surface boat: it stays on the world's water. */
        WATER,
        /** A ground rover. */
        GROUND;

        /** @return its name in a robot file */
        public String yamlName() {
            return name().toLowerCase(Locale.ROOT);
        }
    }

    /** The autopilot firmware a vehicle runs, which decides its flight modes' numbers. */
    public enum Autopilot {
        /** ArduPilot (ArduCopter, Rover). */
        ARDUPILOT,
        /** PX4 Autopilot. */
        PX4;

        /** @return its name in a robot file */
        public String yamlName() {
            return name().toLowerCase(Locale.ROOT);
        }
    }

    /** Checks the values. */
    public VehicleDrive {
        Objects.requireNonNull(medium, "medium");
        Objects.requireNonNull(autopilot, "autopilot");
        if (!(maxSpeed > 0) || !(maxTurnRate > 0) || !(acceptanceRadius > 0) || !(maxClimbRate >= 0) || !(takeoffAltitude >= 0)) {
            throw new IllegalArgumentException("a vehicle drive needs max_speed, max_turn_rate and acceptance_radius > 0 and"
                    + " max_climb_rate, takeoff_altitude >= 0; got " + maxSpeed + ", " + maxTurnRate + ", " + acceptanceRadius + ", "
                    + maxClimbRate + ", " + takeoffAltitude);
        }
        if (medium == Medium.AIR && maxClimbRate == 0) {
            throw new IllegalArgumentException("an air vehicle needs max_climb_rate > 0");
        }
    }
}
