package io.robomw.platform.mavlink.gcs;

import io.robomw.platform.mavlink.wire.MavAutopilot;
import io.robomw.platform.mavlink.wire.MavType;

/**
 * What the ground station learns of a vehicle from its HEARTBEAT: its autopilot's dialect and
 * whether it flies, floats or drives, which decide the numbers of its modes (mavlink.md §1.3):
 * ArduPilot's GUIDED is 4 on copters and 15 on rovers and boats; PX4's OFFBOARD is main mode 6.
 * A type 11 (surface boat) is treated as a rover (mavros once failed on it).
 *
 * @param autopilot the HEARTBEAT's autopilot
 * @param medium    where it moves
 */
public record VehicleKind(Dialect autopilot, Medium medium) {

    /** The autopilot firmware, by its quirks. */
    public enum Dialect {
        /** ArduPilot (MAV_AUTOPILOT 3). */
        ARDUPILOT,
        /** PX4 (MAV_AUTOPILOT 12). */
        PX4,
        /** Anything else, treated as PX4 is (MAVSDK's "pure" MAVLink). */
        GENERIC
    }

    /** Where the vehicle moves. */
    public enum Medium {
        /** A multirotor (or another flyer). */
        AIR,
        /** A surface boat. */
        WATER,
        /** A ground rover. */
        GROUND
    }

    /**
     * @param type      HEARTBEAT.type
     * @param autopilot HEARTBEAT.autopilot
     * @return what they say
     */
    public static VehicleKind of(long type, long autopilot) {
        Dialect d = autopilot == MavAutopilot.ARDUPILOTMEGA.code() ? Dialect.ARDUPILOT
                : autopilot == MavAutopilot.PX4.code() ? Dialect.PX4 : Dialect.GENERIC;
        Medium m = type == MavType.SURFACE_BOAT.code() ? Medium.WATER
                : type == MavType.GROUND_ROVER.code() ? Medium.GROUND : Medium.AIR;
        return new VehicleKind(d, m);
    }

    /** @return whether it is an ArduPilot (else PX4 rules apply) */
    public boolean ardupilot() {
        return autopilot == Dialect.ARDUPILOT;
    }

    /** @return the custom mode the ground station flies it in: GUIDED (ArduPilot) or OFFBOARD (PX4) */
    public long guidedMode() {
        if (ardupilot()) {
            return medium == Medium.AIR ? 4 : 15;
        }
        return 6L << 16;
    }

    /** @return the custom mode it holds in: LOITER 5 (copter), HOLD 4 (rover, boat), PX4 AUTO.LOITER */
    public long holdMode() {
        if (ardupilot()) {
            return medium == Medium.AIR ? 5 : 4;
        }
        return 4L << 16 | 3L << 24;
    }

    /**
     * @param customMode a custom mode
     * @return DO_SET_MODE's param2 and param3 for it: ArduPilot's mode number; PX4's main and sub-mode
     */
    public double[] setModeParams(long customMode) {
        if (ardupilot()) {
            return new double[]{customMode, 0};
        }
        return new double[]{customMode >> 16 & 0xFF, customMode >> 24 & 0xFF};
    }
}
