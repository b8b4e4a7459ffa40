package io.robomw.platform.mavlink.wire;

/** MAV_DISTANCE_SENSOR: The kind of a range finder (DISTANCE_SENSOR). Only the values RoboMW uses; others are not errors on the wire, they are unknown. */
public enum DistanceSensorType implements WireCode {
    /** 0: A laser range finder (lidar). */
    LASER(0),
    /** 1: An ultrasound range finder. */
    ULTRASOUND(1),
    /** 2: An infrared range finder. */
    INFRARED(2),
    /** 3: A radar. */
    RADAR(3),
    /** 4: Unknown kind. */
    UNKNOWN(4);

    private static final Table<DistanceSensorType> TABLE = WireCode.table(DistanceSensorType.class, "MAV_DISTANCE_SENSOR");

    private final int code;

    DistanceSensorType(int code) {
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
    public static java.util.Optional<DistanceSensorType> find(long code) {
        return TABLE.find(code);
    }

    /**
     * @param code a number from the wire
     * @return its value
     * @throws IllegalArgumentException naming the code if it is not known
     */
    public static DistanceSensorType of(long code) {
        return TABLE.of(code);
    }
}
