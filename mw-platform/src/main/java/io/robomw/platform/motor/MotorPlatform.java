package io.robomw.platform.motor;

import io.robomw.api.Clock;
import io.robomw.api.RobotException;
import io.robomw.api.spi.CommandPriority;
import io.robomw.api.spi.MotorCommand;
import io.robomw.api.spi.MotorTarget;
import io.robomw.api.spi.PlatformConfig;
import io.robomw.platform.exec.Container;
import io.robomw.platform.exec.ExecutionActionThread;
import io.robomw.platform.exec.LogicObject;
import io.robomw.platform.exec.RefreshSlot;

import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.Locale;
import java.util.Set;
import java.util.concurrent.CompletableFuture;

/**
 * The paper's motor platform: turns motor commands into containers for the execution action
 * thread and keeps each motor's wanted state; a {@link MotorDriver} pushes the states to the brick.
 * A platform writer implements the driver and builds this around it; nothing here is subclassed.
 *
 * <h2>Threads</h2>
 * {@link #container}, {@link #stopContainer} and {@link #submitDetached} may be called on any
 * thread: they build containers (the caller's thread does, in {@code RobotPlatform.run}) whose
 * actions, logic and end actions then run on the execution action thread, the <b>action side</b>;
 * {@link #flushOutputs} runs there too, at the end of each cycle, and publishes the states that
 * changed. The <b>link side</b> ({@link #linkSide()}: the brick's link agent's thread, or inline on
 * a simulation's cycling thread) takes them whole and hands them to the driver; readings come
 * back through each port's own state object (see {@link MotorLinkSide}). The driver never runs on
 * the action thread, so the action thread never waits for I/O.
 *
 * <p>A command whose targets are all continuous ({@code drive}) refreshes a running continuous
 * command on the same motors in place, so a program repeating it at 10 Hz costs one container,
 * not ten a second; sent with {@link #submitDetached} (nobody waits for it), it goes through the
 * platform's {@link RefreshSlot} and costs no container at all after the first.
 *
 * <h2>Reaching a target</h2>
 * A logic object per motor ends its rotation when the {@link RotationPredictor} says the rotation,
 * by the time a stop sent now reaches the brick, is within half a cycle's travel of the target. A
 * motor without encoder ({@link MotorDriver#hasEncoder}) is stopped by time: {@code degrees /
 * speed} after the start. A brick that ends a limited rotation itself
 * ({@link LinkTiming#stopsAtLimit()}) is not stopped by the middleware: the rotation is done when
 * the driver reports that the brick stopped the motor after the state that started it was sent
 * ({@link FeedbackSink#stoppedAtLimit}); the brick counts from where the motor was when the
 * command arrived, which a reading taken here may not know yet on a busy link. A rotation that has
 * not reached its target {@code 3 × degrees / speed + 2 s} after it started fails with a
 * {@link RobotException} (the motor is blocked, or the brick stopped answering with progress),
 * instead of leaving its caller waiting.
 */
public final class MotorPlatform {

    /** The refresh key of all-continuous commands: a newer one on the same motors and priority refreshes the running one. */
    private static final String CONTINUOUS = "continuous";
    /** The logic object of a continuous command: it never holds, so the command runs until replaced, stopped or its watchdog fires. */
    private static final LogicObject NEVER = now -> false;

    /** The most a rotation that still moves may take, in {@link #deadlineNanos} windows, before it counts as blocked. */
    static final int MOST_DEADLINES = 4;

    private final String robot;
    private final Clock clock;
    private final Set<String> ports;
    /** Every motor's state on both sides, in the description's port order; fixed at construction. */
    private final MotorPort[] motors;
    private final MotorDriver driver;
    private final RotationPredictor predictor;
    private final MotorHandOff handOff;
    private final MotorLinkSide linkSide;
    /** Whether a container set a wanted state this cycle that the next flush publishes; action side. */
    private boolean anyChanged;
    /** Stops whose action ran this cycle, for the next flush; action side. */
    private final List<CompletableFuture<Void>> stopsThisCycle = new ArrayList<>(2);
    /** The requirements of the last command's motors, kept so a repeated {@code drive} shares one set. */
    private volatile Requirements lastRequirements;
    /** The slot detached all-continuous commands go through ({@link #submitDetached}), made for the last such command. */
    private volatile DriveSlot driveSlot;

