package io.robomw.platform.mavlink.gcs;

import io.robomw.platform.mavlink.wire.CoordinateFrame;
import io.robomw.platform.mavlink.wire.Messages;
import io.robomw.platform.mavlink.wire.Payload;
import io.robomw.platform.mavlink.wire.TypeMask;

/**
 * The SET_POSITION_TARGET_LOCAL_NED messages the driver streams, in the frames both ArduPilot and
 * PX4 take (LOCAL_NED, BODY_NED) with the type masks ArduPilot documents. Stateless.
 */
final class Setpoints {

    private Setpoints() {
    }

    private static Payload base(int system, CoordinateFrame frame, int mask, long timeBootMs) {
        return Payload.of(Messages.SetPositionTargetLocalNed.MESSAGE)
                .set(Messages.SetPositionTargetLocalNed.TIME_BOOT_MS, timeBootMs)
                .set(Messages.SetPositionTargetLocalNed.TARGET_SYSTEM, system)
                .set(Messages.SetPositionTargetLocalNed.TARGET_COMPONENT, GroundStation.AUTOPILOT_COMPONENT)
                .set(Messages.SetPositionTargetLocalNed.COORDINATE_FRAME, frame.code())
                .set(Messages.SetPositionTargetLocalNed.TYPE_MASK, mask);
    }

    /**
     * @return a position in LOCAL_NED (north, east, down from the vehicle's origin) and a yaw
     *         (clockwise from north): mask 2552
     */
    static Payload position(int system, long timeBootMs, double north, double east, double down, double yaw) {
        return base(system, CoordinateFrame.LOCAL_NED, TypeMask.POSITION_YAW, timeBootMs)
                .set(Messages.SetPositionTargetLocalNed.X, north)
                .set(Messages.SetPositionTargetLocalNed.Y, east)
                .set(Messages.SetPositionTargetLocalNed.Z, down)
                .set(Messages.SetPositionTargetLocalNed.YAW, yaw);
    }

    /**
     * @return velocities in BODY_NED (forward, right, down) and a yaw rate (clockwise): mask 1479
     */
    static Payload bodyVelocity(int system, long timeBootMs, double forward, double right, double down, double yawRate) {
        return base(system, CoordinateFrame.BODY_NED, TypeMask.VELOCITY_YAW_RATE, timeBootMs)
                .set(Messages.SetPositionTargetLocalNed.VX, forward)
                .set(Messages.SetPositionTargetLocalNed.VY, right)
                .set(Messages.SetPositionTargetLocalNed.VZ, down)
                .set(Messages.SetPositionTargetLocalNed.YAW_RATE, yawRate);
    }
}
