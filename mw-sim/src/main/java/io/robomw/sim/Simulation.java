package io.robomw.sim;

import io.robomw.api.Robot;
import io.robomw.api.RobotException;
import io.robomw.api.spi.FailurePolicy;
import io.robomw.api.spi.IdleStrategy;
import io.robomw.api.spi.OwnerThread;
import io.robomw.api.spi.PlatformProvider;
import io.robomw.api.spi.AgencyConfig;
import io.robomw.api.spi.MessagingConfig;
import io.robomw.api.spi.PlatformServices;
import io.robomw.api.spi.RobotPlatform;
import io.robomw.config.description.RobotDescription;
import io.robomw.config.description.RobotDescriptionLoader;
import io.robomw.config.robot.ConfiguredRobot;
import io.robomw.config.robot.DescriptionRobotFactory;
import io.robomw.sim.world.WorldDescription;
import io.robomw.sim.world.WorldLoader;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.io.IOException;
import java.nio.file.Path;
import java.time.Duration;
import java.util.ArrayList;
import java.util.HashMap;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Map;
import java.util.Set;
import java.util.concurrent.CopyOnWriteArrayList;
import java.util.concurrent.locks.LockSupport;
import java.util.function.BooleanSupplier;

/**
 * A simulated world with its robots opened through all three layers: each robot is a
 * {@link Robot} (Configuration Layer) on the {@code sim} platform (Platform Layer, found by
 * {@link java.util.ServiceLoader}) whose body is in the world. The robot files of the world are
 * used as they are, whatever their {@code platform:}: in a simulation they run on {@code sim}.
 *
 * <p>The robots of one robot file that can be driven together (see {@link SimWorld#batchRobots()})
 * start in a batch: the same three layers over arrays, which controllers drive through
 * {@link SimWorld#driveBatched}. Each is still a {@link Robot} ({@link #robot}, {@link #robots}):
 * its first verb promotes it out of its batch, and from then on it runs on its own stack.
 *
 * <h2>Two ways to run</h2>
 * <ul>
 *   <li><b>As fast as possible</b>, repeatably: {@link #run(Duration, Runnable...)} runs programs
 *   on their own threads and advances the world only while all of them wait for their robots
 *   (lockstep), so the same seed and programs give the same trajectories, bit for bit.
 *   {@link #runFor(Duration)} advances the world without programs (for step listeners).</li>
 *   <li><b>In real time</b>: {@link #startRealTime(double)} steps the world on a thread of its own,
 *   paced by the wall clock (times a speed factor); programs call robots from any thread.</li>
 * </ul>
 *
 * <h2>Failures</h2>
 * The thread that steps the world (the real-time thread, an {@link OwnerThread}, or the caller of
 * the fast runs) owns the simulation's clock, and hands what it catches to the simulation's
 * {@link FailurePolicy} (the one in the {@link PlatformServices} it was given, else a
 * {@linkplain FailurePolicy#logging() logging} one; every simulated robot's platform reports to
 * the same one):
 * <ul>
 *   <li>a failure it can survive fails what it concerns, and the clock goes on: a step listener's
 *   is reported and the other listeners run; one robot's (its sensors, its cycle, a controller's
 *   work on it) ends that robot's commands (see {@link SimWorld}); in a real-time run, a failure
 *   of the whole step (the physics) is reported and the next step is tried;</li>
 *   <li>any other one (see {@link FailurePolicy#survivable}) {@linkplain SimWorld#halt halts} the
 *   world: every robot's motors stop, every program waiting for a robot, and every later call,
 *   fails at once with a {@link RobotException} naming the failure ({@link #failure()}), and the
 *   thread ends cleanly.</li>
 * </ul>
 * In a fast run, a failure of the whole step ends the run the same way, and reaches its caller.
 */
public final class Simulation implements AutoCloseable {

    private static final Logger LOG = LoggerFactory.getLogger(Simulation.class);
    private static final long STALL_NANOS = Duration.ofSeconds(60).toNanos();
    /**
     * How far a real-time run may fall behind the wall clock and still catch up, stepping back to
     * back: a thread held up by a collection or a loaded machine for less than this loses no
     * simulated time, so hardware timed by the wall clock (a driver's just-in-time stop, an
     * emulated brick's motors) sees the motion it commanded. Held up longer (a debugger, a
     * suspended laptop), the run goes on from now instead of racing through the missed time.
     */
    static final long CATCH_UP_NANOS = Duration.ofSeconds(1).toNanos();