    /** The motors a command names, in its order, and the set of their ports a container requires. */
    private record Requirements(MotorPort[] motors, Set<String> set) {
    }

    /**
     * @param robot       the robot's name, for messages
     * @param clock       the clock the action thread runs on
     * @param ports       every motor port this platform drives, in the description's order (a
     *                    driver's {@link FeedbackSink#degrees(int, double)} counts in it)
     * @param cyclePeriod the execution action thread's period, which targets are anticipated by
     * @param driver      the brick's motor driver
     */
    public MotorPlatform(String robot, Clock clock, List<String> ports, Duration cyclePeriod, MotorDriver driver) {
        this.robot = robot;
        this.clock = clock;
        this.ports = Set.copyOf(ports);
        List<String> order = List.copyOf(ports);
        this.motors = new MotorPort[order.size()];
        for (int i = 0; i < motors.length; i++) {
            motors[i] = new MotorPort(order.get(i), i);
        }
        this.driver = driver;
        this.predictor = new RotationPredictor(clock, driver.timing(), cyclePeriod.toNanos());
        this.handOff = new MotorHandOff(motors);
        this.linkSide = new MotorLinkSide(this, motors, driver, predictor, handOff);
    }

    /**
     * The motor platform of a robot's description: its name, clock, motor ports and cycle period.
     *
     * @param config the platform's configuration
     * @param driver the brick's motor driver
     */
    public MotorPlatform(PlatformConfig config, MotorDriver driver) {
        this(config.robotName(), config.clock(), config.motorPorts(), config.cyclePeriod(), driver);
    }

    /**
     * Says that the link side is serviced on the thread that cycles the action side, right after
     * each {@link #flushOutputs} (a platform without I/O, cycled by its owner: a simulation), and on
     * the closing thread once cycling has stopped: one thread at a time, so a cycle's batch is
     * handed over without the lock a link thread of its own needs, and a stop just in time does
     * not wait. Call before the first cycle.
     */
    public void linkServicedInline() {
        handOff.inline();
        linkSide.inline();
    }

    /** @return the link side, which the brick's link agent runs */
    public MotorLinkSide linkSide() {
        return linkSide;
    }

    /** @return where a driver's readings go, for a driver that also reads outside {@link MotorDriver#poll} (a sensor read) */
    public FeedbackSink feedback() {
        return linkSide.feedback();
    }

    /** @return the robot's name */
    public String robot() {
        return robot;
    }

    /** @return the motor ports */
    public Set<String> ports() {
        return ports;
    }

    /** @return the clock */
    Clock clock() {
        return clock;
    }

    /**
     * @param port a motor port
     * @return whether this motor's rotation is read back ({@link MotorDriver#hasEncoder})
     */
    public boolean hasEncoder(String port) {
        return driver.hasEncoder(port);
    }

    /**
     * @param port a motor port
     * @return the last encoder reading, degrees
     */
    public double motorDegrees(String port) {
        return port(port).readingDegrees();
    }

    // ---- action side ----

