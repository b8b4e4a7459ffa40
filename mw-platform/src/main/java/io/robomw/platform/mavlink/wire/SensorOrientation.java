package io.robomw.platform.mavlink.wire;

/** MAV_SENSOR_ORIENTATION: Where a sensor points, as a rotation from forward (DISTANCE_SENSOR.orientation). Only the values RoboMW uses; others are not errors on the wire, they are unknown. */
public enum SensorOrientation implements WireCode {
    /** 0: Forward. */
    NONE(0),
    /** 2: Right. */
    YAW_90(2),
    /** 4: Backward. */
    YAW_180(4),
    /** 6: Left. */
    YAW_270(6),
    /** 24: Up. */
    PITCH_90(24),
    /** 25: Down. */
    PITCH_270(25);

    private static final Table<SensorOrientation> TABLE = WireCode.table(SensorOrientation.class, "MAV_SENSOR_ORIENTATION");

    private final int code;

    SensorOrientation(int code) {
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
    public static java.util.Optional<SensorOrientation> find(long code) {
        return TABLE.find(code);
    }

    /**
     * @param code a number from the wire
     * @return its value
     * @throws IllegalArgumentException naming the code if it is not known
     */
    public static SensorOrientation of(long code) {
        return TABLE.of(code);
    }
}
