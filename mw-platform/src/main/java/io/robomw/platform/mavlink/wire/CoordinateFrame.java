package io.robomw.platform.mavlink.wire;

/** MAV_FRAME: The coordinate frame of a setpoint or mission item. Only the values RoboMW uses; others are not errors on the wire, they are unknown. */
public enum CoordinateFrame implements WireCode {
    /** 0: Latitude, longitude, altitude above mean sea level. */
    GLOBAL(0),
    /** 1: Local north-east-down from the origin (home). */
    LOCAL_NED(1),
    /** 2: Not a coordinate frame: a mission command. */
    MISSION(2),
    /** 3: Latitude, longitude, altitude above home. */
    GLOBAL_RELATIVE_ALT(3),
    /** 5: GLOBAL with integer coordinates. */
    GLOBAL_INT(5),
    /** 6: GLOBAL_RELATIVE_ALT with integer coordinates. */
    GLOBAL_RELATIVE_ALT_INT(6),
    /** 7: North-east-down offsets from the vehicle's position. */
    LOCAL_OFFSET_NED(7),
    /** 8: Velocities in the body frame (x forward, y right), positions as LOCAL_NED. */
    BODY_NED(8),
    /** 9: Offsets in the body frame: forward, right, down from the vehicle's position, rotated by its heading. */
    BODY_OFFSET_NED(9),
    /** 12: Forward-right-down from the vehicle. */
    BODY_FRD(12);

    private static final Table<CoordinateFrame> TABLE = WireCode.table(CoordinateFrame.class, "MAV_FRAME");

    private final int code;

    CoordinateFrame(int code) {
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
    public static java.util.Optional<CoordinateFrame> find(long code) {
        return TABLE.find(code);
    }

    /**
     * @param code a number from the wire
     * @return its value
     * @throws IllegalArgumentException naming the code if it is not known
     */
    public static CoordinateFrame of(long code) {
        return TABLE.of(code);
    }
}
