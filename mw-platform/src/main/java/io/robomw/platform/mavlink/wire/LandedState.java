package io.robomw.platform.mavlink.wire;

/** MAV_LANDED_STATE: Whether a vehicle is on the ground or flying (EXTENDED_SYS_STATE). Only the values RoboMW uses; others are not errors on the wire, they are unknown. */
public enum LandedState implements WireCode {
    /** 0: Unknown. */
    UNDEFINED(0),
    /** 1: On the ground. */
    ON_GROUND(1),
    /** 2: In the air. */
    IN_AIR(2),
    /** 3: Taking off. */
    TAKEOFF(3),
    /** 4: Landing. */
    LANDING(4);

    private static final Table<LandedState> TABLE = WireCode.table(LandedState.class, "MAV_LANDED_STATE");

    private final int code;

    LandedState(int code) {
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
    public static java.util.Optional<LandedState> find(long code) {
        return TABLE.find(code);
    }

    /**
     * @param code a number from the wire
     * @return its value
     * @throws IllegalArgumentException naming the code if it is not known
     */
    public static LandedState of(long code) {
        return TABLE.of(code);
    }
}
