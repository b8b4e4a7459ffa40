package io.robomw.sim;

import io.robomw.api.Clock;
import io.robomw.api.ManualClock;
import io.robomw.api.Pose;
import io.robomw.api.spi.FailurePolicy;
import io.robomw.config.description.Body;
import io.robomw.config.description.RobotDescription;
import io.robomw.platform.exec.ExecutionActionThread;
import io.robomw.sim.lockstep.Lockstep;
import io.robomw.sim.physics.Dyn4jPhysics;
import io.robomw.sim.physics.Physics;
import io.robomw.sim.physics.SwarmPhysics;
import io.robomw.sim.sensing.RangeIndex;
import io.robomw.sim.world.WorldDescription;
import org.dyn4j.geometry.Vector2;

import java.util.ArrayList;
import java.util.Collections;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Map;

/**
 * A simulated world: rigid bodies ({@link Physics}: dyn4j's or the {@linkplain SwarmPhysics swarm
 * engine}, as the world file's {@code physics:} key says) for the arena's walls, its obstacles and its robots, a
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
 *   reads (for a robot driven in a {@linkplain #batchRobots() batch}: its batch's cycle of it, over
 *   the batch's arrays, instead), then run the {@linkplain #addRobotController robot controllers}
 *   that are due on it;</li>
 *   <li>set each robot's body velocities from its commanded wheel speeds, for the next step;</li>
 *   <li>(end of step) hand the completions that wake programs over, in one go.</li>
 * </ol>
 * Steps 2 and 4–6 work robot by robot on the world's worker threads ({@link Parallel}); each
 * robot's work touches only that robot (sensing reads the others' bodies
 * as placed in the range index after the motion), so the outcome does not depend on the threads.
 * The same seed and the same commands give the same trajectory, bit for bit. The per-robot work
 * is done in as few passes over the robots as the order allows, each pass a hand-over to the
 * worker threads: a step in which no sensor, no cycle and no controller is due is one pass (step
 * 2, pending reads, step 6: none of it reads the clock or another robot); otherwise two, step 2
 * (and each body's place in the range index) before the clock moves, then 4–6 robot by robot.
 *
 * <h2>Failures</h2>
 * What one robot's part of a step throws (its sensors, its execution action thread's cycle, its
 * pending reads, a {@linkplain #addRobotController controller}'s work on it) concerns that robot
 * only: if the {@link FailurePolicy} says it is survivable, it is reported there, the robot's
 * commands end with it at its next cycle (their end actions stop its motors), and the step goes
 * on for every other robot. Any other failure (of the physics, or one the policy says no thread
 * survives) leaves {@link #step()} for the thread that steps the world, which then
 * {@linkplain #halt halts} it.
 *
 * <p>Not thread-safe: one thread steps it (a {@link Simulation} does). Poses and trajectories may
 * be read from other threads.
 */
public final class SimWorld implements AutoCloseable {


    private final WorldDescription description;
    private final ManualClock clock = new ManualClock();
    private final Lockstep lockstep = new Lockstep();
    private final Physics physics;
    /** The same physics when it is dyn4j's (for the naive ray casts); else {@code null}. */
    private final Dyn4jPhysics dyn4j;
    /** The farthest a robot may move in a step with the swarm engine (half the thinnest static), metres. */
    private final double thinnestStatic;
    private final List<SimRobot> robots = new ArrayList<>();
    /** What the robots change at every step, in arrays by robot index. */
    private final RobotStates states = new RobotStates();
    /** What the robots read from one robot file share. */
    private final Map<RobotModel.Key, RobotModel> models = new java.util.HashMap<>();
    private final Map<String, SimRobot> byName = new LinkedHashMap<>();
    private final RangeIndex rangeIndex;
    private final long stepNanos;
    private final double stepSeconds;
    private final double physicsHz;
    private final int trajectoryEvery;
    private final Parallel parallel;
    private final FailurePolicy failures;
    /** The role robots' failures are reported under ({@code sim-<world>}). */
    private final String role;
    /** Per robot (by index): the execution action threads the world cycles, or {@code null}. */
    private Cycled[] cycled = new Cycled[0];
    /**
     * Per robot (by index): the batch that drives it ({@link #batchRobots()}), or {@code null} (its own
     * execution action thread does, if it has one). Written by the stepping thread between passes (under
     * {@link #stepLock}), read by the pass.
     */
    private SimBatch[] batchOf = new SimBatch[0];
    /** Per robot (by index): its member index in {@link #batchOf}'s batch. */
    private int[] memberOf = new int[0];
    /** The batches, in the order they were made. */
    private final List<SimBatch> batches = new ArrayList<>();
    /** Whether any batch's cycle is due in the step being taken. */
    private boolean batchCycling;
    /** Held by the stepping thread while it steps, and by a thread promoting a robot out of its batch. */
    private final java.util.concurrent.locks.ReentrantLock stepLock = new java.util.concurrent.locks.ReentrantLock();
    /** Promotions asked for on a worker thread during a pass: applied at the start of the next step. */
    private final java.util.concurrent.ConcurrentLinkedQueue<Promotion> promotions = new java.util.concurrent.ConcurrentLinkedQueue<>();

