package io.robomw.sim.vehicle;

import io.robomw.config.description.VehicleDrive;

/**
 * An autopilot's outer loop, simply: the velocity targets that take a vehicle to a position, the
 * same for the emulated ArduPilot and PX4 and for the simulator's own vehicle platform.
 * <ul>
 *   <li>A multirotor flies straight at {@code min(speed limit, 1/s · distance, √(2 · 2.5 m/s² ·
 *   distance))} (it slows down to stop at the point) and climbs at {@code 1.5/s · height error}
 *   within its climb rate.</li>
 *   <li>A boat or rover steers toward the point ({@code yaw rate = 2/s · course error}) at a speed
 *   scaled by the cosine of that error (it turns before it goes), and stops within half the
 *   radius. A boat crabs against the current: it takes its drift as its ground velocity less its
 *   speed through the water along its heading (what its GPS and its own speed tell an autopilot),
 *   and heads and throttles for the velocity through the water that makes its ground velocity point
 *   at the point (up to its top speed).</li>
 *   <li>A yaw target is turned to at {@code 2/s · yaw error} within the turn rate.</li>
 * </ul>
 * Stateless.
 */
public final class Guidance {

    /** Position gain, 1/s. */
    public static final double POSITION_GAIN = 1.0;
    /** Climb gain, 1/s. */
    public static final double CLIMB_GAIN = 1.5;
    /** Yaw gain, 1/s. */
    public static final double YAW_GAIN = 2.0;
    /** The deceleration a multirotor plans to stop with, m/s². */
    public static final double STOPPING_ACCELERATION = 2.5;

    private Guidance() {
    }

    /**
     * @param s        the vehicle now
     * @param medium   where it moves
     * @param speed    the horizontal speed limit, m/s
     * @param climb    the climb rate limit, m/s
     * @param turnRate the turn rate limit, rad/s
     * @param x        the point's x (world, east)
     * @param y        its y (north)
     * @param z        its altitude (multirotors)
     * @param radius   how close counts as there (boats and rovers stop within half of it)
     * @param yawRate  the yaw rate to keep meanwhile (a multirotor's; NaN: none)
     * @return the targets for now
     */
    public static VehicleTarget goTo(SimVehicle.Snapshot s, VehicleDrive.Medium medium, double speed, double climb, double turnRate,
                                     double x, double y, double z, double radius, double yawRate) {
        double dx = x - s.x();
        double dy = y - s.y();
        double dist = Math.hypot(dx, dy);
        double rate = Double.isNaN(yawRate) ? 0 : clamp(yawRate, turnRate);
        if (medium == VehicleDrive.Medium.AIR) {
            double v = Math.min(speed, Math.min(POSITION_GAIN * dist, Math.sqrt(2 * STOPPING_ACCELERATION * dist)));
            double vx = dist > 1e-6 ? v * dx / dist : 0;
            double vy = dist > 1e-6 ? v * dy / dist : 0;
            return new VehicleTarget(vx, vy, clamp(CLIMB_GAIN * (z - s.z()), climb), rate);
        }
        if (dist < radius / 2) {
            return new VehicleTarget(0, 0, 0, rate);
        }
        double ground = Math.min(speed, POSITION_GAIN * dist);
        double wx = ground * dx / dist;
        double wy = ground * dy / dist;
        double limit = speed;
        if (medium == VehicleDrive.Medium.WATER) {
            wx -= s.vx() - s.surge() * Math.cos(s.heading());
            wy -= s.vy() - s.surge() * Math.sin(s.heading());
            limit = Math.max(speed, Math.hypot(wx, wy));
        }
        double err = normalize(Math.atan2(wy, wx) - s.heading());
        double steer = clamp(YAW_GAIN * err, turnRate);
        double v = Math.min(limit, Math.hypot(wx, wy)) * Math.max(0, Math.cos(err));
        return new VehicleTarget(v * Math.cos(s.heading()), v * Math.sin(s.heading()), 0, steer);
    }

    /**
     * @param s        the vehicle now
     * @param heading  the heading wanted (world, anti-clockwise from east)
     * @param turnRate the limit, rad/s
     * @return the yaw rate that turns it there
     */
    public static double yawRateTo(SimVehicle.Snapshot s, double heading, double turnRate) {
        return clamp(YAW_GAIN * normalize(heading - s.heading()), turnRate);
    }

    /** @return v limited to ±max */
    public static double clamp(double v, double max) {
        return Math.max(-max, Math.min(max, v));
    }

    /** @return an angle in (-π, π] */
    public static double normalize(double a) {
        double r = Math.IEEEremainder(a, 2 * Math.PI);
        return r <= -Math.PI ? r + 2 * Math.PI : r;
    }
}
