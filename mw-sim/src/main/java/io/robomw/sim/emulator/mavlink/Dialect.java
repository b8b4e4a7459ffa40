package io.robomw.sim.emulator.mavlink;

import io.robomw.config.description.VehicleDrive;
import io.robomw.platform.mavlink.wire.MavAutopilot;

import java.util.Optional;

/**
 * What differs between ArduPilot and PX4 as the emulator mimics them (mavlink.md §1.3-1.5): the
 * autopilot code in HEARTBEAT, the flight modes' numbers, how long guided targets live, and how a
 * take-off's altitude is chosen.
 *
 * <pre>
 * mode      ArduCopter   Rover/boat   PX4 custom_mode = main &lt;&lt; 16 | sub &lt;&lt; 24
 * MANUAL    STABILIZE 0  MANUAL 0     MANUAL (1)
 * GUIDED    GUIDED 4     GUIDED 15    OFFBOARD (6)
 * AUTO      AUTO 3       AUTO 10      AUTO (4) . MISSION (4)
 * HOLD      LOITER 5     HOLD 4       AUTO (4) . LOITER (3)
 * TAKEOFF   -            -            AUTO (4) . TAKEOFF (2)
 * LAND      LAND 9       -            AUTO (4) . LAND (6)
 * RTL       RTL 6        RTL 11       AUTO (4) . RTL (5)
 * </pre>
 * Modes that need a pilot's sticks hold instead (no pilot here): ArduCopter ALT_HOLD 2, POSHOLD 16
 * and BRAKE 17, Rover LOITER 5 (HOLD), ACRO 1 and STEERING 3 (MANUAL), PX4 ALTCTL and POSCTL; the
 * HEARTBEAT then reports the number that was asked for.
 */
enum Dialect {
    /** ArduPilot: ArduCopter for multirotors, Rover for rovers and boats. */
    ARDUPILOT(MavAutopilot.ARDUPILOTMEGA),
    /** PX4 Autopilot. */
    PX4(MavAutopilot.PX4);

    /** PX4's main modes. */
    static final int PX4_MANUAL = 1;
    /** PX4's AUTO main mode. */
    static final int PX4_AUTO = 4;
    /** PX4's OFFBOARD main mode. */
    static final int PX4_OFFBOARD = 6;
    /** PX4 AUTO sub-modes. */
    static final int PX4_TAKEOFF = 2;
    /** PX4 AUTO.LOITER. */
    static final int PX4_LOITER = 3;
    /** PX4 AUTO.MISSION. */
    static final int PX4_MISSION = 4;
    /** PX4 AUTO.RTL. */
    static final int PX4_RTL = 5;
    /** PX4 AUTO.LAND. */
    static final int PX4_LAND = 6;

    private final MavAutopilot autopilot;

    Dialect(MavAutopilot autopilot) {
        this.autopilot = autopilot;
    }

    /** @return the HEARTBEAT autopilot code */
    MavAutopilot autopilot() {
        return autopilot;
    }

    /**
     * @param autopilot a robot file's autopilot
     * @return its dialect
     */
    static Dialect of(VehicleDrive.Autopilot autopilot) {
        return autopilot == VehicleDrive.Autopilot.PX4 ? PX4 : ARDUPILOT;
    }

    /**
     * @param mode   a flight mode
     * @param medium the vehicle's medium
     * @return its {@code custom_mode}, if the vehicle has that mode
     */
    Optional<Long> customMode(FlightMode mode, VehicleDrive.Medium medium) {
        if (this == PX4) {
            return Optional.of(switch (mode) {
                case MANUAL -> px4(PX4_MANUAL, 0);
                case GUIDED -> px4(PX4_OFFBOARD, 0);
                case AUTO -> px4(PX4_AUTO, PX4_MISSION);
                case HOLD -> px4(PX4_AUTO, PX4_LOITER);
                case TAKEOFF -> px4(PX4_AUTO, PX4_TAKEOFF);
                case LAND -> px4(PX4_AUTO, PX4_LAND);
                case RTL -> px4(PX4_AUTO, PX4_RTL);
            });
        }
        if (medium == VehicleDrive.Medium.AIR) {
            return switch (mode) {
                case MANUAL -> Optional.of(0L);
                case AUTO -> Optional.of(3L);
                case GUIDED -> Optional.of(4L);
                case HOLD -> Optional.of(5L);
                case RTL -> Optional.of(6L);
                case LAND -> Optional.of(9L);
                case TAKEOFF -> Optional.empty();
            };
        }
        return switch (mode) {
            case MANUAL -> Optional.of(0L);
            case HOLD -> Optional.of(4L);
            case AUTO -> Optional.of(10L);
            case RTL -> Optional.of(11L);
            case GUIDED -> Optional.of(15L);
            case TAKEOFF, LAND -> Optional.empty();
        };
    }

    /**
     * @param customMode a {@code custom_mode} (PX4: main mode in bits 16-23, sub-mode in 24-31)
     * @param medium     the vehicle's medium
     * @return the flight mode it stands for, if the vehicle has it
     */
    Optional<FlightMode> mode(long customMode, VehicleDrive.Medium medium) {
        for (FlightMode m : FlightMode.values()) {
            Optional<Long> code = customMode(m, medium);
            if (code.isPresent() && code.get() == customMode) {
                return Optional.of(m);
            }
        }
        if (this == ARDUPILOT && medium == VehicleDrive.Medium.AIR && (customMode == 2 || customMode == 16 || customMode == 17)) {
            return Optional.of(FlightMode.HOLD); // ALT_HOLD, POSHOLD, BRAKE: without a pilot's sticks, the copter holds
        }
        if (this == ARDUPILOT && medium != VehicleDrive.Medium.AIR && (customMode == 5 || customMode == 1 || customMode == 3)) {
            return Optional.of(customMode == 5 ? FlightMode.HOLD : FlightMode.MANUAL); // LOITER holds; ACRO, STEERING are manual
        }
        if (this == PX4 && (customMode >> 16 & 0xFF) == PX4_AUTO && (customMode >> 24 & 0xFF) == 0) {
            return Optional.of(FlightMode.HOLD); // AUTO without a sub-mode: PX4 holds (AUTO.READY)
        }
        if (this == PX4 && ((customMode >> 16 & 0xFF) == 2 || (customMode >> 16 & 0xFF) == 3)) {
            return Optional.of(FlightMode.HOLD); // ALTCTL, POSCTL: without a pilot's sticks, the vehicle holds
        }
        return Optional.empty();
    }

    /**
     * The custom mode a DO_SET_MODE command asks for: ArduPilot's mode number in param2; PX4's main
     * mode in param2 and sub-mode in param3.
     *
     * @param param2 the command's param2
     * @param param3 its param3 (NaN when unset)
     * @return the custom mode
     */
    long customModeOfCommand(double param2, double param3) {
        if (this == PX4) {
            long sub = Double.isFinite(param3) ? (long) param3 : 0;
            return px4((long) param2, sub);
        }
        return (long) param2;
    }

    private static long px4(long main, long sub) {
        return (main & 0xFF) << 16 | (sub & 0xFF) << 24;
    }

    /** @return the seconds a velocity target lives without being sent again (ArduPilot's guided timeout; PX4's COM_OF_LOSS_T) */
    double targetTimeoutSeconds() {
        return this == PX4 ? 1.0 : 3.0;
    }
}