    private final SimWorld world;
    /** Every robot opened here, by name: its own, or its handle while its world drives it in a batch ({@link BatchedRobot}). */
    private final Map<String, Robot> robots = new LinkedHashMap<>();
    /** Every robot's own Configuration Layer, to close. */
    private final List<ConfiguredRobot> opened = new ArrayList<>();
    private final List<Runnable> stepListeners = new CopyOnWriteArrayList<>();
    private final Set<String> emulated;
    private final FailurePolicy failures;
    /** The role the clock's owner reports under, and the real-time thread's name: {@code sim-<world>}. */
    private final String role;
    private volatile boolean realTime;
    private volatile boolean paused;
    private volatile double realTimeSpeed = 1;
    private volatile long stepWallNanos;
    private volatile boolean stepScheduled;
    private OwnerThread realTimeThread;
    /** Why the world was halted, once it was. */
    private volatile RobotException failure;

    private Simulation(WorldDescription description, int sensingThreads, SimWorld.RangeMethod rangeMethod, Set<String> emulated,
                       PlatformServices given) {
        this.failures = given.find(FailurePolicy.class).orElseGet(FailurePolicy::logging);
        this.role = "sim-" + description.name();
        this.world = new SimWorld(description, sensingThreads, rangeMethod, failures);
        this.emulated = Set.copyOf(emulated);
        RobotDescriptionLoader loader = new RobotDescriptionLoader();
        Map<Path, RobotDescription> files = new HashMap<>();
        try {
            for (WorldDescription.RobotPlacement p : description.robots()) {
                RobotDescription d = renamed(files.computeIfAbsent(p.description(), loader::load), p.name());
                try {
                    world.addRobot(p.name(), d, p.start());
                } catch (IllegalArgumentException e) {
                    throw new RobotException(description.source() + ": robot '" + p.name() + "' (" + p.description() + "): " + e.getMessage(), e);
                }
            }
            PlatformServices services = given.with(SimWorld.class, world).with(FailurePolicy.class, failures);
            // the providers looked up once, not three class path scans a robot (minutes for 100,000 robots)
            Map<String, PlatformProvider> providers = new HashMap<>();
            Map<List<?>, List<io.robomw.api.spi.SensorChannel>> channels = new java.util.IdentityHashMap<>();
            io.robomw.api.spi.RobotComponents components = io.robomw.api.spi.RobotComponents.find();
            for (SimRobot r : world.robots()) {
                if (this.emulated.contains(r.name())) {
                    continue;
                }
                RobotDescription d = r.description();
                PlatformProvider provider = providers.computeIfAbsent(d.platform(), k -> DescriptionRobotFactory.provider(d));
                // one list of sensor channels for every robot of a robot file (its renamed copies share its sensors)
                List<io.robomw.api.spi.SensorChannel> sensorChannels = channels.computeIfAbsent(d.sensors(), k -> DescriptionRobotFactory.sensorChannels(d));
                RobotPlatform platform = provider.open(DescriptionRobotFactory.platformConfig(d, sensorChannels, services, world.clock(),
                        io.robomw.api.spi.Cycling.BY_OWNER));
                try {
                    ConfiguredRobot robot = ConfiguredRobot.withComponents(() -> d, platform, null, components);
                    opened.add(robot);
                    robots.put(r.name(), robot);
                } catch (RuntimeException e) {
                    platform.close();
                    throw e;
                }
            }
            // Robots of one robot file are driven together, over arrays, until one is addressed one by one.
            world.batchRobots();
            for (SimRobot r : world.robots()) {
                if (world.batched(r.index())) {
                    robots.put(r.name(), new BatchedRobot((ConfiguredRobot) robots.get(r.name()), world, r.index()));
                }
            }
        } catch (IOException e) {
            close();
            throw new RobotException(description.source() + ": cannot open the simulated robots: " + e.getMessage(), e);
        } catch (RuntimeException e) {
            close();
            throw e;
        }
    }

    /**
     * Loads a world file and opens its robots.
     *
     * @param worldFile the world YAML
     * @return the simulation, with the world at time 0
     */
    public static Simulation load(Path worldFile) {
        return create(new WorldLoader().load(worldFile));
    }

    /**
     * Loads a world file whose named robots are driven from outside, by brick emulators: they get a
     * body in the world but no in-process platform.
     *
     * @param worldFile the world YAML
     * @param emulated  names of the robots that emulators drive
     * @return the simulation
     */
    public static Simulation load(Path worldFile, Set<String> emulated) {
        return load(worldFile, emulated, PlatformServices.none());
    }