    /**
     * Builds the container of a motor command: it starts every motor, stops each when its target
     * is reached, and on interruption stops them all (braking). Any thread.
     *
     * @param command the command
     * @return its container
     * @throws IllegalArgumentException if a target names a port this platform does not drive
     */
    public Container container(MotorCommand command) {
        List<MotorTarget> targets = command.targets();
        Requirements required = requirements(targets);
        MotorPort[] used = required.motors();
        Container.Builder b = Container.builder(command.name())
                .requires(required.set())
                .priority(command.priority())
                .watchdog(command.watchdogTimeout());
        boolean continuous = true;
        for (MotorTarget t : targets) {
            continuous &= t.continuous();
        }
        if (continuous) {
            // A drive: its speeds taken now, so the action thread reads one small array, not the command.
            return continuousContainer(b, used, speeds(command));
        }
        long[] startedAt = new long[1];
        MotorState[] started = new MotorState[targets.size()];
        // Per target: the encoder reading at the start, the farthest it has moved from there, and when it last moved on.
        double[] origin = new double[targets.size()];
        double[] farthest = new double[targets.size()];
        long[] movedAt = new long[targets.size()];
        b.action(now -> {
            startedAt[0] = now;
            for (int i = 0; i < targets.size(); i++) {
                MotorTarget t = targets.get(i);
                origin[i] = used[i].readingDegrees();
                movedAt[i] = now;
                double speed = t.degrees() == 0 ? 0 : t.degreesPerSecond();
                if (t.continuous()) {
                    if (!same(used[i].wanted, speed, t.degrees(), MotorState.StopMode.BRAKE)) {
                        setWanted(used[i], new MotorState(t.port(), speed, t.degrees(), MotorState.StopMode.BRAKE), false);
                    }
                } else {
                    started[i] = new MotorState(t.port(), speed, t.degrees(), MotorState.StopMode.BRAKE);
                    setWanted(used[i], started[i], true);
                }
            }
        });
        for (int i = 0; i < targets.size(); i++) {
            MotorTarget t = targets.get(i);
            if (t.continuous()) {
                continue;
            }
            int index = i;
            MotorPort p = used[i];
            b.logic(now -> {
                if (reached(p, t, started[index], now - startedAt[0])) {
                    setWanted(p, MotorState.stopped(t.port(), MotorState.StopMode.BRAKE), false);
                    return true;
                }
                double moved = Math.abs(p.readingDegrees() - origin[index]);
                if (moved > farthest[index]) {
                    farthest[index] = moved;
                    movedAt[index] = now;
                }
                long stall = deadlineNanos(t);
                if (now - movedAt[index] > stall || now - startedAt[0] > MOST_DEADLINES * stall) {
                    throw new RobotException(String.format(Locale.ROOT,
                            "robot '%s': motor %s did not finish turning %.0f° at %.0f°/s: its encoder %s (turned about %.0f°); is it blocked?",
                            robot, t.port(), t.degrees(), Math.abs(t.degreesPerSecond()),
                            now - movedAt[index] > stall ? String.format(Locale.ROOT, "showed no progress for %.1f s", stall / 1e9)
                                    : String.format(Locale.ROOT, "still short after %.1f s", MOST_DEADLINES * stall / 1e9),
                            predictor.turned(p)));
                }
                return false;
            });
        }
        b.onEnd(interrupted -> {
            for (MotorPort p : used) {
                stop(p, MotorState.StopMode.BRAKE);
            }
        });
        return b.build();
    }

    /** The container of an all-continuous command (a drive) on these motors, from its builder with name, motors, priority and watchdog set. */
    private Container continuousContainer(Container.Builder b, MotorPort[] used, double[] speeds) {
        b.action(now -> setSpeeds(used, speeds));
        b.logic(NEVER);
        b.refreshes(CONTINUOUS);
        b.onEnd(interrupted -> {
            for (MotorPort p : used) {
                stop(p, MotorState.StopMode.BRAKE);
            }
        });
        return b.build();
    }

    /** What a drive's action does: wants each motor turning at its speed, without end. */
    private void setSpeeds(MotorPort[] used, double[] speeds) {
        for (int i = 0; i < used.length; i++) {
            MotorPort p = used[i];
            // A refreshed drive most often asks for what is wanted already: nothing to change.
            if (!same(p.wanted, speeds[i], Double.POSITIVE_INFINITY, MotorState.StopMode.BRAKE)) {
                setWanted(p, new MotorState(p.name, speeds[i], Double.POSITIVE_INFINITY, MotorState.StopMode.BRAKE), false);
            }
        }
    }

    /** @return a command's speeds, in its targets' order */
    private static double[] speeds(MotorCommand command) {
        List<MotorTarget> targets = command.targets();
        double[] speeds = new double[targets.size()];
        for (int i = 0; i < speeds.length; i++) {
            speeds[i] = targets.get(i).degreesPerSecond();
        }
        return speeds;
    }

    /**
     * Hands a command nobody waits for to the execution action thread: an all-continuous one (a
     * {@code drive}) through this platform's {@link RefreshSlot} for its motors, name, priority and
     * watchdog (no container per refresh: the cycle refreshes the running drive in place, or starts
     * one from the slot's speeds, in the command's place among the others); anything else as its
     * {@link #container}.
     *
     * @param command the command
     * @param thread  the robot's execution action thread
     * @throws IllegalArgumentException if a target names a port this platform does not drive
     */
    public void submitDetached(MotorCommand command, ExecutionActionThread thread) {
        List<MotorTarget> targets = command.targets();
        for (int i = 0; i < targets.size(); i++) { // no iterator: a drive is refreshed at every tick of every robot
            if (!targets.get(i).continuous()) {
                thread.submit(container(command));
                return;
            }
        }
        if (targets.size() == 2) {
            thread.refresh(driveSlot(command), targets.get(0).degreesPerSecond(), targets.get(1).degreesPerSecond());
        } else {
            thread.refresh(driveSlot(command), speeds(command));
        }
    }

