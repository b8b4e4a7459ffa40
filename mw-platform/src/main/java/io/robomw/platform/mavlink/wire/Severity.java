package io.robomw.platform.mavlink.wire;

/** MAV_SEVERITY: How serious a STATUSTEXT is (syslog's levels). Only the values RoboMW uses; others are not errors on the wire, they are unknown. */
public enum Severity implements WireCode {
    /** 0: System is unusable. */
    EMERGENCY(0),
    /** 1: Action must be taken at once. */
    ALERT(1),
    /** 2: Critical conditions. */
    CRITICAL(2),
    /** 3: Error conditions. */
    ERROR(3),
    /** 4: Warning conditions. */
    WARNING(4),
    /** 5: Normal but significant. */
    NOTICE(5),
    /** 6: Informational. */
    INFO(6),
    /** 7: Debug-level messages. */
    DEBUG(7);

    private static final Table<Severity> TABLE = WireCode.table(Severity.class, "MAV_SEVERITY");

    private final int code;

    Severity(int code) {
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
    public static java.util.Optional<Severity> find(long code) {
        return TABLE.find(code);
    }

    /**
     * @param code a number from the wire
     * @return its value
     * @throws IllegalArgumentException naming the code if it is not known
     */
    public static Severity of(long code) {
        return TABLE.of(code);
    }
}