    /**
     * Loads a world file, some of whose robots are driven by brick emulators, with services for
     * every robot's platform: a {@link FailurePolicy} among them is the one the simulation's
     * clock, its robots' platforms and its emulators report to.
     *
     * @param worldFile the world YAML
     * @param emulated  names of the robots that emulators drive (none: every robot runs in this process)
     * @param services  services for the platforms (the simulation adds its world, and its failure policy)
     * @return the simulation
     */
    public static Simulation load(Path worldFile, Set<String> emulated, PlatformServices services) {
        WorldDescription d = new WorldLoader().load(worldFile);
        for (String name : emulated) {
            if (d.robots().stream().noneMatch(r -> r.name().equals(name))) {
                throw new IllegalArgumentException(d.source() + " has no robot '" + name + "'; its robots are "
                        + d.robots().stream().map(WorldDescription.RobotPlacement::name).toList());
            }
        }
        return new Simulation(d, Runtime.getRuntime().availableProcessors(), SimWorld.RangeMethod.GRID, emulated, services);
    }

    /**
     * @param description a world
     * @return the simulation, sensing on as many threads as there are processors
     */
    public static Simulation create(WorldDescription description) {
        return create(description, Runtime.getRuntime().availableProcessors());
    }

    /**
     * @param description    a world
     * @param sensingThreads threads for range sensing
     * @return the simulation
     */
    public static Simulation create(WorldDescription description, int sensingThreads) {
        return new Simulation(description, sensingThreads, SimWorld.RangeMethod.GRID, Set.of(), PlatformServices.none());
    }

    /**
     * @param description    a world
     * @param sensingThreads worker threads
     * @param rangeMethod    how range sensors cast rays (the benchmark compares both)
     * @return the simulation
     */
    public static Simulation create(WorldDescription description, int sensingThreads, SimWorld.RangeMethod rangeMethod) {
        return new Simulation(description, sensingThreads, rangeMethod, Set.of(), PlatformServices.none());
    }

    private static RobotDescription renamed(RobotDescription d, String name) {
        MessagingConfig m = d.messaging();
        AgencyConfig a = d.agency();
        // A node or home named after the robot (the default) takes the name the world gives it.
        MessagingConfig messaging = m.nodeName().equals(d.name())
                ? new MessagingConfig(name, m.listen(), m.connect(), m.topicPasswords(), m.source()) : m;
        AgencyConfig agency = a.homeName().equals(AgencyConfig.defaults(d.name(), a.source()).homeName())
                ? new AgencyConfig(AgencyConfig.defaults(name, a.source()).homeName(), a.bind(), a.port(), a.clusterKey(), a.source()) : a;
        return new RobotDescription(name, "sim", d.connection(), d.cyclePeriod(), d.watchdogTimeout(), d.capabilities(), d.drive(),
                d.body(), d.sensors(), d.actuators(), d.leggedDrive(), d.highLevelActions(), messaging, agency, d.source(), d.vehicleDrive());
    }

    /** @return the policy the simulation's clock, its robots' platforms and its emulators report failures to */
    public FailurePolicy failures() {
        return failures;
    }

    /**
     * @return why the world was halted (the thread stepping it died of a failure it could not
     *         survive, or a fast run's step failed), if it was: every robot call fails with it
     */
    public java.util.Optional<RobotException> failure() {
        return java.util.Optional.ofNullable(failure);
    }

    /** @return the world */
    public SimWorld world() {
        return world;
    }

    /**
     * @param name a robot's name in the world
     * @return the robot
     * @throws IllegalArgumentException if there is none of that name
     */
    public Robot robot(String name) {
        Robot r = robots.get(name);
        if (r == null && emulated.contains(name)) {
            throw new IllegalArgumentException("robot '" + name + "' is driven by a brick emulator; open it through its driver (a robot file with its real platform)");
        }
        if (r == null) {
            throw new IllegalArgumentException("world '" + world.description().name() + "' has no robot '" + name + "'; it has " + robots.keySet());
        }
        return r;
    }

    /** @return every robot, in the world's order */
    public List<Robot> robots() {
        return List.copyOf(robots.values());
    }

    /**
     * @param listener run on the stepping thread after every step (a controller, a recorder)
     */
    public void addStepListener(Runnable listener) {
        stepListeners.add(listener);
    }

    /**
     * @param listener a listener added before; it is not run after the current step
     */
    public void removeStepListener(Runnable listener) {
        stepListeners.remove(listener);
    }

    /**
     * One step and its listeners. A listener's survivable failure is reported and the others run;
     * what the world's step throws, and a failure nothing survives, leave for the caller.
     */
    private void step() {
        world.step();
        for (Runnable l : stepListeners) {
            try {
                l.run();
            } catch (Throwable t) {
                failures.surviveOrRethrow(role + ": step listener " + l, t);
            }
        }
    }

