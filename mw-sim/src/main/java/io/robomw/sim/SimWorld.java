package io.robomw.sim;

import io.robomw.api.ManualClock;
import io.robomw.api.Pose;
import io.robomw.config.description.Body;
import io.robomw.config.description.RobotDescription;
import io.robomw.platform.exec.ExecutionActionThread;
import io.robomw.sim.lockstep.Lockstep;
import io.robomw.sim.sensing.RangeIndex;
import io.robomw.sim.world.WorldDescription;
import org.dyn4j.dynamics.Settings;
import org.dyn4j.geometry.Geometry;
import org.dyn4j.geometry.MassType;
import org.dyn4j.geometry.Vector2;
import org.dyn4j.world.World;

import java.util.ArrayList;
import java.util.Collections;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Map;

/**
 * A simulated world: dyn4j bodies for the arena's walls, its obstacles and its robots, a
 * {@link ManualClock} that only the world moves, and the robots' execution action threads, which
 * the world cycles on that clock.
 *
 * <h2>One step, in order</h2>
 * <ol>
 *   <li>advance the physics by one fixed step ({@code 1 / physics_hz});</li>
 *   <li>update each robot's encoders from how it actually moved, and its contacts;</li>
 *   <li>advance the clock;</li>
 *   <li>sample every range sensor that is due (each sensor has its own seeded noise, so results
 *   do not depend on threads);</li>
 *   <li>cycle every robot's execution action thread that is due, then complete its pending sensor
 *   reads;</li>
 *   <li>set each robot's body velocities from its commanded wheel speeds, for the next step;</li>
 *   <li>(end of step) hand the completions that wake programs over, in one go.</li>
 * </ol>
 * Steps 2 and 4–6 work robot by robot on the world's worker threads ({@link Parallel}); each
 * robot's work touches only that robot, so the outcome does not depend on the threads.
 * The same seed and the same commands give the same trajectory, bit for bit.
 *
 * <p>Not thread-safe: one thread steps it (a {@link Simulation} does). Poses and trajectories may
 * be read from other threads.
 */
public final class SimWorld implements AutoCloseable {


    private final WorldDescription description;
    private final ManualClock clock = new ManualClock();
    private final Lockstep lockstep = new Lockstep();
    private final World<org.dyn4j.dynamics.Body> physics = new World<>();
    private final List<SimRobot> robots = new ArrayList<>();
    private final Map<String, SimRobot> byName = new LinkedHashMap<>();
    private final RangeIndex rangeIndex;
    private final long stepNanos;
    private final double stepSeconds;
    private final int trajectoryEvery;
    private final Parallel parallel;
    private final List<SimRobot> cycledRobots = new ArrayList<>();
    private final List<Cycled> cycledThreads = new ArrayList<>();
    private long steps;
    private double[] px = new double[0];
    private double[] py = new double[0];
    private double[] ph = new double[0];
    private double[] pl = new double[0];
    private double[] pw = new double[0];
    private boolean initialSampleDue;
    private long[] sensingPeriods;
    private final RayCaster rayCaster;
    private final RangeMethod rangeMethod;

    /** Casts one ray for a range sensor. */
    @FunctionalInterface
    interface RayCaster {
        /**
         * @return the distance to the nearest hit within maxRange, or +∞
         */
        double cast(double ox, double oy, double angle, double maxRange, int self);
    }

    private double dyn4jRay(double ox, double oy, double angle, double maxRange, int self) {
        org.dyn4j.dynamics.Body own = robots.get(self).body();
        org.dyn4j.world.DetectFilter<org.dyn4j.dynamics.Body, org.dyn4j.dynamics.BodyFixture> filter =
                new org.dyn4j.world.DetectFilter<>(true, true, null) {
                    @Override
                    public boolean isAllowed(org.dyn4j.dynamics.Body body, org.dyn4j.dynamics.BodyFixture fixture) {
                        return body != own && super.isAllowed(body, fixture);
                    }
                };
        double best = Double.POSITIVE_INFINITY;
        for (var hit : physics.raycast(new org.dyn4j.geometry.Ray(new Vector2(ox, oy), angle), maxRange, filter)) {
            best = Math.min(best, hit.getRaycast().getDistance());
        }
        return best;
    }

