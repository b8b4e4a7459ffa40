package io.robomw.platform.mavlink.wire;

/** MAV_PARAM_TYPE: The type of a parameter's value (PARAM_VALUE, PARAM_SET; the value is always sent as a float). Only the values RoboMW uses; others are not errors on the wire, they are unknown. */
public enum ParamType implements WireCode {
    /** 1: 8-bit unsigned integer. */
    UINT8(1),
    /** 2: 8-bit signed integer. */
    INT8(2),
    /** 3: 16-bit unsigned integer. */
    UINT16(3),
    /** 4: 16-bit signed integer. */
    INT16(4),
    /** 5: 32-bit unsigned integer. */
    UINT32(5),
    /** 6: 32-bit signed integer. */
    INT32(6),
    /** 9: 32-bit float. */
    REAL32(9);

    private static final Table<ParamType> TABLE = WireCode.table(ParamType.class, "MAV_PARAM_TYPE");

    private final int code;

    ParamType(int code) {
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
    public static java.util.Optional<ParamType> find(long code) {
        return TABLE.find(code);
    }

    /**
     * @param code a number from the wire
     * @return its value
     * @throws IllegalArgumentException naming the code if it is not known
     */
    public static ParamType of(long code) {
        return TABLE.of(code);
    }
}
