package io.robomw.sim.vehicle;

import io.robomw.config.description.VehicleDrive;
import io.robomw.sim.world.WorldDescription;

import java.util.Objects;

/**
 * A simulated vehicle (a multirotor, a surface boat or a ground rover) in a world: its dynamics
 * ({@link Multirotor}, {@link SurfaceBoat}, {@link Rover}), its battery, and the targets its
 * autopilot sets (an emulated ArduPilot or PX4, or the simulator's own vehicle platform). The
 * world's physics moves its body horizontally, so walls, obstacles and other robots stop it; its
 * dynamics give the body its velocities before each step and keep its altitude.
 *
 * <h2>Frames</h2>
 * The world's: x east, y north, z up (metres above the ground, or the water), heading
 * anti-clockwise from east. MAVLink's local frame is north-east-down with yaw clockwise from north:
 * the emulator converts.
 *
 * <h2>Threads</h2>
 * The simulation's thread steps it, and whoever runs on that thread (a step listener) sets its
 * targets and reads it. {@link #snapshot()} may be called from any thread.
 */
public final class SimVehicle {

    private final VehicleSpec spec;
    private final Dynamics dynamics;
    private final Battery battery;
    private final VehicleState state = new VehicleState();
    private VehicleTarget target = VehicleTarget.HOLD;
    private volatile Snapshot snapshot;
    private double time;

    /**
     * A vehicle's state at the end of a step, for other threads.
     *
     * @param time         simulated seconds since it was made
     * @param x            m east
     * @param y            m north
     * @param z            m up
     * @param heading      rad, anti-clockwise from east
     * @param vx           m/s east
     * @param vy           m/s north
     * @param vz           m/s up
     * @param yawRate      rad/s, anti-clockwise
     * @param armed        whether its motors may run
     * @param landed       whether it stands on the ground (a multirotor); a boat or rover never is
     * @param battery      charge left, 0 to 1
     * @param volts        battery voltage
     * @param amps         battery current
     * @param surge        m/s along the heading through the water or over the ground (boats, rovers; 0 for a multirotor)
     */
    public record Snapshot(double time, double x, double y, double z, double heading, double vx, double vy, double vz, double yawRate,
                           boolean armed, boolean landed, double battery, double volts, double amps, double surge) {
    }

    /**
     * @param spec    its constants
     * @param x       where it starts, m east
     * @param y       m north
     * @param heading rad
     */
    public SimVehicle(VehicleSpec spec, double x, double y, double heading) {
        this.spec = Objects.requireNonNull(spec, "spec");
        this.dynamics = switch (spec.medium()) {
            case AIR -> new Multirotor(spec);
            case WATER -> new SurfaceBoat(spec);
            case GROUND -> new Rover(spec);
        };
        this.battery = new Battery(spec.batteryWh(), spec.batteryCells());
        state.x = x;
        state.y = y;
        state.heading = heading;
        state.landed = spec.medium() == VehicleDrive.Medium.AIR;
        publish();
    }

    /** @return its constants */
    public VehicleSpec spec() {
        return spec;
    }

    /** @return where it moves */
    public VehicleDrive.Medium medium() {
        return spec.medium();
    }

    /**
     * @param t the autopilot's targets from now on
     */
    public void target(VehicleTarget t) {
        this.target = Objects.requireNonNull(t, "target");
    }

    /** @return the targets set last */
    public VehicleTarget target() {
        return target;
    }

    /** Arms its motors (they may run); the snapshot says so at once. */
    public void arm() {
        state.armed = true;
        publish();
    }

    /** Disarms it: its motors stop (a multirotor in the air falls). */
    public void disarm() {
        state.armed = false;
        target = VehicleTarget.HOLD;
        publish();
    }

    /**
     * One step, after the world's physics moved its body.
     *
     * @param dt      the step, seconds
     * @param x       the body's x after the step
     * @param y       its y
     * @param heading its heading
     * @param vx      its velocity x (what it really did: a wall stops it)
     * @param vy      its velocity y
     * @param world   wind, current and water
     */
    public void advance(double dt, double x, double y, double heading, double vx, double vy, WorldDescription.Surroundings world) {
        state.x = x;
        state.y = y;
        state.heading = heading;
        state.vx = vx;
        state.vy = vy;
        double watts = dynamics.step(dt, state, target, world);
        battery.draw(watts, dt);
        time += dt;
        publish();
    }

    private void publish() {
        snapshot = new Snapshot(time, state.x, state.y, state.z, state.heading, state.vx, state.vy, state.vz, state.yawRate,
                state.armed, state.landed, battery.remaining(), battery.volts(), battery.amps(), state.surge);
    }

    /** @return the velocity x to give its body for the next step */
    public double commandX() {
        return state.vx;
    }

    /** @return the velocity y to give its body for the next step */
    public double commandY() {
        return state.vy;
    }

    /** @return the yaw rate to give its body for the next step */
    public double commandYawRate() {
        return state.yawRate;
    }

    /** @return its state at the end of the last step (any thread) */
    public Snapshot snapshot() {
        return snapshot;
    }

    /** @return its battery (the simulation's thread) */
    public Battery battery() {
        return battery;
    }
}