    /** A robot's execution action thread and when it is due. */
    private static final class Cycled {
        private final ExecutionActionThread thread;
        private final long period;
        private long next;

        Cycled(ExecutionActionThread thread, long now) {
            this.thread = thread;
            this.period = thread.period().toNanos();
            this.next = now;
        }
    }

    /**
     * Builds the world. Robots are added with {@link #addRobot}.
     *
     * @param description the world
     * @param sensingThreads worker threads for the per-robot parts of a step (1 = all on the stepping thread)
     */
    public SimWorld(WorldDescription description, int sensingThreads) {
        this(description, sensingThreads, RangeMethod.GRID);
    }

    /** How range sensors find what they see. */
    public enum RangeMethod {
        /** The world's own grid of segments and discs ({@link RangeIndex}): what the simulator uses. */
        GRID,
        /**
         * A dyn4j world ray cast through its broadphase for every ray: the straightforward way,
         * kept as the baseline the benchmark compares against.
         */
        DYN4J_RAYCAST
    }

    /**
     * Builds the world with a chosen range method (for benchmarks).
     *
     * @param description    the world
     * @param sensingThreads worker threads for the per-robot parts of a step
     * @param rangeMethod    how range sensors cast their rays
     */
    public SimWorld(WorldDescription description, int sensingThreads, RangeMethod rangeMethod) {
        this.description = description;
        this.stepSeconds = 1.0 / description.physicsHz();
        this.stepNanos = Math.round(1e9 / description.physicsHz());
        this.trajectoryEvery = Math.max(1, (int) Math.round(description.physicsHz() / 10));
        physics.setGravity(World.ZERO_GRAVITY);
        Settings settings = physics.getSettings();
        settings.setStepFrequency(stepSeconds);
        settings.setAtRestDetectionEnabled(true);
        // Robots move at most a few centimetres per step and walls are thick: continuous collision
        // detection (tunnelling prevention) buys nothing and costs a pass over every moving body.
        settings.setContinuousDetectionMode(org.dyn4j.dynamics.ContinuousDetectionMode.NONE);
        List<double[]> segments = new ArrayList<>();
        List<double[]> discs = new ArrayList<>();
        if (description.walls()) {
            double w = description.width();
            double h = description.height();
            double t = description.wallThickness();
            addStaticBox(w / 2, -t / 2, w + 2 * t, t, 0, segments);
            addStaticBox(w / 2, h + t / 2, w + 2 * t, t, 0, segments);
            addStaticBox(-t / 2, h / 2, t, h, 0, segments);
            addStaticBox(w + t / 2, h / 2, t, h, 0, segments);
        }
        for (WorldDescription.Obstacle o : description.obstacles()) {
            if (o instanceof WorldDescription.Box b) {
                addStaticBox(b.x(), b.y(), b.width(), b.height(), b.angle(), segments);
            } else if (o instanceof WorldDescription.Circle c) {
                org.dyn4j.dynamics.Body body = new org.dyn4j.dynamics.Body();
                body.addFixture(Geometry.createCircle(c.radius()));
                body.translate(c.x(), c.y());
                body.setMass(MassType.INFINITE);
                physics.addBody(body);
                discs.add(new double[]{c.x(), c.y(), c.radius()});
            } else if (o instanceof WorldDescription.Polygon p) {
                Vector2[] v = p.points().stream().map(xy -> new Vector2(xy[0], xy[1])).toArray(Vector2[]::new);
                org.dyn4j.dynamics.Body body = new org.dyn4j.dynamics.Body();
                body.addFixture(Geometry.createPolygon(v));
                body.setMass(MassType.INFINITE);
                physics.addBody(body);
                for (int i = 0; i < v.length; i++) {
                    segments.add(new double[]{v[i].x, v[i].y, v[(i + 1) % v.length].x, v[(i + 1) % v.length].y});
                }
            }
        }
        double margin = description.wallThickness() + 1;
        double cell = Math.max(0.25, Math.min(2.0, Math.sqrt(description.width() * description.height() / 4096)));
        this.rangeIndex = new RangeIndex(-margin, -margin, description.width() + 2 * margin, description.height() + 2 * margin, cell,
                segments.toArray(double[][]::new), discs.toArray(double[][]::new));
        this.parallel = new Parallel(sensingThreads);
        this.rangeMethod = rangeMethod;
        this.rayCaster = rangeMethod == RangeMethod.GRID ? rangeIndex::castRay : this::dyn4jRay;
    }

