package io.robomw.sim.vehicle;

import io.robomw.sim.world.WorldDescription;

/**
 * A multirotor, after ArduPilot SITL's frame model (mavlink.md §1.6), reduced to what a ground
 * station sees:
 * <ul>
 *   <li>its velocity answers the autopilot's target in the first order ({@code velocityTime}),
 *   at most {@code maxAcceleration} horizontally, within {@code maxSpeed} and
 *   {@code maxClimbRate};</li>
 *   <li>the air drags it linearly, {@code a = −(v − wind)·g / terminal velocity} (SITL's
 *   "linear air drag", terminal velocity 15 m/s); its velocity loop cancels the drag of its own
 *   motion and most of the wind's, a fifth of the wind's is left: a wind of 5 m/s moves it 0.33
 *   m/s off its target velocity (a hovering multirotor drifts until its position loop pulls it
 *   back);</li>
 *   <li>on the ground it stands (landed) until it is armed and asked to climb; it lands when it
 *   comes down to z = 0; disarmed in the air, it falls;</li>
 *   <li>it draws a hover power of {@code 180 W/kg}, more when it climbs or goes fast (drag), and
 *   10 W armed on the ground.</li>
 * </ul>
 * Not modelled: attitude (roll and pitch), rotor dynamics, noise, ground effect.
 */
final class Multirotor implements Dynamics {

    /** SITL's default terminal velocity, m/s. */
    static final double TERMINAL_VELOCITY = 15;
    /** The part of the wind's drag the velocity loop does not cancel. */
    static final double UNCANCELLED_DRAG = 0.2;
    /** Hover power per kilogram, watts. */
    static final double HOVER_WATTS_PER_KG = 180;
    /** Power armed on the ground, watts. */
    static final double IDLE_WATTS = 10;
    /** The time constant of the yaw rate's response, seconds. */
    static final double YAW_TIME = 0.2;

    private final VehicleSpec spec;

    Multirotor(VehicleSpec spec) {
        this.spec = spec;
    }

    @Override
    public double step(double dt, VehicleState s, VehicleTarget target, WorldDescription.Surroundings world) {
        if (s.landed) {
            s.vx = 0;
            s.vy = 0;
            s.yawRate = 0;
            s.z = 0;
            if (!s.armed || target.vz() <= 0) {
                s.vz = 0;
                return s.armed ? IDLE_WATTS : 0;
            }
            s.landed = false;
        }
        if (!s.armed) {
            s.vz -= GRAVITY * dt;
        } else {
            double tvx = target.vx();
            double tvy = target.vy();
            double speed = Math.hypot(tvx, tvy);
            if (speed > spec.maxSpeed()) {
                tvx *= spec.maxSpeed() / speed;
                tvy *= spec.maxSpeed() / speed;
            }
            double ax = (tvx - s.vx) / spec.velocityTime();
            double ay = (tvy - s.vy) / spec.velocityTime();
            double a = Math.hypot(ax, ay);
            if (a > spec.maxAcceleration()) {
                ax *= spec.maxAcceleration() / a;
                ay *= spec.maxAcceleration() / a;
            }
            double drag = GRAVITY / TERMINAL_VELOCITY * UNCANCELLED_DRAG;
            ax += world.windX() * drag;
            ay += world.windY() * drag;
            s.vx += ax * dt;
            s.vy += ay * dt;
            double tvz = Dynamics.clamp(target.vz(), spec.maxClimbRate());
            s.vz += Dynamics.clamp((tvz - s.vz) / spec.velocityTime(), spec.maxAcceleration()) * dt;
            double tyr = Dynamics.clamp(target.yawRate(), spec.maxTurnRate());
            s.yawRate += (tyr - s.yawRate) / YAW_TIME * dt;
        }
        s.z += s.vz * dt;
        if (s.z <= 0) {
            s.z = 0;
            s.vz = 0;
            s.vx = 0;
            s.vy = 0;
            s.yawRate = 0;
            s.landed = true;
        }
        if (!s.armed) {
            return 0;
        }
        double airSpeed = Math.hypot(s.vx - world.windX(), s.vy - world.windY());
        double hover = HOVER_WATTS_PER_KG * spec.mass();
        return hover * (1 + 0.5 * Math.max(0, s.vz) / Math.max(0.1, spec.maxClimbRate()) + 0.3 * Math.pow(airSpeed / spec.maxSpeed(), 2));
    }
}
