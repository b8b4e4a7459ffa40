package io.robomw.platform.mavlink.wire;

/** MAV_CMD: The commands RoboMW sends or the emulator answers (COMMAND_LONG, COMMAND_INT, mission items). Only the values RoboMW uses; others are not errors on the wire, they are unknown. */
public enum MavCmd implements WireCode {
    /** 16: Navigate to a waypoint (mission item). */
    NAV_WAYPOINT(16),
    /** 17: Loiter around a point, indefinitely. */
    NAV_LOITER_UNLIM(17),
    /** 20: Return to the launch (home) position. */
    NAV_RETURN_TO_LAUNCH(20),
    /** 21: Land at a location (param7 altitude ignored by copters). */
    NAV_LAND(21),
    /** 22: Take off (param7: altitude, metres). */
    NAV_TAKEOFF(22),
    /** 23: Land at a local position. */
    NAV_LAND_LOCAL(23),
    /** 24: Take off from a local position. */
    NAV_TAKEOFF_LOCAL(24),
    /** 115: Turn to a heading (param1 degrees, param2 rate, param3 direction, param4 relative). */
    CONDITION_YAW(115),
    /** 176: Set the mode (param1 base mode flags, param2 custom mode, param3 custom sub-mode). */
    DO_SET_MODE(176),
    /** 178: Change the speed (param2 m/s). */
    DO_CHANGE_SPEED(178),
    /** 192: Go to a global position. */
    DO_REPOSITION(192),
    /** 300: Start the mission. */
    MISSION_START(300),
    /** 400: Arm (param1 1) or disarm (0); param2 21196 forces it. */
    COMPONENT_ARM_DISARM(400),
    /** 519: Request PROTOCOL_VERSION. */
    REQUEST_PROTOCOL_VERSION(519),
    /** 511: Set a message's stream interval (param1 message id, param2 µs). */
    SET_MESSAGE_INTERVAL(511),
    /** 512: Send a message once (param1 its id). */
    REQUEST_MESSAGE(512),
    /** 520: Send AUTOPILOT_VERSION (deprecated: REQUEST_MESSAGE). */
    REQUEST_AUTOPILOT_CAPABILITIES(520);

    private static final Table<MavCmd> TABLE = WireCode.table(MavCmd.class, "MAV_CMD");

    private final int code;

    MavCmd(int code) {
        this.code = code;
    }

    @Override
    public int code() {
        return code;
    }

    /**
     * @param code a number from the wire
     * @return its value, if known
     */
    public static java.util.Optional<MavCmd> find(long code) {
        return TABLE.find(code);
    }

    /**
     * @param code a number from the wire
     * @return its value
     * @throws IllegalArgumentException naming the code if it is not known
     */
    public static MavCmd of(long code) {
        return TABLE.of(code);
    }
}