    private void addStaticBox(double x, double y, double w, double h, double angle, List<double[]> segments) {
        org.dyn4j.dynamics.Body body = new org.dyn4j.dynamics.Body();
        body.addFixture(Geometry.createRectangle(w, h));
        body.rotate(angle);
        body.translate(x, y);
        body.setMass(MassType.INFINITE);
        physics.addBody(body);
        double c = Math.cos(angle);
        double s = Math.sin(angle);
        double[][] corners = {{w / 2, h / 2}, {-w / 2, h / 2}, {-w / 2, -h / 2}, {w / 2, -h / 2}};
        for (int i = 0; i < 4; i++) {
            double[] a = corners[i];
            double[] b = corners[(i + 1) % 4];
            segments.add(new double[]{x + a[0] * c - a[1] * s, y + a[0] * s + a[1] * c, x + b[0] * c - b[1] * s, y + b[0] * s + b[1] * c});
        }
    }

    /**
     * Puts a robot's body into the world.
     *
     * @param name        its unique name
     * @param description its description (body size, mass, friction, drive, sensors)
     * @param start       where it starts
     * @return the simulated robot
     */
    public SimRobot addRobot(String name, RobotDescription description, Pose start) {
        if (byName.containsKey(name)) {
            throw new IllegalArgumentException("world '" + this.description.name() + "' already has a robot named '" + name + "'");
        }
        Body b = description.body();
        org.dyn4j.dynamics.Body body = new org.dyn4j.dynamics.Body();
        body.addFixture(Geometry.createRectangle(b.length(), b.width()), b.mass() / (b.length() * b.width()), b.friction(), 0);
        body.setMass(MassType.NORMAL);
        body.rotate(start.heading());
        body.translate(start.x(), start.y());
        body.setAtRestDetectionEnabled(true);
        physics.addBody(body);
        SimRobot robot = new SimRobot(robots.size(), name, description, body, this.description.seed(), clock::nanoTime);
        robots.add(robot);
        byName.put(name, robot);
        initialSampleDue = true;
        sensingPeriods = null;
        return robot;
    }

    /**
     * Cycles a robot's execution action thread on this world's clock from now on.
     *
     * @param robot  the robot
     * @param thread its execution action thread
     */
    public void attach(SimRobot robot, ExecutionActionThread thread) {
        cycledRobots.add(robot);
        cycledThreads.add(new Cycled(thread, clock.nanoTime()));
    }

    /** @return the world's description */
    public WorldDescription description() {
        return description;
    }

    /** @return the clock only this world moves */
    public ManualClock clock() {
        return clock;
    }

    /** @return the lockstep that keeps programs and time together */
    public Lockstep lockstep() {
        return lockstep;
    }

    /** @return the robots, in the order they were added */
    public List<SimRobot> robots() {
        return Collections.unmodifiableList(robots);
    }

    /**
     * @param name a robot's name
     * @return that robot, or {@code null}
     */
    public SimRobot robot(String name) {
        return byName.get(name);
    }

    /** @return the physics world, for tools that need it (the naive baseline of the benchmark) */
    public World<org.dyn4j.dynamics.Body> physics() {
        return physics;
    }