    /** @return the slot for this all-continuous command: the last one made if it fits, else a new one (the old retired) */
    private RefreshSlot driveSlot(MotorCommand command) {
        DriveSlot last = driveSlot;
        if (last != null && last.fits(command)) {
            return last.slot;
        }
        synchronized (this) {
            last = driveSlot;
            if (last != null && last.fits(command)) {
                return last.slot;
            }
            DriveSlot made = new DriveSlot(command.name(), requirements(command.targets()), command.priority(), command.watchdogTimeout());
            if (last != null) {
                last.slot.retire();
            }
            driveSlot = made;
            return made.slot;
        }
    }

    /** The refresh slot of all-continuous commands on some motors, with one name, priority and watchdog. */
    private final class DriveSlot implements RefreshSlot.Handler {
        final String name;
        final Requirements required;
        final CommandPriority priority;
        final Duration watchdog;
        final RefreshSlot slot;

        DriveSlot(String name, Requirements required, CommandPriority priority, Duration watchdog) {
            this.name = name;
            this.required = required;
            this.priority = priority;
            this.watchdog = watchdog;
            this.slot = new RefreshSlot(name, required.set(), priority, CONTINUOUS, required.motors().length, this);
        }

        /** @return whether a command goes through this slot: the same motors in the same order, name, priority and watchdog */
        boolean fits(MotorCommand command) {
            List<MotorTarget> targets = command.targets();
            MotorPort[] used = required.motors();
            if (targets.size() != used.length || command.priority() != priority || !command.name().equals(name)
                    || !command.watchdogTimeout().equals(watchdog)) {
                return false;
            }
            for (int i = 0; i < used.length; i++) {
                if (!used[i].name.equals(targets.get(i).port())) {
                    return false;
                }
            }
            return true;
        }

        @Override
        public void refresh(double[] values, long nowNanos) {
            setSpeeds(required.motors(), values);
        }

        @Override
        public Container container(double[] values) {
            Container.Builder b = Container.builder(name).requires(required.set()).priority(priority).watchdog(watchdog);
            return continuousContainer(b, required.motors(), values.clone());
        }
    }

    /**
     * The motors a command's targets name, in its order, and the set of their ports: the last
     * command's when it named the same motors (a {@code drive} repeated at every tick), so its
     * containers share one set and the action thread compares them at a glance.
     *
     * @throws IllegalArgumentException if a target names a port this platform does not drive
     */
    private Requirements requirements(List<MotorTarget> targets) {
        Requirements last = lastRequirements;
        if (last != null && last.motors().length == targets.size()) {
            boolean same = true;
            for (int i = 0; i < targets.size() && same; i++) {
                same = last.motors()[i].name.equals(targets.get(i).port());
            }
            if (same) {
                return last;
            }
        }
        MotorPort[] used = new MotorPort[targets.size()];
        List<String> names = new ArrayList<>(targets.size());
        for (int i = 0; i < used.length; i++) {
            used[i] = port(targets.get(i).port());
            names.add(used[i].name);
        }
        Requirements r = new Requirements(used, Set.copyOf(names));
        lastRequirements = r;
        return r;
    }

    /** @return whether a wanted state equals the one these values make for its port (as {@link MotorState#equals} compares them) */
    private static boolean same(MotorState wanted, double degreesPerSecond, double limitDegrees, MotorState.StopMode mode) {
        return wanted != null && Double.compare(wanted.degreesPerSecond(), degreesPerSecond) == 0
                && Double.compare(wanted.limitDegrees(), limitDegrees) == 0 && wanted.stopMode() == mode;
    }

    /** Wants a motor stopped; allocates no state if it is wanted stopped that way already. */
    private void stop(MotorPort p, MotorState.StopMode mode) {
        if (!same(p.wanted, 0, 0, mode)) {
            setWanted(p, MotorState.stopped(p.name, mode), false);
        }
    }

