package io.robomw.sim.programs;

import io.robomw.api.Robot;
import io.robomw.api.UnsupportedActionException;
import io.robomw.sim.SensorModel;
import io.robomw.sim.SimRobot;
import io.robomw.sim.Simulation;

import java.util.List;
import java.util.SplittableRandom;

/**
 * Wanders every robot of a simulation at once: a Braitenberg-style reactive controller, run at a
 * fixed rate (default 10 Hz) robot by robot in the world's pass over its robots, that reads each robot's range sensors and
 * sets its velocities with the continuous {@link Robot#drive} command (through all three layers,
 * refreshed at every tick, so the watchdog never fires while it runs): a robot its world drives in a
 * batch with the others of its robot file through the batch ({@link io.robomw.sim.SimWorld#driveBatched}:
 * the same layers over arrays), a robot addressed one by one through its own {@link Robot}. Robots without range
 * sensors drive in gentle random curves. Deterministic: each robot has its own seeded random
 * stream, and the robots are controlled in parallel on the world's worker threads.
 *
 * <p>Robots driven by brick emulators are left alone. It runs without program threads, so it
 * scales to thousands of robots; use it with
 * {@link Simulation#runFor} or a real-time run.
 */
public final class WanderController implements Runnable {

    private final Simulation simulation;
    private final List<SimRobot> bodies;
    private final List<Robot> robots;
    private final long everySteps;
    private final double[] speed;
    private final double[] turnBias;
    private final SplittableRandom[] random;
    /** Per robot: its wheels' top speed and half its track (NaN if it has no differential drive), a legged robot's top turn rate (else NaN). */
    private final double[] maxWheelSpeed;
    private final double[] halfTrack;
    private final double[] maxTurnRate;
    /** Per robot, per range sensor: bit 1 ahead, bit 2 left, bit 4 right, from its mounting angle (shared by the robots of one robot file). */
    private final int[][] sectors;
    /** Per robot, per range sensor: its longest range (shared as the sectors are). */
    private final double[][] maxRanges;
    /** By a robot's index here: its index in the world. */
    private final int[] worldIndex;
    private final io.robomw.sim.SimWorld world;
    /** By a robot's index in the world: its index here, or -1 if it is not controlled (a brick emulator drives it). */
    private final int[] byWorldIndex;

    /**
     * @param simulation the simulation whose robots wander
     * @param rateHz     control rate, ticks per simulated second
     * @param seed       seed of the random turns
     */
    public WanderController(Simulation simulation, double rateHz, long seed) {
        this.simulation = simulation;
        java.util.Set<String> opened = new java.util.HashSet<>();
        for (Robot r : simulation.robots()) {
            opened.add(r.name());
        }
        this.bodies = simulation.world().robots().stream().filter(b -> opened.contains(b.name())).toList();
        this.robots = bodies.stream().map(b -> simulation.robot(b.name())).toList();
        this.everySteps = Math.max(1, Math.round(1 / (rateHz * simulation.world().stepSeconds())));
        this.speed = new double[bodies.size()];
        this.turnBias = new double[bodies.size()];
        this.random = new SplittableRandom[bodies.size()];
        this.sectors = new int[bodies.size()][];
        this.maxRanges = new double[bodies.size()][];
        this.worldIndex = bodies.stream().mapToInt(SimRobot::index).toArray();
        this.world = simulation.world();
        java.util.Map<List<SensorModel>, int[]> sharedSectors = new java.util.IdentityHashMap<>();
        java.util.Map<List<SensorModel>, double[]> sharedRanges = new java.util.IdentityHashMap<>();
        this.maxWheelSpeed = new double[bodies.size()];
        this.halfTrack = new double[bodies.size()];
        this.maxTurnRate = new double[bodies.size()];
        this.byWorldIndex = new int[simulation.world().robots().size()];
        java.util.Arrays.fill(byWorldIndex, -1);
        for (int i = 0; i < bodies.size(); i++) {
            byWorldIndex[bodies.get(i).index()] = i;
        }
        SplittableRandom root = new SplittableRandom(seed);
        for (int i = 0; i < bodies.size(); i++) {
            random[i] = root.split();
            var d = bodies.get(i).description();
            speed[i] = d.drive().map(dd -> dd.maxSpeed() * 0.6).or(() -> d.leggedDrive().map(l -> l.maxSpeed() * 0.6)).orElse(0.0);
            turnBias[i] = random[i].nextDouble(-0.3, 0.3);
            maxWheelSpeed[i] = d.drive().map(dd -> dd.maxSpeed()).orElse(Double.NaN);
            halfTrack[i] = d.drive().map(dd -> dd.trackWidth() / 2).orElse(Double.NaN);
            maxTurnRate[i] = d.leggedDrive().map(l -> l.maxTurnRate()).orElse(Double.NaN);
            List<SensorModel> range = bodies.get(i).rangeSensors();
            sectors[i] = sharedSectors.computeIfAbsent(range, r -> {
                int[] sector = new int[r.size()];
                for (int k = 0; k < r.size(); k++) {
                    double a = Math.IEEEremainder(r.get(k).mountAngle(), 2 * Math.PI);
                    sector[k] = (Math.abs(a) < 0.3 ? 1 : 0) | (a > 0 && a < 1.8 ? 2 : 0) | (a < 0 && a > -1.8 ? 4 : 0);
                }
                return sector;
            });
            maxRanges[i] = sharedRanges.computeIfAbsent(range, r -> r.stream().mapToDouble(SensorModel::maxRange).toArray());
        }
    }

