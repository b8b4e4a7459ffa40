package io.robomw.platform.mavlink.wire;

/**
 * MAV_MODE_FLAG: the bits of HEARTBEAT's {@code base_mode} (and of DO_SET_MODE's param1). Each
 * constant is one bit; a mode is their OR.
 */
public enum ModeFlag implements WireCode {
    /** 1: the custom mode ({@code custom_mode}) is what the autopilot flies by. */
    CUSTOM_MODE_ENABLED(1),
    /** 2: test mode. */
    TEST_ENABLED(2),
    /** 4: autonomous mode (waypoints, mission). */
    AUTO_ENABLED(4),
    /** 8: guided mode (setpoints from a ground station). */
    GUIDED_ENABLED(8),
    /** 16: the attitude is stabilised. */
    STABILIZE_ENABLED(16),
    /** 32: hardware in the loop. */
    HIL_ENABLED(32),
    /** 64: a remote control's input is used. */
    MANUAL_INPUT_ENABLED(64),
    /** 128: armed: the motors may run. */
    SAFETY_ARMED(128);

    private final int code;

    ModeFlag(int code) {
        this.code = code;
    }

    @Override
    public int code() {
        return code;
    }

    /**
     * @param baseMode a {@code base_mode} byte
     * @return whether this bit is set in it
     */
    public boolean in(long baseMode) {
        return (baseMode & code) != 0;
    }
}
