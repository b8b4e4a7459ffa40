package io.robomw.platform.mavlink.wire;

/** MAV_TYPE: The kind of a MAVLink system, as its HEARTBEAT says. Only the values RoboMW uses; others are not errors on the wire, they are unknown. */
public enum MavType implements WireCode {
    /** 0: Generic micro air vehicle. */
    GENERIC(0),
    /** 1: Fixed wing aircraft. */
    FIXED_WING(1),
    /** 2: Quadrotor. */
    QUADROTOR(2),
    /** 6: A ground control station. */
    GCS(6),
    /** 10: Ground rover. */
    GROUND_ROVER(10),
    /** 11: Surface vessel, boat, ship. */
    SURFACE_BOAT(11),
    /** 12: Submarine. */
    SUBMARINE(12),
    /** 13: Hexarotor. */
    HEXAROTOR(13),
    /** 14: Octorotor. */
    OCTOROTOR(14),
    /** 21: VTOL with tilting rotors. */
    VTOL_TILTROTOR(21),
    /** 43: A multirotor of unspecified arrangement. */
    GENERIC_MULTIROTOR(43);

    private static final Table<MavType> TABLE = WireCode.table(MavType.class, "MAV_TYPE");

    private final int code;

    MavType(int code) {
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
    public static java.util.Optional<MavType> find(long code) {
        return TABLE.find(code);
    }

    /**
     * @param code a number from the wire
     * @return its value
     * @throws IllegalArgumentException naming the code if it is not known
     */
    public static MavType of(long code) {
        return TABLE.of(code);
    }
}