    /** @return the range index */
    public RangeIndex rangeIndex() {
        return rangeIndex;
    }

    /** @return steps taken */
    public long steps() {
        return steps;
    }

    /** @return simulated seconds since the start */
    public double time() {
        return clock.nanoTime() / 1e9;
    }

    /** @return the fixed physics step, seconds */
    public double stepSeconds() {
        return stepSeconds;
    }

    /**
     * Advances the world by one step; see the class description for the order.
     */
    public void step() {
        lockstep.beginStep();
        try {
            advance();
        } finally {
            lockstep.endStep();
        }
    }

    /** @return the worker threads of this world, for controllers that work on every robot */
    public Parallel parallel() {
        return parallel;
    }

    private void advance() {
        if (initialSampleDue) {
            sampleRangeSensors();
            initialSampleDue = false;
        }
        physics.step(1, stepSeconds);
        steps++;
        boolean record = steps % trajectoryEvery == 0;
        parallel.forEach(robots.size(), i -> robots.get(i).afterStep(physics, stepSeconds, record));
        clock.advanceNanos(stepNanos);
        sampleRangeSensors();
        long now = clock.nanoTime();
        parallel.forEach(cycledRobots.size(), i -> {
            SimRobot robot = cycledRobots.get(i);
            Cycled c = cycledThreads.get(i);
            while (c.next <= now) {
                c.thread.cycle();
                c.next += c.period;
            }
            robot.completeReads(this);
        });
        parallel.forEach(robots.size(), i -> robots.get(i).applyDrive());
    }

    /** Samples every range sensor that is due at this step. */
    private void sampleRangeSensors() {
        if (sensingPeriods == null) {
            java.util.TreeSet<Long> periods = new java.util.TreeSet<>();
            for (SimRobot r : robots) {
                for (SensorModel s : r.rangeSensors()) {
                    periods.add(s.everySteps(description.physicsHz()));
                }
            }
            sensingPeriods = periods.stream().mapToLong(Long::longValue).toArray();
        }
        boolean any = false;
        for (long p : sensingPeriods) {
            any |= steps % p == 0;
        }
        if (!any) {
            return;
        }
        if (rangeMethod == RangeMethod.GRID) {
            indexRobots();
        }
        parallel.forEach(robots.size(), i -> {
            SimRobot r = robots.get(i);
            Pose p = r.pose();
            for (SensorModel s : r.rangeSensors()) {
                if (steps % s.everySteps(description.physicsHz()) == 0) {
                    s.sampleRange(rayCaster, r.index(), p.x(), p.y(), p.heading(), r.headPan(), r.headTilt());
                }
            }
        });
    }

    private void indexRobots() {
        int n = robots.size();
        if (px.length != n) {
            px = new double[n];
            py = new double[n];
            ph = new double[n];
            pl = new double[n];
            pw = new double[n];
        }
        for (int i = 0; i < n; i++) {
            SimRobot r = robots.get(i);
            Pose p = r.pose();
            px[i] = p.x();
            py[i] = p.y();
            ph[i] = p.heading();
            pl[i] = r.description().body().length();
            pw[i] = r.description().body().width();
        }
        rangeIndex.indexRobots(n, px, py, ph, pl, pw);
    }

    /**
     * @param x     a point's x
     * @param y     a point's y
     * @param color whether the colour number is wanted rather than the brightness
     * @return the floor's brightness (0..1) or colour number there
     */
    double floorAt(double x, double y, boolean color) {
        List<WorldDescription.FloorPatch> patches = description.patches();
        for (int i = patches.size() - 1; i >= 0; i--) {
            WorldDescription.FloorPatch p = patches.get(i);
            if (p.contains(x, y)) {
                return color ? p.color() : p.brightness();
            }
        }
        return color ? 0 : description.floorBrightness();
    }

    /** Stops the worker threads. */
    @Override
    public void close() {
        parallel.close();
    }
}
