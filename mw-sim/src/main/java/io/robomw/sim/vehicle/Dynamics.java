package io.robomw.sim.vehicle;

import io.robomw.sim.world.WorldDescription;

/**
 * How one kind of vehicle answers its autopilot's targets over one step: its velocities for the
 * next step (and its altitude) from the state after the last. Implementations are stateless; the
 * state is the vehicle's.
 */
interface Dynamics {

    /** Standard gravity, m/s². */
    double GRAVITY = 9.81;

    /**
     * @param dt     the step, seconds
     * @param s      the state after the physics step; its velocities are set for the next one
     * @param target the autopilot's targets
     * @param world  wind, current and water
     * @return the power drawn over the step, watts
     */
    double step(double dt, VehicleState s, VehicleTarget target, WorldDescription.Surroundings world);

    /**
     * @param v   a value
     * @param max its magnitude's limit
     * @return v limited to ±max
     */
    static double clamp(double v, double max) {
        return Math.max(-max, Math.min(max, v));
    }
}
