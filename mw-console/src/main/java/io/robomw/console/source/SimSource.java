package io.robomw.console.source;

import io.robomw.api.Pose;
import io.robomw.console.observe.Observation;
import io.robomw.console.observe.Observer;
import io.robomw.console.observe.WorldMap;
import io.robomw.sim.SensorModel;
import io.robomw.sim.SimRobot;
import io.robomw.sim.Simulation;

/**
 * Watches a simulated world from inside its run: the map once, then every robot's true pose and
 * range readings every {@value #PERIOD_SECONDS} s of simulated time, from a step listener (so a
 * fast run is watched at its own pace and a real-time one in real time). Observations are stamped
 * with the wall time the run had when watching began plus the simulated time since.
 */
public final class SimSource implements AutoCloseable {

    /** Simulated seconds between two observations of the robots. */
    public static final double PERIOD_SECONDS = 0.05;

    private final Simulation sim;
    private final Observer observer;
    private final long epochNanos;
    private final Runnable listener = this::onStep;
    private double next;

    private SimSource(Simulation sim, Observer observer) {
        this.sim = sim;
        this.observer = observer;
        this.epochNanos = System.currentTimeMillis() * 1_000_000L - Math.round(sim.world().time() * 1e9);
    }

    /**
     * Starts watching.
     *
     * @param sim      the simulation
     * @param observer who is told
     * @return the source; close it to stop watching
     */
    public static SimSource watch(Simulation sim, Observer observer) {
        SimSource s = new SimSource(sim, observer);
        observer.observe(new Observation.World(s.now(), WorldMap.of(sim.world())));
        s.observeRobots();
        sim.addStepListener(s.listener);
        return s;
    }

    private long now() {
        return epochNanos + Math.round(sim.world().time() * 1e9);
    }

    private void onStep() {
        if (sim.world().time() + 1e-9 >= next) {
            next = sim.world().time() + PERIOD_SECONDS;
            observeRobots();
        }
    }

    private void observeRobots() {
        long t = now();
        for (SimRobot r : sim.world().robots()) {
            Pose p = r.pose();
            double z = r.vehicle() == null ? 0 : r.vehicle().snapshot().z();
            observer.observe(new Observation.RobotPose(t, r.name(), p.x(), p.y(), z, p.heading(), true));
            for (SensorModel s : r.rangeSensors()) {
                observer.observe(new Observation.SensorReading(t, r.name(), s.spec().name(), r.latest(s), "m"));
            }
        }
    }

    @Override
    public void close() {
        sim.removeStepListener(listener);
    }
}
