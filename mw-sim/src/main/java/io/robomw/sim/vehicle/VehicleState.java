package io.robomw.sim.vehicle;

/**
 * One vehicle's state in the world's frame (x east, y north, z up; heading anti-clockwise from
 * east), as its dynamics step it. Horizontal position and heading come from the world's physics
 * after each step (so walls and obstacles stop it); the dynamics set the velocities for the next
 * step, and keep the altitude themselves. Touched by the simulation's thread only.
 */
final class VehicleState {
    double x;
    double y;
    double z;
    double heading;
    double vx;
    double vy;
    double vz;
    double yawRate;
    /** Surge through the water (boats) or along the ground (rovers), m/s along the heading. */
    double surge;
    boolean armed;
    boolean landed = true;
}
