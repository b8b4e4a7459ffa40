package io.robomw.sim.vehicle;

import io.robomw.sim.world.WorldDescription;

/**
 * A ground rover, after ArduPilot SITL's "very crude" rover model (mavlink.md §1.6): its speed
 * along its heading follows {@code a = maxAcceleration·(target − speed)/maxSpeed} (a first-order
 * response), it turns at the target yaw rate (skid-steer: also at rest, first order), it does not
 * slide sideways, and walls and obstacles stop it (the world's physics). It draws
 * {@code 20 W/kg} at full speed and 3 W armed at rest. Not modelled: slip, slopes, Ackermann
 * steering's turning circle.
 */
final class Rover implements Dynamics {

    /** The time constant of the yaw rate's response, seconds. */
    static final double YAW_TIME = 0.2;

    private final VehicleSpec spec;

    Rover(VehicleSpec spec) {
        this.spec = spec;
    }

    @Override
    public double step(double dt, VehicleState s, VehicleTarget target, WorldDescription.Surroundings world) {
        double c = Math.cos(s.heading);
        double sn = Math.sin(s.heading);
        double actual = s.vx * c + s.vy * sn;
        double want = 0;
        double tyr = 0;
        if (s.armed) {
            want = Dynamics.clamp(target.vx() * c + target.vy() * sn, spec.maxSpeed());
            tyr = Dynamics.clamp(target.yawRate(), spec.maxTurnRate());
        }
        s.surge = actual + spec.maxAcceleration() * (want - actual) / spec.maxSpeed() * dt;
        s.yawRate += (tyr - s.yawRate) / YAW_TIME * dt;
        s.vx = s.surge * c;
        s.vy = s.surge * sn;
        s.z = 0;
        s.vz = 0;
        s.landed = false;
        return s.armed ? 3 + 20 * spec.mass() * Math.abs(s.surge) / spec.maxSpeed() : 0;
    }
}
