package io.robomw.platform.mavlink.wire;

/** MAV_STATE: A system's status in its HEARTBEAT. Only the values RoboMW uses; others are not errors on the wire, they are unknown. */
public enum MavState implements WireCode {
    /** 0: Uninitialized system, state is unknown. */
    UNINIT(0),
    /** 1: System is booting up. */
    BOOT(1),
    /** 2: System is calibrating. */
    CALIBRATING(2),
    /** 3: Grounded and on standby: it can be launched. */
    STANDBY(3),
    /** 4: Active and might be already airborne: motors engaged. */
    ACTIVE(4),
    /** 5: In a non-normal flight mode (failsafe): it can still navigate. */
    CRITICAL(5),
    /** 6: In an emergency: mayday. */
    EMERGENCY(6),
    /** 7: Powering off. */
    POWEROFF(7),
    /** 8: Terminating itself. */
    FLIGHT_TERMINATION(8);

    private static final Table<MavState> TABLE = WireCode.table(MavState.class, "MAV_STATE");

    private final int code;

    MavState(int code) {
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
    public static java.util.Optional<MavState> find(long code) {
        return TABLE.find(code);
    }

    /**
     * @param code a number from the wire
     * @return its value
     * @throws IllegalArgumentException naming the code if it is not known
     */
    public static MavState of(long code) {
        return TABLE.of(code);
    }
}
