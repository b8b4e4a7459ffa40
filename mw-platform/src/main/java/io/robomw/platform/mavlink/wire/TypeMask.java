package io.robomw.platform.mavlink.wire;

/**
 * POSITION_TARGET_TYPEMASK: the {@code type_mask} of SET_POSITION_TARGET_LOCAL_NED, where a set
 * bit means "ignore this field". Bits count from 0 here, as in the enum; the ArduPilot wiki counts
 * them from 1 ("bit1: PosX"), a known trap. The combined masks are those ArduPilot documents
 * (ardupilot.org/dev/docs/copter-commands-in-guided-mode.html, mavlink-rover-commands.html).
 */
public final class TypeMask {

    /** Ignore x. */
    public static final int X_IGNORE = 1;
    /** Ignore y. */
    public static final int Y_IGNORE = 1 << 1;
    /** Ignore z. */
    public static final int Z_IGNORE = 1 << 2;
    /** Ignore vx. */
    public static final int VX_IGNORE = 1 << 3;
    /** Ignore vy. */
    public static final int VY_IGNORE = 1 << 4;
    /** Ignore vz. */
    public static final int VZ_IGNORE = 1 << 5;
    /** Ignore afx. */
    public static final int AX_IGNORE = 1 << 6;
    /** Ignore afy. */
    public static final int AY_IGNORE = 1 << 7;
    /** Ignore afz. */
    public static final int AZ_IGNORE = 1 << 8;
    /** The acceleration fields are a force (not used). */
    public static final int FORCE_SET = 1 << 9;
    /** Ignore yaw. */
    public static final int YAW_IGNORE = 1 << 10;
    /** Ignore yaw rate. */
    public static final int YAW_RATE_IGNORE = 1 << 11;

    /** Every position bit. */
    public static final int POSITION_BITS = X_IGNORE | Y_IGNORE | Z_IGNORE;
    /** Every velocity bit. */
    public static final int VELOCITY_BITS = VX_IGNORE | VY_IGNORE | VZ_IGNORE;
    /** Every acceleration bit. */
    public static final int ACCELERATION_BITS = AX_IGNORE | AY_IGNORE | AZ_IGNORE;

    /** 3576 (0x0DF8): position only. */
    public static final int POSITION = VELOCITY_BITS | ACCELERATION_BITS | YAW_IGNORE | YAW_RATE_IGNORE;
    /** 3527 (0x0DC7): velocity only. */
    public static final int VELOCITY = POSITION_BITS | ACCELERATION_BITS | YAW_IGNORE | YAW_RATE_IGNORE;
    /** 2552: position and yaw (MAVSDK's offboard position setpoint). */
    public static final int POSITION_YAW = VELOCITY_BITS | ACCELERATION_BITS | YAW_RATE_IGNORE;
    /** 1479: velocity and yaw rate (Rover documents 1511: the same with vz ignored too, which a rover does not use). */
    public static final int VELOCITY_YAW_RATE = POSITION_BITS | ACCELERATION_BITS | YAW_IGNORE;

    private TypeMask() {
    }

    /**
     * @param mask a type mask
     * @param bit  one of the ignore bits
     * @return whether the field is used (its bit is clear)
     */
    public static boolean uses(int mask, int bit) {
        return (mask & bit) == 0;
    }
}
