package io.robomw.sim.emulator.mavlink;

/**
 * The flight modes the emulated autopilot knows, whatever their numbers in each dialect
 * ({@link Dialect} maps them to HEARTBEAT's {@code custom_mode} and back).
 */
enum FlightMode {
    /** No guidance: ArduCopter STABILIZE, Rover MANUAL, PX4 MANUAL. The vehicle holds still here (no pilot). */
    MANUAL,
    /** Targets from a ground station: ArduPilot GUIDED, PX4 OFFBOARD. */
    GUIDED,
    /** Flies the uploaded mission: ArduPilot AUTO, PX4 AUTO.MISSION. */
    AUTO,
    /** Holds its position: ArduCopter LOITER, Rover HOLD, PX4 AUTO.LOITER. */
    HOLD,
    /** Climbs to the take-off altitude (PX4 AUTO.TAKEOFF; ArduPilot takes off in GUIDED). */
    TAKEOFF,
    /** Comes down and disarms: ArduCopter LAND, PX4 AUTO.LAND. */
    LAND,
    /** Goes home: ArduPilot RTL, PX4 AUTO.RTL. */
    RTL
}