    /**
     * A step taken on the caller's thread (a fast run, the first real-time step): a failure of
     * the step halts the world and goes on to the caller.
     */
    private void stepOnCaller() {
        try {
            step();
        } catch (Throwable t) {
            halt(t, "a step at " + String.format(java.util.Locale.ROOT, "%.3f", world.time()) + " s failed");
            if (!FailurePolicy.survivable(t)) {
                failures.died(role, t); // the caller hears of it too, but the one counter sees every death
            }
            throw t;
        }
    }

    /**
     * Halts the world for good: records why, stops every robot and fails every wait (see
     * {@link SimWorld#halt}). Must not throw.
     *
     * @param cause what killed the stepping
     * @param what  what happened, for the message
     */
    private void halt(Throwable cause, String what) {
        RobotException why = new RobotException("simulation '" + world.description().name() + "' (" + world.description().source() + "): "
                + what + ": " + cause + "; every robot was stopped and simulated time stands still (close the simulation and load it again)", cause);
        if (failure == null) {
            failure = why;
        }
        realTime = false;
        world.halt(failure);
    }

    private void requireNotHalted(String what) {
        RobotException failed = failure;
        if (failed != null) {
            throw new RobotException("cannot " + what + ": " + failed.getMessage(), failed);
        }
    }

    /**
     * The wall-clock time the step now being taken stands for, for step listeners that mirror
     * hardware running in real time (a brick emulator's motors): in a real-time run, the step's
     * scheduled time, which is in the past when the run catches up after its thread was held up;
     * otherwise the time now.
     *
     * @return {@link System#nanoTime()} time
     */
    public long stepWallNanos() {
        return stepScheduled ? stepWallNanos : System.nanoTime();
    }

    /**
     * Runs programs in lockstep with the world, as fast as possible, until they all finish.
     * Each program runs on its own thread named {@code program-N}; the world advances only while
     * every program waits for a robot call.
     *
     * @param maxSimTime the longest the programs may take in simulated time
     * @param programs   the programs
     * @throws RobotException if a program fails (its exception is the cause), or runs over time
     */
    public void run(Duration maxSimTime, Runnable... programs) {
        requireStopped("run programs");
        requireNotHalted("run programs");
        world.lockstep().driver(Thread.currentThread());
        double end = world.time() + maxSimTime.toNanos() / 1e9;
        Programs running = new Programs(world.lockstep(), programs);
        try {
            while (true) {
                world.lockstep().awaitAllWaiting(STALL_NANOS);
                if (!world.lockstep().hasPrograms()) {
                    break;
                }
                if (world.time() > end) {
                    throw new RobotException("programs did not finish within " + maxSimTime.toMillis() / 1000.0 + " s of simulated time; still running: "
                            + running.running());
                }
                stepOnCaller();
            }
        } finally {
            world.lockstep().driver(null);
            running.join(1000);
        }
        running.rethrowFailures();
    }

    /**
     * Starts programs on their own threads for a real-time run ({@link #startRealTime}); they may
     * call their robots at once, and wait while the run is paused. (For a fast, repeatable run,
     * use {@link #run(Duration, Runnable...)}.)
     *
     * @param programs the programs
     * @return the running programs, to check on
     */
    public Programs startPrograms(Runnable... programs) {
        return new Programs(world.lockstep(), programs);
    }

    /**
     * Advances the world by a span of simulated time, as fast as possible, without programs.
     *
     * @param simTime how long
     */
    public void runFor(Duration simTime) {
        requireStopped("step");
        requireNotHalted("step");
        world.lockstep().driver(Thread.currentThread());
        try {
            double end = world.time() + simTime.toNanos() / 1e9 - world.stepSeconds() / 2;
            while (world.time() < end) {
                stepOnCaller();
            }
        } finally {
            world.lockstep().driver(null);
        }
    }

    /**
     * Advances the world until a condition holds.
     *
     * @param condition checked after every step
     * @param maxSimTime the longest to go
     * @return whether the condition held in time
     */
    public boolean runUntil(BooleanSupplier condition, Duration maxSimTime) {
        requireStopped("step");
        requireNotHalted("step");
        double end = world.time() + maxSimTime.toNanos() / 1e9;
        while (!condition.getAsBoolean()) {
            if (world.time() >= end) {
                return false;
            }
            stepOnCaller();
        }
        return true;
    }