    /**
     * @return a safety-priority container that stops every motor at once and holds them for one
     *         cycle, so that no normal command queued in the same cycle can restart them
     */
    public Container stopContainer() {
        return stopContainer(null);
    }

    /**
     * {@link #stopContainer()}, telling when the stop is on the wire.
     *
     * @param handed completed once the link side has written the batch that carries the stop (or
     *               every batch before it, when the motors were stopped already), or {@code null}
     * @return the container
     */
    public Container stopContainer(CompletableFuture<Void> handed) {
        return Container.builder("stop")
                .requires(ports)
                .priority(CommandPriority.SAFETY)
                .action(now -> {
                    for (MotorPort p : motors) {
                        stop(p, MotorState.StopMode.BRAKE);
                    }
                    if (handed != null) {
                        stopsThisCycle.add(handed);
                    }
                })
                .logic(now -> true)
                .build();
    }

    /**
     * Fails every stop still waiting to be written (the link failed, the platform closed).
     *
     * @param why what the waiting callers get
     */
    public void failPendingStops(RuntimeException why) {
        handOff.failPendingStops(why);
    }

    private boolean reached(MotorPort p, MotorTarget t, MotorState started, long elapsedNanos) {
        double speed = Math.abs(t.degreesPerSecond());
        if (t.degrees() == 0 || speed == 0) {
            return true;
        }
        if (p.stoppedAtLimit() == started) {
            return true;
        }
        if (predictor.timing().stopsAtLimit()) {
            return false;
        }
        if (!driver.hasEncoder(t.port())) {
            return elapsedNanos >= t.degrees() / speed * 1e9;
        }
        MotorPort.Start start = p.start();
        if (start == null || start.state() != started) {
            return false;
        }
        double lead = speed * predictor.cycleNanos() / 2e9;
        return predictor.turned(p, start) >= t.degrees() - lead;
    }

    /**
     * How long a rotation's encoder may show no progress before it counts as blocked: three times
     * its time at speed, plus 2 s. A rotation that moves on, however slowly (a driver that creeps up
     * to its target slower while the host is loaded, as the Intelligent Interface's does), goes on,
     * up to {@link #MOST_DEADLINES} of these in all.
     */
    private static long deadlineNanos(MotorTarget t) {
        return Math.round(3 * t.degrees() / Math.abs(t.degreesPerSecond()) * 1e9) + 2_000_000_000L;
    }

    /** @param always publish it even if it equals the wanted state (a new rotation, which the brick must start again) */
    private void setWanted(MotorPort p, MotorState state, boolean always) {
        MotorState before = p.wanted;
        p.wanted = state;
        if (always || !state.equals(before)) {
            p.changed = state;
            anyChanged = true;
        }
    }

    /**
     * Publishes the states changed during this cycle for the link side, without saying which
     * cycle it is (a refusal of them then concerns every command).
     *
     * @return whether anything changed
     */
    public boolean flushOutputs() {
        return flushOutputs(Long.MAX_VALUE);
    }

    /**
     * Publishes the states changed during this cycle for the link side, as one batch, and queues
     * this cycle's stops behind it. Called by the action thread at the end of each cycle.
     *
     * @param cycle the execution action thread's cycle that set them (the one now ending)
     * @return whether anything changed
     */
    public boolean flushOutputs(long cycle) {
        boolean changed = anyChanged;
        if (changed) {
            handOff.publish(cycle);
            anyChanged = false;
        }
        if (!stopsThisCycle.isEmpty()) {
            handOff.queueStops(stopsThisCycle);
            stopsThisCycle.clear();
        }
        return changed;
    }

    /**
     * Sets every motor to coast (its output idle, drawing no current) and publishes it: what a
     * robot leaves its motors in when it closes, as the bricks' own tools do on stop-and-disconnect.
     * Called by the closing thread once the execution action thread has stopped.
     */
    public void coastAll() {
        for (MotorPort p : motors) {
            stop(p, MotorState.StopMode.COAST);
        }
        flushOutputs();
    }

    /**
     * @return the port's state
     * @throws IllegalArgumentException if this platform drives no motor on that port
     */
    MotorPort port(String port) {
        for (MotorPort p : motors) {
            if (p.name.equals(port)) {
                return p;
            }
        }
        throw new IllegalArgumentException("robot '" + robot + "' has no motor on port " + port + "; its motor ports are " + ports);
    }
}
