package io.robomw.sim.vehicle;

import io.robomw.sim.world.WorldDescription;

/**
 * A surface boat, after ArduPilot SITL's motor-boat model (mavlink.md §1.6):
 * <ul>
 *   <li>its surge through the water follows {@code a = (thrust − c·u·|u|) / mass}: quadratic drag,
 *   with {@code c} such that full thrust gives {@code maxSpeed}; the autopilot's speed loop sets
 *   the thrust (up to full ahead, half astern) to reach the target's part along the heading;</li>
 *   <li>it moves along its heading through the water (a keel stops sideways motion through it), and
 *   the water's current carries it: {@code velocity = velocity through the water + current};</li>
 *   <li>it turns at the target yaw rate in the first order (skid-steer: also at rest);</li>
 *   <li>it stays on the world's water: a step that would take it onto land is cut to what stays
 *   on water (it slides along the shore, or stops at it, its surge gone);</li>
 *   <li>it draws {@code 40 W/kg·(thrust/full thrust)} and 5 W armed at rest.</li>
 * </ul>
 * Not modelled: waves, heave, roll and pitch, added mass, wind on the hull.
 */
final class SurfaceBoat implements Dynamics {

    /** The time constant of the yaw rate's response, seconds. */
    static final double YAW_TIME = 0.4;
    /** Power at full thrust per kilogram, watts. */
    static final double FULL_WATTS_PER_KG = 40;
    /** Power armed at rest, watts. */
    static final double IDLE_WATTS = 5;

    private final VehicleSpec spec;
    private final double maxThrust;
    private final double dragCoefficient;

    SurfaceBoat(VehicleSpec spec) {
        this.spec = spec;
        this.maxThrust = spec.mass() * spec.maxAcceleration();
        this.dragCoefficient = maxThrust / (spec.maxSpeed() * spec.maxSpeed());
    }

    @Override
    public double step(double dt, VehicleState s, VehicleTarget target, WorldDescription.Surroundings world) {
        double c = Math.cos(s.heading);
        double sn = Math.sin(s.heading);
        double thrust = 0;
        double tyr = 0;
        if (s.armed) {
            double want = Math.max(-spec.maxSpeed() / 2, Math.min(spec.maxSpeed(), target.vx() * c + target.vy() * sn));
            thrust = spec.mass() * (want - s.surge) / spec.velocityTime() + dragCoefficient * s.surge * Math.abs(s.surge);
            thrust = Math.max(-maxThrust / 2, Math.min(maxThrust, thrust));
            tyr = Dynamics.clamp(target.yawRate(), spec.maxTurnRate());
        }
        s.surge += (thrust - dragCoefficient * s.surge * Math.abs(s.surge)) / spec.mass() * dt;
        s.yawRate += (tyr - s.yawRate) / YAW_TIME * dt;
        double vx = s.surge * c + world.currentX();
        double vy = s.surge * sn + world.currentY();
        if (!world.onWater(s.x + vx * dt, s.y + vy * dt)) {
            boolean alongX = world.onWater(s.x + vx * dt, s.y);
            boolean alongY = world.onWater(s.x, s.y + vy * dt);
            vx = alongX ? vx : 0;
            vy = alongX ? 0 : (alongY ? vy : 0);
            s.surge = 0;
        }
        s.vx = vx;
        s.vy = vy;
        s.z = 0;
        s.vz = 0;
        s.landed = false;
        return s.armed ? IDLE_WATTS + FULL_WATTS_PER_KG * spec.mass() * Math.abs(thrust) / maxThrust : 0;
    }
}