    /**
     * Starts stepping the world on an {@link OwnerThread} named {@code sim-<world>}, paced by the
     * wall clock. The first step is taken before this returns. A run whose thread was held up for
     * up to a second catches up, stepping back to back; held up longer, it goes on from now. What
     * the thread catches goes to the simulation's {@link FailurePolicy} (see the class description).
     *
     * @param speed simulated seconds per wall-clock second (1 = real time)
     * @throws RobotException if the world was halted by a failure
     */
    public synchronized void startRealTime(double speed) {
        requireNotHalted("run in real time");
        if (realTimeThread != null) {
            throw new IllegalStateException("the simulation already runs in real time");
        }
        if (!(speed > 0)) {
            throw new IllegalArgumentException("speed must be > 0, got " + speed);
        }
        realTime = true;
        paused = false;
        realTimeSpeed = speed;
        // One step before returning: sensors are sampled and emulators' inputs are set up by the time
        // anyone talks to a robot.
        stepOnCaller();
        // Robot calls may wait from now on; the run's thread takes the driver's place at its first round.
        world.lockstep().driver(Thread.currentThread());
        RealTimeRun run = new RealTimeRun();
        realTimeThread = OwnerThread.start(role, Thread.NORM_PRIORITY, run, run, failures);
    }

    /**
     * The real-time run's duty and its pacing, on its owner thread: each round takes one step at
     * its scheduled wall-clock time (the idle wait between rounds is the pacing), or, paused, none.
     */
    private final class RealTimeRun implements OwnerThread.Duty, IdleStrategy {

        /** How long a paused run, or one whose step failed, waits before it looks again (a resume wakes it sooner). */
        private static final long IDLE_NANOS = 10_000_000;

        /** When the next step is due, {@link System#nanoTime()} time; owner thread only. */
        private long next = System.nanoTime();
        private boolean started;

        @Override
        public int doWork() {
            if (!started) {
                started = true;
                world.lockstep().driver(Thread.currentThread()); // programs that block wake this thread, not the caller's
            }
            if (paused) {
                return 0;
            }
            stepWallNanos = next;
            stepScheduled = true;
            step();
            return 1;
        }

        @Override
        public void idle(int steps) {
            if (steps == 0) {
                // paused, or the step failed (reported): simulated time holds, and goes on from now
                LockSupport.parkNanos(this, IDLE_NANOS);
                next = System.nanoTime();
                return;
            }
            next += Math.round(world.stepSeconds() * 1e9 / realTimeSpeed);
            for (long now; realTime && (now = System.nanoTime()) < next; ) {
                LockSupport.parkNanos(this, next - now);
            }
            long late = System.nanoTime() - next;
            if (late > CATCH_UP_NANOS) {
                LOG.debug("real-time run {} ms behind the wall clock; going on from now", late / 1_000_000);
                next = System.nanoTime();
            }
        }

        @Override
        public void onDeath(Throwable failure) {
            halt(failure, "its real-time thread " + role + " died");
        }
    }

    /**
     * Pauses a real-time run: simulated time stands still, and robot calls from any thread wait
     * (they are not refused) until {@link #resumeRealTime()}.
     */
    public void pauseRealTime() {
        paused = true;
    }

    /** Resumes a paused real-time run. */
    public void resumeRealTime() {
        paused = false;
        OwnerThread t = realTimeThread;
        if (t != null) {
            t.wake();
        }
    }

    /** @return whether a real-time run is paused */
    public boolean isPaused() {
        return paused;
    }

    /**
     * Changes the speed of a real-time run without stopping it.
     *
     * @param speed simulated seconds per wall-clock second, &gt; 0
     */
    public void setRealTimeSpeed(double speed) {
        if (!(speed > 0)) {
            throw new IllegalArgumentException("speed must be > 0, got " + speed);
        }
        realTimeSpeed = speed;
    }

    /** @return simulated seconds per wall-clock second of the real-time run */
    public double realTimeSpeed() {
        return realTimeSpeed;
    }

    /** Stops the real-time thread, waiting for its current step. */
    public synchronized void stopRealTime() {
        OwnerThread t = realTimeThread;
        if (t == null) {
            return;
        }
        realTime = false;
        t.close();
        stepScheduled = false;
        realTimeThread = null;
        world.lockstep().driver(null);
    }

    private void requireStopped(String what) {
        if (realTimeThread != null) {
            throw new IllegalStateException("cannot " + what + " while the simulation runs in real time; call stopRealTime() first");
        }
    }

    /** Stops the real-time thread, closes every robot and the world. */
    @Override
    public void close() {
        stopRealTime();
        for (ConfiguredRobot r : opened) {
            try {
                r.close();
            } catch (RuntimeException e) {
                LOG.warn("closing simulated robot {}: {}", r.name(), e.toString());
            }
        }
        world.close();
    }
}