    /**
     * Installs it in the world's own pass over the robots ({@link io.robomw.sim.SimWorld#addRobotController}):
     * each robot's tick runs right after its sensors and its cycle, on the worker thread that
     * handles that robot. The robots wander exactly as with the controller as a step listener
     * ({@link #run()}), with one hand-over to the worker threads less per tick.
     *
     * @param simulation the simulation
     * @param rateHz     control rate
     * @param seed       seed
     * @return the controller
     */
    public static WanderController install(Simulation simulation, double rateHz, long seed) {
        WanderController c = new WanderController(simulation, rateHz, seed);
        simulation.world().addRobotController(c.everySteps, c::controlRobot);
        return c;
    }

    /** One robot's tick, by its index in the world (nothing for a robot it does not control). */
    private void controlRobot(int worldIndex) {
        int i = byWorldIndex[worldIndex];
        if (i >= 0) {
            control(i);
        }
    }

    /**
     * One tick for every robot when due, as a step listener (on the world's worker threads); what
     * {@link #install} runs inside the world's pass instead.
     */
    @Override
    public void run() {
        if (simulation.world().steps() % everySteps != 0) {
            return;
        }
        simulation.world().parallel().forEach(bodies.size(), this::control);
    }

    /** One robot's tick; touches only that robot and its own random stream. */
    private void control(int i) {
        {
            if (speed[i] == 0) {
                return;
            }
            double left = Double.POSITIVE_INFINITY;
            double right = Double.POSITIVE_INFINITY;
            double ahead = Double.POSITIVE_INFINITY;
            int[] sectorOf = sectors[i];
            double[] maxRange = maxRanges[i];
            int robot = worldIndex[i];
            for (int k = 0; k < sectorOf.length; k++) {
                // the sample from the world's arrays: the robot's own objects are not touched to read it
                double d = world.rangeReading(robot, k) / maxRange[k];
                int sector = sectorOf[k];
                if ((sector & 1) != 0) {
                    ahead = Math.min(ahead, d);
                }
                if ((sector & 2) != 0) {
                    left = Math.min(left, d);
                } else if ((sector & 4) != 0) {
                    right = Math.min(right, d);
                }
            }
            double v;
            double w;
            if (Double.isInfinite(ahead) && Double.isInfinite(left) && Double.isInfinite(right)) {
                if (random[i].nextDouble() < 0.05) {
                    turnBias[i] = random[i].nextDouble(-0.6, 0.6);
                }
                v = speed[i];
                w = turnBias[i];
            } else {
                double near = Math.min(ahead, Math.min(left, right));
                v = near < 0.25 ? 0 : speed[i] * Math.min(1, near);
                double side = (Double.isInfinite(left) ? 1 : left) - (Double.isInfinite(right) ? 1 : right);
                w = near < 0.25 ? (side >= 0 ? 1.5 : -1.5) : 2.0 * side + turnBias[i] * 0.3;
            }
            try {
                if (world.batched(robot)) {
                    // driven with the other robots of its robot file: the same three layers, over arrays
                    world.driveBatched(robot, v, clampTurn(i, v, w));
                } else {
                    robots.get(i).drive(v, clampTurn(i, v, w));
                }
            } catch (UnsupportedActionException e) {
                speed[i] = 0;
            }
        }
    }

    /** Keeps both wheels within the robot's maximum speed, or a legged robot within its turn rate. */
    private double clampTurn(int i, double v, double w) {
        if (!Double.isNaN(maxWheelSpeed[i])) {
            double max = (maxWheelSpeed[i] - Math.abs(v)) / halfTrack[i];
            return Math.max(-max, Math.min(max, w));
        }
        if (!Double.isNaN(maxTurnRate[i])) {
            return Math.max(-maxTurnRate[i], Math.min(maxTurnRate[i], w));
        }
        return 0.0;
    }
}