    /** A promotion asked for while a pass ran. */
    private record Promotion(int robot, java.util.function.Consumer<Pose> handOver) {
    }
    /** The earliest time a cycle is due. */
    private long nextCycle = Long.MAX_VALUE;
    private long steps;
    private boolean initialSampleDue;
    private long[] sensingPeriods;
    private final RayCaster rayCaster;
    private final RangeMethod rangeMethod;
    /** The wall clock phases are timed with, when profiling ({@link #profile}); {@code null} otherwise. */
    private Clock profileClock;
    private final long[] phaseNanos = new long[Phase.values().length];
    /** The clock the robots' parts are timed with, on the robots of every {@value #PART_SAMPLE}th index; {@code null} otherwise. */
    private volatile Clock partClock;
    /**
     * Each thread's sums of the robots' parts it timed since {@link #profile(Clock, boolean)} (by {@link Parallel#slot}, then by ordinal, after
     * {@link #PART_PAD} slots of padding: each thread's sums in cache lines of their own). Plain longs a thread adds to
     * alone: a shared adder's atomic update per part of a timed robot cost more than some parts it timed (profiled at
     * 10,000 robots on a loaded machine: 5 % of a step's processor time in {@code LongAdder.add}). Read by
     * {@link #robotPartNanos} between steps, after the pass that wrote them has ended.
     */
    private final long[][] partSums;
    /** Controllers run robot by robot in the world's own pass ({@link #addRobotController}). */
    private volatile RobotController[] controllers = new RobotController[0];
    /** The controllers due at the step being taken (touched by the stepping thread, read by the pass). */
    private RobotController[] dueControllers = new RobotController[0];
    private int dueCount;

    /** A controller's work on one robot, and how often it is due. */
    private record RobotController(long everySteps, java.util.function.IntConsumer control) {
    }

    /** The phases of a step that {@link #profile} times, in the order a step runs them. */
    public enum Phase {
        /**
         * The physics step: broadphase, contacts, integration (dyn4j: on the stepping thread; swarm: detection split between the
         * workers, the solve on the stepping thread, each body's move left to {@link #AFTER_STEP}).
         */
        PHYSICS,
        /**
         * Per robot, after the motion (worker threads): with the swarm engine its body's move, then encoders, contacts, pose; when sensors are due,
         * its body's place in the range index; in a step where no sensor and no cycle is due, also
         * its pending reads and its body's velocities (the whole step in one pass).
         */
        AFTER_STEP,
        /** The robots' cells in the range index, when sensors are due (stepping thread). */
        INDEX,
        /**
         * Per robot, in a step where sensors or cycles are due (worker threads): its range sensors that
         * are due, its execution action thread if due and its pending reads, its body's velocities.
         */
        ROBOTS
    }

    /**
     * The parts of a robot's work in a step that {@link #profile(Clock, boolean)} times (on the
     * worker threads, robot by robot: their sum is processor time, not wall time).
     */
    public enum RobotPart {
        /** After the motion: with the swarm engine the body's move itself, then encoders, contacts, the true pose, the trajectory. */
        MOTION,
        /** Its body's place in the range index, when sensors are due. */
        PLACE,
        /** Its range sensors that are due: the ray casts. */
        SENSING,
        /** Its execution action threads' cycles that are due (the Platform Layer: containers, refreshes, the inline link side and driver). */
        CYCLES,
        /** Completing its pending sensor reads. */
        READS,
        /** The robot controllers due on it (the wander controller: reading its sensors, {@code drive} through the Configuration Layer). */
        CONTROLLERS,
        /** Setting its body's velocities from its commanded wheel speeds. */
        DRIVE
    }

    /** One robot in this many has its parts timed when profiling (a clock reading per part of every robot would cost more than some parts). */
    static final int PART_SAMPLE = 8;
    /** Longs of padding on either side of a thread's sums of the robots' parts (a cache line). */
    private static final int PART_PAD = 8;

    /** Casts one ray for a range sensor. */
    @FunctionalInterface
    interface RayCaster {
        /**
         * @return the distance to the nearest hit within maxRange, or +∞
         */
        double cast(double ox, double oy, double angle, double maxRange, int self);
    }

    private double dyn4jRay(double ox, double oy, double angle, double maxRange, int self) {
        org.dyn4j.dynamics.Body own = dyn4j.body(robots.get(self).body());
        org.dyn4j.world.DetectFilter<org.dyn4j.dynamics.Body, org.dyn4j.dynamics.BodyFixture> filter =
                new org.dyn4j.world.DetectFilter<>(true, true, null) {
                    @Override
                    public boolean isAllowed(org.dyn4j.dynamics.Body body, org.dyn4j.dynamics.BodyFixture fixture) {
                        return body != own && super.isAllowed(body, fixture);
                    }
                };
        double best = Double.POSITIVE_INFINITY;
        for (var hit : dyn4j.world().raycast(new org.dyn4j.geometry.Ray(new Vector2(ox, oy), angle), maxRange, filter)) {
            best = Math.min(best, hit.getRaycast().getDistance());
        }
        return best;
    }

    /**
     * A robot's execution action thread and when it is due; {@code more}: the robot's next one, if it has more;
     * {@code poll}: a round of its link side (encoders read), for a robot promoted out of a batch, or {@code null}.
     */
    private static final class Cycled {
        private final ExecutionActionThread thread;
        private final long period;
        private final Runnable poll;
        private long next;
        private Cycled more;

