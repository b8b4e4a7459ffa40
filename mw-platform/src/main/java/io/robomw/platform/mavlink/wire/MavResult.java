package io.robomw.platform.mavlink.wire;

/** MAV_RESULT: The result of a command, in COMMAND_ACK. Only the values RoboMW uses; others are not errors on the wire, they are unknown. */
public enum MavResult implements WireCode {
    /** 0: Valid, supported, executed. */
    ACCEPTED(0),
    /** 1: Valid, but not now (try later). */
    TEMPORARILY_REJECTED(1),
    /** 2: Invalid (parameters out of range): retrying it will not help. */
    DENIED(2),
    /** 3: Not supported (unknown command). */
    UNSUPPORTED(3),
    /** 4: Valid, but execution failed. */
    FAILED(4),
    /** 5: Valid and running; a final result follows. */
    IN_PROGRESS(5),
    /** 6: Cancelled (the long-running command was cancelled). */
    CANCELLED(6),
    /** 7: Supported only as COMMAND_LONG. */
    COMMAND_LONG_ONLY(7),
    /** 8: Supported only as COMMAND_INT. */
    COMMAND_INT_ONLY(8);

    private static final Table<MavResult> TABLE = WireCode.table(MavResult.class, "MAV_RESULT");

    private final int code;

    MavResult(int code) {
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
    public static java.util.Optional<MavResult> find(long code) {
        return TABLE.find(code);
    }

    /**
     * @param code a number from the wire
     * @return its value
     * @throws IllegalArgumentException naming the code if it is not known
     */
    public static MavResult of(long code) {
        return TABLE.of(code);
    }
}
