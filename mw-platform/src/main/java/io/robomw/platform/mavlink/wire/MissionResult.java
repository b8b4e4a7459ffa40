package io.robomw.platform.mavlink.wire;

/** MAV_MISSION_RESULT: The result of a mission transfer (MISSION_ACK). Only the values RoboMW uses; others are not errors on the wire, they are unknown. */
public enum MissionResult implements WireCode {
    /** 0: Accepted: OK. */
    ACCEPTED(0),
    /** 1: Generic error. */
    ERROR(1),
    /** 2: Coordinate frame not supported. */
    UNSUPPORTED_FRAME(2),
    /** 3: Command not supported. */
    UNSUPPORTED(3),
    /** 4: Too many items. */
    NO_SPACE(4),
    /** 5: A parameter is invalid. */
    INVALID(5),
    /** 13: An item came out of sequence. */
    INVALID_SEQUENCE(13),
    /** 14: Not accepting mission commands now. */
    DENIED(14),
    /** 15: The transfer was cancelled. */
    OPERATION_CANCELLED(15);

    private static final Table<MissionResult> TABLE = WireCode.table(MissionResult.class, "MAV_MISSION_RESULT");

    private final int code;

    MissionResult(int code) {
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
    public static java.util.Optional<MissionResult> find(long code) {
        return TABLE.find(code);
    }

    /**
     * @param code a number from the wire
     * @return its value
     * @throws IllegalArgumentException naming the code if it is not known
     */
    public static MissionResult of(long code) {
        return TABLE.of(code);
    }
}