        Cycled(ExecutionActionThread thread, Runnable poll, long now) {
            this.thread = thread;
            this.period = thread.period().toNanos();
            this.poll = poll;
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
        this(description, sensingThreads, rangeMethod, FailurePolicy.logging());
    }

    /**
     * Builds the world with a chosen range method, reporting robots' failures to a policy.
     *
     * @param description    the world
     * @param sensingThreads worker threads for the per-robot parts of a step
     * @param rangeMethod    how range sensors cast their rays
     * @param failures       where what one robot's part of a step throws is reported
     */
    public SimWorld(WorldDescription description, int sensingThreads, RangeMethod rangeMethod, FailurePolicy failures) {
        this.failures = java.util.Objects.requireNonNull(failures, "failures");
        this.role = "sim-" + description.name();
        this.description = description;
        this.physicsHz = description.physicsHz();
        this.stepSeconds = 1.0 / description.physicsHz();
        this.stepNanos = Math.round(1e9 / description.physicsHz());
        this.trajectoryEvery = (int) Math.max(1, Math.min(Integer.MAX_VALUE, Math.round(description.trajectories().everySeconds() * description.physicsHz())));
        this.parallel = new Parallel(sensingThreads);
        this.partSums = new long[parallel.slots()][2 * PART_PAD + RobotPart.values().length];
        this.rayBatches = new SensorModel.RayBatch[parallel.slots()];
        for (int t = 0; t < rayBatches.length; t++) {
            rayBatches[t] = new SensorModel.RayBatch();
        }
        double margin = description.wallThickness() + 1;
        if (description.engine() == WorldDescription.PhysicsEngine.SWARM) {
            if (rangeMethod == RangeMethod.DYN4J_RAYCAST) {
                parallel.close();
                throw new IllegalArgumentException("world '" + description.name() + "' (" + description.source()
                        + "): dyn4j ray casts need the dyn4j engine, not physics engine swarm");
            }
            this.dyn4j = null;
            this.physics = new SwarmPhysics(parallel, -margin, -margin, description.width() + margin, description.height() + margin);
        } else {
            this.dyn4j = new Dyn4jPhysics(stepSeconds);
            this.physics = dyn4j;
        }
        this.thinnestStatic = thinnestStatic(description);
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
                physics.addStaticCircle(c.x(), c.y(), c.radius());
                discs.add(new double[]{c.x(), c.y(), c.radius()});
            } else if (o instanceof WorldDescription.Polygon p) {
                double[][] v = p.points().toArray(double[][]::new);
                physics.addStaticPolygon(v);
                for (int i = 0; i < v.length; i++) {
                    segments.add(new double[]{v[i][0], v[i][1], v[(i + 1) % v.length][0], v[(i + 1) % v.length][1]});
                }
            }
        }
        // About one cell per robot in a crowded world (at least 4096 cells, 0.25-2 m each): a robot's
        // short rays then gather a few cells (the bodies beyond their reach are dropped as gathered),
        // and re-indexing the robots walks a quarter of the cells four per robot did (measured at
        // 10,000 robots: 14 % less processor time a step); the nearest hit is the same whatever the cells.
        double cell = Math.max(0.25, Math.min(2.0, Math.sqrt(description.width() * description.height()
                / Math.max(4096, description.robots().size()))));
        this.rangeIndex = new RangeIndex(-margin, -margin, description.width() + 2 * margin, description.height() + 2 * margin, cell,
                segments.toArray(double[][]::new), discs.toArray(double[][]::new));
        this.rangeMethod = rangeMethod;
        this.rayCaster = rangeMethod == RangeMethod.GRID ? rangeIndex::castRay : this::dyn4jRay;
        // room for the world file's robots at once (grown by doubling, 100,000 robots left a third of every array empty)
        states.reserve(description.robots().size());
    }

    /** @return half the thickness of the thinnest wall or obstacle (+∞ without any) */
    private static double thinnestStatic(WorldDescription d) {
        double thinnest = d.walls() ? d.wallThickness() : Double.POSITIVE_INFINITY;
        for (WorldDescription.Obstacle o : d.obstacles()) {
            if (o instanceof WorldDescription.Box b) {
                thinnest = Math.min(thinnest, Math.min(b.width(), b.height()));
            } else if (o instanceof WorldDescription.Circle c) {
                thinnest = Math.min(thinnest, 2 * c.radius());
            } else if (o instanceof WorldDescription.Polygon p) {
                // a convex polygon's width: the least, over its edges, of the farthest vertex from the edge's line
                List<double[]> v = p.points();
                for (int i = 0; i < v.size(); i++) {
                    double[] a = v.get(i);
                    double[] b = v.get((i + 1) % v.size());
                    double len = Math.hypot(b[0] - a[0], b[1] - a[1]);
                    double far = 0;
                    for (double[] q : v) {
                        far = Math.max(far, Math.abs((b[0] - a[0]) * (q[1] - a[1]) - (b[1] - a[1]) * (q[0] - a[0])) / len);
                    }
                    thinnest = Math.min(thinnest, far);
                }
            }
        }
        return thinnest / 2;
    }

    private void addStaticBox(double x, double y, double w, double h, double angle, List<double[]> segments) {
        physics.addStaticBox(x, y, w, h, angle);
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
        if (physics instanceof SwarmPhysics) {
            checkSwarmBody(name, description);
        }
        int body = physics.addBody(b.length(), b.width(), b.mass(), b.friction(), start.x(), start.y(), start.heading());
        RobotModel model = models.computeIfAbsent(RobotModel.Key.of(description), k -> new RobotModel(description, physicsHz));
        SimRobot robot = new SimRobot(robots.size(), name, description, physics, body, this.description.seed(), clock::nanoTime,
                this.description.trajectories(), failures, states, model, this.description.surroundings());
        robots.add(robot);
        if (robots.size() > cycled.length) {
            // grown by doubling (a copy per robot made loading 100,000 robots quadratic: minutes); slots past the robots stay empty
            int room = Math.max(robots.size(), 2 * cycled.length);
            cycled = java.util.Arrays.copyOf(cycled, room);
            batchOf = java.util.Arrays.copyOf(batchOf, room);
            memberOf = java.util.Arrays.copyOf(memberOf, room);
            bodyLength = java.util.Arrays.copyOf(bodyLength, room);
            bodyWidth = java.util.Arrays.copyOf(bodyWidth, room);
        }
        bodyLength[robot.index()] = b.length();
        bodyWidth[robot.index()] = b.width();
        byName.put(name, robot);
        initialSampleDue = true;
        sensingPeriods = null;
        return robot;
    }

    /**
     * The swarm engine has no continuous collision detection: a robot must not move, in one step,
     * more than half its own width (against another robot coming the other way) or half the thinnest
     * wall or obstacle, or it could pass through.
     */
    private void checkSwarmBody(String name, RobotDescription robot) {
        double perStep = robot.drive().map(d -> d.maxSpeed()).orElse(0.0) * stepSeconds;
        double own = Math.min(robot.body().length(), robot.body().width()) / 4;
        if (perStep > Math.min(own, thinnestStatic)) {
            throw new IllegalArgumentException(String.format(java.util.Locale.ROOT,
                    "robot '%s' moves up to %.4f m per physics step (max_speed %.3f m/s at physics_hz %.0f); the swarm engine "
                            + "has no continuous collision detection and allows at most %.4f m (a quarter of the robot's width, half "
                            + "the thinnest wall or obstacle): raise physics_hz or use physics engine dyn4j",
                    name, perStep, perStep / stepSeconds, physicsHz, Math.min(own, thinnestStatic)));
        }
    }

    /**
     * Cycles a robot's execution action thread on this world's clock from now on.
     *
     * @param robot  the robot
     * @param thread its execution action thread
     */
    public void attach(SimRobot robot, ExecutionActionThread thread) {
        attach(robot, thread, null);
    }

    /**
     * Cycles a robot's execution action thread on this world's clock from now on; a robot of a
     * motor platform whose link side the world may service on its own (its encoders read) can be
     * driven in a {@linkplain #batchRobots() batch} until it is addressed one by one.
     *
     * @param robot the robot
     * @param thread its execution action thread
     * @param poll   one round of its platform's link side (send what is published, read the encoders), or {@code null}
     */
    public void attach(SimRobot robot, ExecutionActionThread thread, Runnable poll) {
        Cycled c = new Cycled(thread, poll, clock.nanoTime());
        int i = robot.index();
        if (cycled[i] == null) {
            cycled[i] = c;
        } else {
            Cycled last = cycled[i];
            while (last.more != null) {
                last = last.more;
            }
            last.more = c;
        }
        nextCycle = Math.min(nextCycle, c.next);
    }

    /**
     * Puts the robots that can be driven together into batches, one per robot file (with its cycle
     * rate and watchdog): every robot stepped from the world's arrays alone (a differential drive,
     * nothing else to move or feel), on the ground, whose own platform is a motor platform the world
     * may poll ({@link #attach(SimRobot, ExecutionActionThread, Runnable)}). From then on a batched
     * robot's own execution action thread is not cycled: its batch ({@link SimBatch}) is, over
     * arrays, and controllers drive it through {@link #driveBatched}; until a program or an agent
     * addresses it one by one ({@link #promote}). Before the first step.
     *
     * @return the batches made
     */
    public synchronized List<SimBatch> batchRobots() {
        if (steps > 0) {
            throw new IllegalStateException("world '" + description.name() + "': robots are batched before the first step");
        }
        record Key(RobotModel model, java.time.Duration period, java.time.Duration watchdog, Object drive, Object capabilities) {
        }
        Map<Key, List<SimRobot>> groups = new LinkedHashMap<>();
        for (SimRobot r : robots) {
            int i = r.index();
            Cycled c = cycled[i];
            RobotDescription d = r.description();
            if (batchOf[i] != null || c == null || c.more != null || c.poll == null || !states.plain[i] || d.drive().isEmpty()
                    || !d.capabilities().contains(io.robomw.api.Capability.GROUND)) {
                continue;
            }
            groups.computeIfAbsent(new Key(r.model(), d.cyclePeriod(), d.watchdogTimeout(), d.drive().get(), d.capabilities()),
                    k -> new ArrayList<>()).add(r);
        }
        List<SimBatch> made = new ArrayList<>();
        for (List<SimRobot> members : groups.values()) {
            SimBatch batch = new SimBatch(members.get(0).description(), members, states, clock.nanoTime());
            for (int m = 0; m < members.size(); m++) {
                batchOf[members.get(m).index()] = batch;
                memberOf[members.get(m).index()] = m;
            }
            batches.add(batch);
            made.add(batch);
        }
        return made;
    }

    /**
     * @param robot a robot's index
     * @return whether its batch drives it ({@link #batchRobots()}), rather than its own platform
     */
    public boolean batched(int robot) {
        return batchOf[robot] != null;
    }

    /**
     * A batched robot's {@code drive(v, ω)} through its batch (Configuration Layer, then Platform
     * Layer, then the simulated motors), for controllers that work robot by robot in the world's
     * pass ({@link #addRobotController}); its robot's {@code drive} does the same for a robot that
     * is not batched.
     *
     * @param robot        a batched robot's index
     * @param linearSpeed  metres per second
     * @param angularSpeed radians per second, positive left
     * @throws IllegalStateException                    if the robot is not batched (any more)
     * @throws io.robomw.api.UnsupportedActionException naming the robot, as its {@code drive} would
     */
    public void driveBatched(int robot, double linearSpeed, double angularSpeed) {
        SimBatch batch = batchOf[robot];
        if (batch == null) {
            throw new IllegalStateException("robot '" + robots.get(robot).name() + "' is not driven in a batch; drive it through its Robot");
        }
        batch.drive(memberOf[robot], linearSpeed, angularSpeed);
    }

    /**
     * Promotes a robot out of its batch, for a program or an agent that addresses it one by one:
     * its batch releases it (the batch's drive ends, its motors brake), its own platform's link is
     * polled (its encoders read), its own execution action thread is cycled from its next due
     * cycle on (the times it would have had, had it never been batched), and {@code handOver}
     * gets the batch's odometry of it, for its own odometry to go on from. Done at once, between
     * two steps (a step under way is waited for); asked on one of the world's worker threads
     * during a pass, done at the start of the next step. Nothing if it is not batched. Any thread.
     *
     * @param robot    a robot's index
     * @param handOver takes its pose by the batch's odometry, on the thread that promotes it
     */
    public void promote(int robot, java.util.function.Consumer<Pose> handOver) {
        if (Parallel.onWorker()) {
            promotions.add(new Promotion(robot, handOver));
            return;
        }
        stepLock.lock();
        try {
            applyPromotion(robot, handOver);
        } finally {
            stepLock.unlock();
        }
    }

    /** {@link #promote}, under the step lock. */
    private void applyPromotion(int i, java.util.function.Consumer<Pose> handOver) {
        SimBatch batch = batchOf[i];
        if (batch == null) {
            return;
        }
        try {
            Pose pose = batch.release(memberOf[i]);
            batchOf[i] = null;
            long t = clock.nanoTime();
            for (Cycled c = cycled[i]; c != null; c = c.more) {
                if (c.next <= t) {
                    c.next += ((t - c.next) / c.period + 1) * c.period;
                }
                c.poll.run();
                nextCycle = Math.min(nextCycle, c.next);
            }
            handOver.accept(pose);
        } catch (Throwable e) {
            robotFailed(i, e);
        }
    }

    /** @return the batches ({@link #batchRobots()}) */
    public List<SimBatch> batches() {
        return Collections.unmodifiableList(batches);
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

    /**
     * A range sensor's last sample, without touching the robot's object: for controllers that work
     * robot by robot in the world's pass ({@link #addRobotController}).
     *
     * @param robot a robot's index
     * @param k     one of its range sensors, by its place among them ({@link SensorModel#rangeIndex()})
     * @return the sensor's last sample, metres
     */
    public double rangeReading(int robot, int k) {
        return states.range(robot, k);
    }

    /** @return the world's rigid-body physics */
    public Physics physics() {
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
            stepLock.lock();
            try {
                for (Promotion p; (p = promotions.poll()) != null; ) {
                    applyPromotion(p.robot(), p.handOver());
                }
                advance();
            } finally {
                stepLock.unlock();
            }
        } finally {
            lockstep.endStep();
        }
    }

    /** @return the worker threads of this world, for controllers that work on every robot */
    public Parallel parallel() {
        return parallel;
    }

    /**
     * Runs a controller robot by robot inside the world's own pass over the robots, at every step
     * whose number is a multiple of {@code everySteps}: for each robot, after its range sensors,
     * its execution action thread's cycle and its pending reads, before its body's velocities are
     * set, on whichever worker thread handles that robot (while its state is in that processor's
     * cache, and without a hand-over of its own). Equivalent to a step listener that calls
     * {@code control} for every robot on the worker threads (the world's clock and the robots'
     * sensors are the same), since what it commands reaches the motors at the next cycle either
     * way. {@code control} must touch only robot {@code i} and the controller's own state for it;
     * what it throws is that robot's failure (see the class description).
     *
     * @param everySteps the controller's period, in steps (at least 1)
     * @param control    its work on the robot of the given {@linkplain SimRobot#index() index}
     */
    public synchronized void addRobotController(long everySteps, java.util.function.IntConsumer control) {
        if (everySteps < 1) {
            throw new IllegalArgumentException("a controller runs every 1 or more steps, got " + everySteps);
        }
        RobotController[] more = java.util.Arrays.copyOf(controllers, controllers.length + 1);
        more[controllers.length] = new RobotController(everySteps, control);
        controllers = more;
    }

    /**
     * @param control a controller added with {@link #addRobotController}; it does not run after the current step
     */
    public synchronized void removeRobotController(java.util.function.IntConsumer control) {
        controllers = java.util.Arrays.stream(controllers).filter(c -> c.control() != control).toArray(RobotController[]::new);
    }

    /** @return whether a controller is due at this step, with the due ones in {@link #dueControllers} */
    private boolean controllersDue(long step) {
        RobotController[] all = controllers;
        if (dueControllers.length < all.length) {
            dueControllers = new RobotController[all.length];
        }
        int n = 0;
        for (RobotController c : all) {
            if (step % c.everySteps() == 0) {
                dueControllers[n++] = c;
            }
        }
        dueCount = n;
        return n > 0;
    }

    /**
     * Times every phase of the following steps on a wall clock (for benchmarks and diagnosis:
     * where a step's time goes); {@code null} stops. The totals are in {@link #phaseNanos()}.
     *
     * @param wall the wall clock, or {@code null}
     */
    public void profile(Clock wall) {
        profile(wall, false);
    }

    /**
     * Times every phase of the following steps on a wall clock, and with {@code robotParts} also
     * the {@linkplain RobotPart parts} of the robots' work on the robots of every
     * {@value #PART_SAMPLE}th index (see {@link #robotPartNanos()}); {@code null} stops both.
     *
     * @param wall       the wall clock, or {@code null}
     * @param robotParts whether to time the robots' parts too
     */
    public void profile(Clock wall, boolean robotParts) {
        profileClock = wall;
        java.util.Arrays.fill(phaseNanos, 0);
        for (long[] sums : partSums) {
            java.util.Arrays.fill(sums, 0); // between steps: no thread adds to them now
        }
        partClock = robotParts ? wall : null;
    }

    /** @return wall nanoseconds spent in each {@link Phase} (by ordinal) since {@link #profile} */
    public long[] phaseNanos() {
        return phaseNanos.clone();
    }

    /**
     * @return the nanoseconds spent in each {@link RobotPart} (by ordinal) since {@link #profile(Clock, boolean)}, summed over
     *         every robot and thread: estimated from the robots timed (those of every {@value #PART_SAMPLE}th index), scaled
     *         to all of them
     */
    public long[] robotPartNanos() {
        int n = robots.size();
        int timed = (n + PART_SAMPLE - 1) / PART_SAMPLE;
        long[] out = new long[RobotPart.values().length];
        for (int k = 0; k < out.length; k++) {
            long sum = 0;
            for (long[] sums : partSums) {
                sum += sums[PART_PAD + k];
            }
            out[k] = timed == 0 ? 0 : Math.round(sum * (double) n / timed);
        }
        return out;
    }

    /** @return the clock to time robot {@code i}'s parts with, or {@code null} if they are not timed */
    private Clock partClock(int i) {
        Clock c = partClock;
        return c != null && i % PART_SAMPLE == 0 ? c : null;
    }

    /** Adds the time since {@code since} to a part; @return now */
    private long part(Clock c, RobotPart part, long since) {
        long now = c.nanoTime();
        partSums[parallel.slot()][PART_PAD + part.ordinal()] += now - since;
        return now;
    }

    private long tick(long since, Phase phase) {
        Clock c = profileClock;
        if (c == null) {
            return 0;
        }
        long now = c.nanoTime();
        if (phase != null) {
            phaseNanos[phase.ordinal()] += now - since;
        }
        return now;
    }

    private void advance() {
        int n = robots.size();
        if (initialSampleDue) {
            boolean grid = rangeMethod == RangeMethod.GRID;
            if (grid) {
                rangeIndex.robots(n);
            }
            parallel.forEach(n, i -> {
                if (grid) {
                    place(i);
                }
            });
            if (grid) {
                rangeIndex.indexPlacedRobots();
            }
            parallel.forEach(n, i -> {
                try {
                    sense(i, -1);
                } catch (Throwable e) {
                    robotFailed(i, e);
                }
            });
            initialSampleDue = false;
        }
        long t = tick(0, null);
        // the bodies' moves are left to the pass below that reads their new poses (each robot has one body)
        boolean moves = physics.stepLeavingMoves(stepSeconds);
        t = tick(t, Phase.PHYSICS);
        long step = ++steps;
        boolean record = step % trajectoryEvery == 0;
        long now = clock.nanoTime() + stepNanos;
        boolean sensing = sensingDue(step);
        batchCycling = false;
        for (int b = 0; b < batches.size(); b++) {
            SimBatch batch = batches.get(b);
            int due = 0;
            while (batch.nextCycle <= now) {
                batch.nextCycle += batch.periodNanos;
                due++;
            }
            batch.cyclesDue = due;
            batchCycling |= due > 0;
        }
        boolean cycling = now >= nextCycle || batchCycling;
        boolean controlling = controllersDue(step);
        if (!sensing && !cycling && !controlling) {
            // No robot's work after the motion reads the clock or another robot: one pass.
            RobotStates st = states;
            boolean reads = readsPending;
            readsPending = false;
            parallel.forEach(n, i -> {
                try {
                    Clock timer = partClock(i);
                    long t0 = timer == null ? 0 : timer.nanoTime();
                    if (moves) {
                        physics.move(st.body[i]);
                    }
                    if (st.plain[i]) {
                        // a plain robot's step from the world's arrays alone: no object of it is touched
                        st.afterStep(i, physics, record);
                        if (timer != null) {
                            t0 = part(timer, RobotPart.MOTION, t0);
                        }
                        if (reads && cycled[i] != null && batchOf[i] == null) {
                            robots.get(i).completeReads(this);
                        }
                        if (timer != null) {
                            t0 = part(timer, RobotPart.READS, t0);
                        }
                        st.drive(i, physics);
                    } else {
                        SimRobot r = robots.get(i);
                        r.afterStep(stepSeconds, record);
                        if (timer != null) {
                            t0 = part(timer, RobotPart.MOTION, t0);
                        }
                        if (cycled[i] != null && batchOf[i] == null) {
                            r.completeReads(this);
                        }
                        if (timer != null) {
                            t0 = part(timer, RobotPart.READS, t0);
                        }
                        r.applyDrive();
                    }
                    if (timer != null) {
                        part(timer, RobotPart.DRIVE, t0);
                    }
                } catch (Throwable e) {
                    robotFailed(i, e);
                }
            });
            t = tick(t, Phase.AFTER_STEP);
            clock.advanceNanos(stepNanos);
            t = tick(t, Phase.INDEX);
            tick(t, Phase.ROBOTS);
            return;
        }
        boolean grid = sensing && rangeMethod == RangeMethod.GRID;
        if (grid) {
            rangeIndex.robots(n);
        }
        RobotStates st = states;
        parallel.forEach(n, i -> {
            Clock timer = partClock(i);
            long t0 = timer == null ? 0 : timer.nanoTime();
            try {
                if (moves) {
                    physics.move(st.body[i]);
                }
                if (st.plain[i]) {
                    st.afterStep(i, physics, record);
                } else {
                    robots.get(i).afterStep(stepSeconds, record);
                }
            } catch (Throwable e) {
                robotFailed(i, e);
            }
            if (timer != null) {
                t0 = part(timer, RobotPart.MOTION, t0);
            }
            if (grid) {
                place(i);
                if (timer != null) {
                    part(timer, RobotPart.PLACE, t0);
                }
            }
        });
        t = tick(t, Phase.AFTER_STEP);
        clock.advanceNanos(stepNanos);
        if (grid) {
            rangeIndex.indexPlacedRobots();
        }
        t = tick(t, Phase.INDEX);
        long senseStep = sensing ? step : 0;
        RobotController[] due = dueControllers;
        int dueNow = dueCount;
        readsPending = false;
        parallel.forEach(n, i -> {
            Clock timer = partClock(i);
            try {
                long t0 = timer == null ? 0 : timer.nanoTime();
                if (senseStep != 0) {
                    sense(i, senseStep);
                    if (timer != null) {
                        t0 = part(timer, RobotPart.SENSING, t0);
                    }
                }
                SimBatch batch = batchOf[i];
                Cycled c = batch == null ? cycled[i] : null;
                if (batch != null) {
                    if (batch.cyclesDue > 0) {
                        // the Platform Layer of its batch: its member's cycle over the batch's arrays
                        batch.cycle(memberOf[i], now);
                        if (timer != null) {
                            t0 = part(timer, RobotPart.CYCLES, t0);
                        }
                    }
                } else if (c != null) {
                    SimRobot r = robots.get(i);
                    for (; c != null; c = c.more) {
                        while (c.next <= now) {
                            c.next += c.period; // first: a cycle that throws is not run again in this step
                            c.thread.cycle();
                        }
                    }
                    if (timer != null) {
                        t0 = part(timer, RobotPart.CYCLES, t0);
                    }
                    r.completeReads(this);
                    if (timer != null) {
                        t0 = part(timer, RobotPart.READS, t0);
                    }
                }
                for (int k = 0; k < dueNow; k++) {
                    due[k].control().accept(i);
                }
                if (timer != null && dueNow > 0) {
                    t0 = part(timer, RobotPart.CONTROLLERS, t0);
                }
                if (st.plain[i]) {
                    st.drive(i, physics);
                } else {
                    robots.get(i).applyDrive();
                }
                if (timer != null) {
                    part(timer, RobotPart.DRIVE, t0);
                }
            } catch (Throwable e) {
                robotFailed(i, e);
            }
        });
        if (cycling) {
            long earliest = Long.MAX_VALUE;
            for (int i = 0; i < n; i++) {
                if (batchOf[i] != null) {
                    continue; // its own thread is not cycled while its batch drives it
                }
                for (Cycled c = cycled[i]; c != null; c = c.more) {
                    earliest = Math.min(earliest, c.next);
                }
            }
            nextCycle = earliest;
        }
        tick(t, Phase.ROBOTS);
    }

    /**
     * What robot {@code i}'s part of a step threw: reported, and its commands end with it at its
     * next cycle (their end actions stop its motors); the step goes on for the others. On the
     * worker thread that handled the robot.
     *
     * @throws VirtualMachineError the failure itself, if no thread survives it (the step ends with it)
     */
    private void robotFailed(int i, Throwable failure) {
        SimRobot r = robots.get(i);
        failures.surviveOrRethrow(role + ": robot '" + r.name() + "'", failure);
        SimBatch batch = batchOf[i];
        if (batch != null) {
            batch.failed(memberOf[i]); // its batch's drive of it ends: its motors brake
            return;
        }
        for (Cycled c = cycled[i]; c != null; c = c.more) {
            c.thread.linkFailed("to its simulated body in world '" + description.name() + "'", failure);
        }
    }

    /**
     * Stops the world for good, when the thread stepping it dies: every robot's commands end with
     * {@code why} (each execution action thread is cycled once more, on the calling thread, so
     * their end actions stop the motors), every robot's motors are set to rest, and every wait on
     * a simulator future ends with {@code why}, now and later. Must not throw; later steps are
     * the caller's to refuse.
     *
     * @param why what the programs are told, naming what killed the world's thread
     */
    public void halt(io.robomw.api.RobotException why) {
        for (int i = 0; i < robots.size(); i++) {
            for (Cycled c = cycled[i]; c != null; c = c.more) {
                try {
                    c.thread.linkFailed("to its simulated world '" + description.name() + "'", why);
                    c.thread.cycle();
                } catch (Throwable ignored) {
                    // the thread is dying already: what cannot be stopped here is failed below
                }
            }
            try {
                robots.get(i).halt();
            } catch (Throwable ignored) {
                // as above
            }
        }
        lockstep.fail(why);
    }

    /** Places robot {@code i}'s body in the range index, from its pose after the step. */
    private void place(int i) {
        RobotStates st = states;
        rangeIndex.placeRobot(i, st.x[i], st.y[i], st.cos[i], st.sin[i], bodyLength[i], bodyWidth[i]);
    }

    /** Each robot's body length and width, for the range index (by robot index). */
    private double[] bodyLength = new double[0];
    private double[] bodyWidth = new double[0];

    /** Set by a read queued on any robot, cleared by the step that completes the reads: a step with none looks at no robot's queue. */
    private volatile boolean readsPending;

    /** A robot queued a read: the next step completes it. Any thread. */
    void readQueued() {
        readsPending = true;
    }

    /**
     * Samples a robot's range sensors that are due.
     *
     * @param step the step number, or -1 for every sensor
     */
    private void sense(int i, long step) {
        RobotStates st = states;
        RobotModel model = st.model[i];
        List<SensorModel> sensors = model.rangeSensors;
        if (sensors.isEmpty()) {
            return;
        }
        // a plain robot without noise is sensed from the world's arrays and its file's models alone: its own object is not reached
        SimRobot r = st.plain[i] && !model.noisy ? null : robots.get(i);
        double x = st.x[i];
        double y = st.y[i];
        double heading = st.heading[i];
        double c = st.cos[i];
        double s = st.sin[i];
        double pan = st.plain[i] ? 0 : r.headPan();
        double tilt = st.plain[i] ? 0 : r.headTilt();
        double[] ranges = st.ranges;
        int start = st.rangeStart[i];
        if (rangeMethod != RangeMethod.GRID) {
            for (int k = 0; k < sensors.size(); k++) {
                SensorModel m = sensors.get(k);
                if (step < 0 || step % m.everySteps() == 0) {
                    ranges[start + k] = m.sampleRange(rayCaster, i, x, y, heading, c, s, pan, tilt, (r == null ? null : r.noise(k)));
                }
            }
            return;
        }
        // every due sensor's rays cast together: what is around the robot is gathered once
        SensorModel.RayBatch batch = rayBatches[parallel.slot()];
        boolean[] due = batch.due(sensors, step);
        batch.count = 0;
        for (int k = 0; k < due.length; k++) {
            if (due[k]) {
                sensors.get(k).addRays(batch, x, y, heading, c, s, pan);
            }
        }
        if (model.rangeReach > 0) {
            // sensors all round: what is around the robot is what lies within their reach of its centre
            rangeIndex.castRaysWithin(x, y, model.rangeReach, batch.ox, batch.oy, batch.dx, batch.dy, batch.maxRange, batch.count, i, batch.hits,
                    batch.gathered);
        } else {
            rangeIndex.castRays(batch.ox, batch.oy, batch.dx, batch.dy, batch.maxRange, batch.count, i, batch.hits, batch.gathered);
        }
        int first = 0;
        for (int k = 0; k < due.length; k++) {
            SensorModel m = sensors.get(k);
            if (due[k]) {
                ranges[start + k] = m.finishRange(batch.hits, first, tilt, (r == null ? null : r.noise(k)));
                first += m.rays();
            }
        }
    }

    /** Each worker thread's rays of the robot it senses for (by {@link Parallel#slot}: steps are taken one at a time). */
    private final SensorModel.RayBatch[] rayBatches;

    /** @return whether any range sensor samples at this step */
    private boolean sensingDue(long step) {
        if (sensingPeriods == null) {
            java.util.TreeSet<Long> periods = new java.util.TreeSet<>();
            for (SimRobot r : robots) {
                for (SensorModel s : r.rangeSensors()) {
                    periods.add(s.everySteps());
                }
            }
            sensingPeriods = periods.stream().mapToLong(Long::longValue).toArray();
        }
        for (long p : sensingPeriods) {
            if (step % p == 0) {
                return true;
            }
        }
        return false;
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
