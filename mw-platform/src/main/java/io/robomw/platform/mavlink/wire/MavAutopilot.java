package io.robomw.platform.mavlink.wire;

/** MAV_AUTOPILOT: The autopilot firmware of a MAVLink system, as its HEARTBEAT says. Only the values RoboMW uses; others are not errors on the wire, they are unknown. */
public enum MavAutopilot implements WireCode {
    /** 0: Generic autopilot, full support for everything. */
    GENERIC(0),
    /** 3: ArduPilot. */
    ARDUPILOTMEGA(3),
    /** 8: No valid autopilot: what a ground station sends. */
    INVALID(8),
    /** 12: PX4 Autopilot. */
    PX4(12);

    private static final Table<MavAutopilot> TABLE = WireCode.table(MavAutopilot.class, "MAV_AUTOPILOT");

    private final int code;

    MavAutopilot(int code) {
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
    public static java.util.Optional<MavAutopilot> find(long code) {
        return TABLE.find(code);
    }

    /**
     * @param code a number from the wire
     * @return its value
     * @throws IllegalArgumentException naming the code if it is not known
     */
    public static MavAutopilot of(long code) {
        return TABLE.of(code);
    }
}
