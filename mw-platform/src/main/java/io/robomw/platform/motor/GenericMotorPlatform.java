package io.robomw.platform.motor;

import io.robomw.api.Clock;
import io.robomw.api.RobotException;
import io.robomw.api.spi.CommandPriority;
import io.robomw.api.spi.MotorCommand;
import io.robomw.api.spi.MotorTarget;
import io.robomw.platform.exec.Container;
import io.robomw.platform.exec.RefreshSlot;

import java.io.IOException;
import java.util.ArrayList;
import java.util.List;
import java.util.Set;
import java.util.concurrent.CompletableFuture;

/**
 * The paper's motor platform: turns motor commands into containers for the execution action
 * thread, keeps each motor's wanted state, and hands changed states to the driver's
 * {@link #runImpl(List)}. A platform writer subclasses it and implements {@code runImpl} (encode
 * the brick's motor telegrams) and, for motors with encoders, {@link #pollFeedback()}.
 *
 * <h2>Threads</h2>
 * Two sides, so the action thread never waits for I/O:
 * <ul>
 *   <li>the <b>action side</b> ({@link #container}, {@link #stopContainer}, {@link #flushOutputs})
 *   runs on the execution action thread: it sets wanted states and, once per cycle, publishes the
 *   changed ones;</li>
 *   <li>the <b>link side</b> ({@link #serviceLink}) runs on the platform's link thread (or inline,
 *   for a simulator without I/O): it calls {@code runImpl} with the published states, then
 *   {@code pollFeedback}, which reports encoder readings with {@link #reportDegrees}.</li>
 * </ul>
 * Encoder readings and published states cross between the sides through each port's own
 * state object (a reading's two numbers behind a sequence lock, states as immutable records with
 * release stores; a cycle's published batch under one lock): the ports are fixed at construction,
 * so nothing is looked up by name in a map.
 *
 * <p>A command whose targets are all continuous ({@code drive}) refreshes a running continuous
 * command on the same motors in place, so a program repeating it at 10 Hz costs one container,
 * not ten a second; sent with {@link #submitDetached} (nobody waits for it), it goes through the
 * platform's {@link RefreshSlot} and costs no container at all after the first.
 *
 * <h2>Reaching a target</h2>
 * A logic object per motor watches its rotation since the container started, and stops the motor
 * when the rotation is within half a cycle's travel of the target. A reading is a sample the brick
 * took one link delay ({@link #linkDelayNanos()}) before it arrived, and a stop sent now reaches
 * the brick one link delay later: so the logic compares the target with the last reading moved on
 * by the commanded speed over its age and the time a command takes to reach the brick
 * ({@link #commandDelayNanos()}: a link delay, and on a link that carries one exchange at a time
 * the wait for the one under way), so a slow link's delays do not become overshoot. A motor without encoder is stopped by
 * time: {@code degrees / speed} after the start.
 *
 * <p>A brick that ends a limited rotation itself (the NXT's tacho limit; {@link #stopsAtLimit()})
 * is not stopped by the middleware: the rotation is done when the driver reports, with
 * {@link #reportStoppedAtLimit}, that the brick stopped the motor after the state that started it
 * was sent. The brick counts from where the motor was when the command arrived, which a reading
 * taken by the action thread may not know yet (its last reading can be several cycles old on a
 * busy link): comparing the rotation with such a reading can stop the motor early, or never see
 * the target at all.
 *
 * <p>A rotation that has not reached its target {@code 3 × degrees / speed + 2 s} after it
 * started fails with a {@link RobotException} (the motor is blocked, or the brick stopped
 * answering with progress), instead of leaving its caller waiting.
 */
public abstract class GenericMotorPlatform {

    private final String robot;
    private final Clock clock;
    private final Set<String> ports;
    /** Every motor's state on both sides, in the description's port order; the ports are fixed at construction. */
    private final Port[] motors;
    /** Whether a container set a wanted state this cycle that the next {@link #flushOutputs} publishes; action side. */
    private boolean anyChanged;
    /** Guards the ports' {@code published} states, so a cycle's batch is handed over whole. */
    private final Object publishLock = new Object();
    /**
     * Whether any port has a published state the link side has not taken; written under
     * {@link #publishLock} with a release store, read first without it (acquire).
     */
    private boolean anyPublished;
    /** The cycle whose states were published last ({@link #flushOutputs(long)}); under {@link #publishLock}. */
    private long publishedCycle = Long.MAX_VALUE;
    /** The cycle whose published states the link side took last; link side. */
    private long servedCycle = Long.MAX_VALUE;
    /** Batches published so far (each flush that changed something is one); under {@link #publishLock}. */
    private long publishedBatches;
    /** The count of published batches the link side took last; link side. */
    private long takenBatches;
    /** Batches the link side has written (all up to the count); written under {@link #publishLock}. */
    private long sentBatches;
    /** Stops waiting to be handed to the link: each with the batch that must be written first; under {@link #publishLock}. */
    private final List<PendingStop> pendingStops = new ArrayList<>(2);
    /** Stops whose action ran this cycle, for the next flush; action side. */
    private final List<CompletableFuture<Void>> stopsThisCycle = new ArrayList<>(2);
    /** Whether the link side runs on the action side's thread right after each flush ({@link #linkServicedInline}). */
    private boolean linkInline;
    /** A stop waiting for the link side to write every batch up to {@code batch}. */
    private record PendingStop(long batch, CompletableFuture<Void> handed) {
    }

    /** The requirements of the last command's motors, kept so a repeated {@code drive} shares one set. */
    private volatile Requirements lastRequirements;
    private volatile long cyclePeriodNanos = 10_000_000L;

    /**
     * One motor port: its wanted state (action side), the state published for the link side, and
     * what the link side sent, read and predicted for it. One object per port instead of a map per
     * kind keyed by port names: a cycle touches each port's state in one place.
     */
    private static final class Port {
        final String name;
        final int index;
        /** Action side only. */
        MotorState wanted;
        /** Action side only: set this cycle, published by the next flush, else {@code null}. */
        MotorState changed;
        /** Guarded by {@link #publishLock}: published for the link side, not yet taken. */
        MotorState published;
        /** Link side only, during a service: the state taken for this batch, and the one sent before it. */
        MotorState draining;
        MotorState sentBefore;
        // Handed between the sides with release stores and acquire loads (plain moves on x86, no
        // fence per reading): one side writes each, the values are immutable records, and no
        // decision needs a store ordered before a later load of another field.
        // The last encoder reading and the clock time the brick sampled it at, in fields rather
        // than an object per reading (two a cycle per robot: each a reference stored into this
        // long-lived object, a card for G1 to refine), behind a sequence lock: the link side writes
        // them (readingVersion odd while it does, 0 before the first), any thread reads them whole.
        private double readingDegrees;
        private long readingAtNanos;
        private int readingVersion;
        /** Where the motor was, by prediction, when the brick took the running state last sent for it; link side writes. */
        private Start start;
        /** The last state handed to {@code runImpl}; link side writes. */
        private MotorState sent;
        /** A limited rotation the brick stopped by itself (or the link side stopped just in time). */
        private MotorState stoppedAtLimit;

        /** Records a reading; link side only (one writer). */
        void reading(double degrees, long atNanos) {
            int version = readingVersion;
            READING_VERSION.setOpaque(this, version + 1);
            java.lang.invoke.VarHandle.storeStoreFence();
            readingDegrees = degrees;
            readingAtNanos = atNanos;
            READING_VERSION.setRelease(this, version + 2);
        }

        /** @return the reading's version before reading its fields (then {@link #readingWhole}) */
        int readingBegin() {
            return (int) READING_VERSION.getAcquire(this);
        }

        /**
         * @param version what {@link #readingBegin} returned before the fields were read
         * @return whether the fields read since were one whole reading (else read again: the link
         *         side was writing them, two stores)
         */
        boolean readingWhole(int version) {
            java.lang.invoke.VarHandle.loadLoadFence();
            return (version & 1) == 0 && (int) READING_VERSION.getOpaque(this) == version;
        }

        /** @return the last reading's degrees, 0 before the first */
        double readingDegrees() {
            while (true) {
                int version = readingBegin();
                double degrees = readingDegrees;
                if (readingWhole(version)) {
                    return degrees;
                }
                Thread.onSpinWait();
            }
        }

        Start start() {
            return (Start) START.getAcquire(this);
        }

        void start(Start st) {
            START.setRelease(this, st);
        }

        MotorState sent() {
            return (MotorState) SENT.getAcquire(this);
        }

        void sent(MotorState st) {
            SENT.setRelease(this, st);
        }

        MotorState stoppedAtLimit() {
            return (MotorState) STOPPED_AT_LIMIT.getAcquire(this);
        }

        void stoppedAtLimit(MotorState st) {
            STOPPED_AT_LIMIT.setRelease(this, st);
        }

        private static final java.lang.invoke.VarHandle READING_VERSION;
        private static final java.lang.invoke.VarHandle START;
        private static final java.lang.invoke.VarHandle SENT;
        private static final java.lang.invoke.VarHandle STOPPED_AT_LIMIT;

        static {
            try {
                java.lang.invoke.MethodHandles.Lookup l = java.lang.invoke.MethodHandles.lookup();
                READING_VERSION = l.findVarHandle(Port.class, "readingVersion", int.class);
                START = l.findVarHandle(Port.class, "start", Start.class);
                SENT = l.findVarHandle(Port.class, "sent", MotorState.class);
                STOPPED_AT_LIMIT = l.findVarHandle(Port.class, "stoppedAtLimit", MotorState.class);
            } catch (ReflectiveOperationException e) {
                throw new ExceptionInInitializerError(e);
            }
        }

        Port(String name, int index) {
            this.name = name;
            this.index = index;
            this.wanted = MotorState.stopped(name, MotorState.StopMode.BRAKE);
        }
    }

    /** The motors a command names, in its order, and the set of their ports a container requires. */
    private record Requirements(Port[] motors, Set<String> set) {
    }

    /** The refresh key of all-continuous commands: a newer one on the same motors and priority refreshes the running one. */
    private static final String CONTINUOUS = "continuous";

    /** The slot detached all-continuous commands go through ({@link #submitDetached}), made for the last such command. */
    private volatile DriveSlot driveSlot;

    /** The logic object of a continuous command: it never holds, so the command runs until replaced, stopped or its watchdog fires. */
    private static final io.robomw.platform.exec.LogicObject NEVER = now -> false;

    /**
     * @param robot the robot's name, for messages
     * @param clock the clock the action thread runs on
     * @param ports every motor port this platform drives
     */
    protected GenericMotorPlatform(String robot, Clock clock, List<String> ports) {
        this.robot = robot;
        this.clock = clock;
        this.ports = Set.copyOf(ports);
        List<String> order = List.copyOf(ports);
        this.motors = new Port[order.size()];
        for (int i = 0; i < motors.length; i++) {
            motors[i] = new Port(order.get(i), i);
        }
    }

    /**
     * Says that the link side is serviced on the thread that cycles the action side, right after
     * each {@link #flushOutputs} (a platform without I/O: the simulator's, whose
     * {@code BrickPlatform} runs it {@code INLINE}), and on the closing thread once cycling has
     * stopped: one thread at a time, so a cycle's batch is handed over without the lock a link
     * thread of its own needs. Call before the first cycle.
     */
    public void linkServicedInline() {
        linkInline = true;
    }

    /**
     * Pushes motor states to the hardware. Called on the link side with the states that changed
     * since the last call, in port order of the description.
     *
     * @param motors the changed motors
     * @throws IOException if the link failed; the platform reports it to the action thread
     */
    protected abstract void runImpl(List<MotorState> motors) throws IOException;

    /**
     * Reads encoders and reports them with {@link #reportDegrees}. Called on the link side after
     * every {@link #runImpl}. The default reads nothing.
     *
     * @throws IOException if the link failed
     */
    protected void pollFeedback() throws IOException {
    }

    /**
     * @return whether the brick stops a limited rotation ({@link MotorState#limitDegrees()}) by
     *         itself and the driver reports it with {@link #reportStoppedAtLimit} (default: no,
     *         the middleware stops it by the encoder)
     */
    protected boolean stopsAtLimit() {
        return false;
    }

    /**
     * Says that the brick has stopped this motor by itself, after the last state {@link #runImpl}
     * sent for it. Called by drivers from {@link #pollFeedback()} when the brick reports the motor
     * idle; ends the limited rotation that state started (if it did).
     *
     * @param port the motor port
     */
    protected final void reportStoppedAtLimit(String port) {
        Port p = port(port);
        MotorState last = p.sent();
        if (last != null && last.running() && !Double.isInfinite(last.limitDegrees())) {
            p.stoppedAtLimit(last);
        }
    }

    /**
     * @param port a motor port
     * @return whether this motor has an encoder (default: every motor)
     */
    public boolean hasEncoder(String port) {
        return true;
    }

    /** @return the robot's name */
    public String robot() {
        return robot;
    }

    /** @return the motor ports */
    public Set<String> ports() {
        return ports;
    }

    /**
     * @param period the execution action thread's period, used to anticipate targets
     */
    public void cyclePeriod(java.time.Duration period) {
        cyclePeriodNanos = period.toNanos();
    }

    /**
     * Records an encoder reading. Called by drivers from {@link #pollFeedback()}, or by a
     * simulator.
     *
     * @param port    the motor port
     * @param reading degrees of the motor shaft
     */
    protected final void reportDegrees(String port, double reading) {
        port(port).reading(reading, clock.nanoTime() - linkDelayNanos());
    }

    /**
     * {@link #reportDegrees(String, double)} by the port's position in the list the platform was
     * built with, for drivers that poll every motor in that order (no lookup by name).
     *
     * @param portIndex the port's index in the constructor's {@code ports}
     * @param reading   degrees of the motor shaft
     */
    protected final void reportDegrees(int portIndex, double reading) {
        motors[portIndex].reading(reading, clock.nanoTime() - linkDelayNanos());
    }

    /**
     * How long the link takes one way: a reading is that old when it arrives, and a command takes
     * that long to reach the brick. Drivers on slow links return half their measured round trip
     * (see {@code RoundTripEstimate}); the default, 0, suits links without delay.
     *
     * @return the one-way delay, nanoseconds
     */
    protected long linkDelayNanos() {
        return 0;
    }

    /**
     * How long before {@link #runImpl} returns the brick acted on the last command it sent: by
     * default the link's one-way delay (the reply's way back).
     *
     * @return nanoseconds
     */
    protected long actedNanosAgo() {
        return linkDelayNanos();
    }

    /**
     * @param port a motor port
     * @return the degrees one count of its encoder stands for, when the encoder is so coarse that
     *         a reading is only the nearest count (a rotation sensor's 22.5°): the platform then
     *         predicts by the motor's own speed since it started, within half a count of the
     *         reading; 0 (the default) for encoders whose readings are taken as they are
     */
    protected double encoderResolutionDegrees(String port) {
        return 0;
    }

    /**
     * The speed a brick actually turns a motor at in a state: the state's own speed by default;
     * a brick that sets speeds in steps (the RCX's eight power steps) returns its step's speed, so
     * that predictions of where the motor is use it.
     *
     * @param state a motor state
     * @return degrees per second, signed
     */
    protected double actualDegreesPerSecond(MotorState state) {
        return state.degreesPerSecond();
    }

    /**
     * How long a command handed to the link now takes to reach the brick: the link's one-way delay,
     * plus the wait for an exchange already under way on a link that carries one at a time.
     * Drivers on slow links override it; the default is {@link #linkDelayNanos()}.
     *
     * @return nanoseconds
     */
    protected long commandDelayNanos() {
        return linkDelayNanos();
    }

    /**
     * A rotation's state, where the motor was predicted to be when the brick took it, and when
     * that was ({@link Long#MAX_VALUE} while the driver is still sending it: a brick that takes
     * several packets to start a motor starts it only with the last).
     */
    private record Start(MotorState state, double degrees, long sinceNanos) {
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
     * is reached, and on interruption stops them all (braking).
     *
     * @param command the command
     * @return its container
     */
    public Container container(MotorCommand command) {
        List<MotorTarget> targets = command.targets();
        Requirements required = requirements(targets);
        Port[] used = required.motors();
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
        b.action(now -> {
            startedAt[0] = now;
            for (int i = 0; i < targets.size(); i++) {
                MotorTarget t = targets.get(i);
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
            Port p = used[i];
            b.logic(now -> {
                if (reached(p, t, started[index], now - startedAt[0])) {
                    setWanted(p, MotorState.stopped(t.port(), MotorState.StopMode.BRAKE), false);
                    return true;
                }
                long deadline = deadlineNanos(t);
                if (now - startedAt[0] > deadline) {
                    throw new RobotException(String.format(java.util.Locale.ROOT,
                            "robot '%s': motor %s did not finish turning %.0f° at %.0f°/s within %.1f s (turned about %.0f° by its encoder); is it blocked?",
                            robot, t.port(), t.degrees(), Math.abs(t.degreesPerSecond()), deadline / 1e9, turned(p)));
                }
                return false;
            });
        }
        b.onEnd(interrupted -> {
            for (Port p : used) {
                stop(p, MotorState.StopMode.BRAKE);
            }
        });
        return b.build();
    }

    /** The container of an all-continuous command (a drive) on these motors, from its builder with name, motors, priority and watchdog set. */
    private Container continuousContainer(Container.Builder b, Port[] used, double[] speeds) {
        b.action(now -> setSpeeds(used, speeds));
        b.logic(NEVER);
        b.refreshes(CONTINUOUS);
        b.onEnd(interrupted -> {
            for (Port p : used) {
                stop(p, MotorState.StopMode.BRAKE);
            }
        });
        return b.build();
    }

    /** What a drive's action does: wants each motor turning at its speed, without end. */
    private void setSpeeds(Port[] used, double[] speeds) {
        for (int i = 0; i < used.length; i++) {
            Port p = used[i];
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
    public void submitDetached(MotorCommand command, io.robomw.platform.exec.ExecutionActionThread thread) {
        List<MotorTarget> targets = command.targets();
        for (MotorTarget t : targets) {
            if (!t.continuous()) {
                thread.submit(container(command));
                return;
            }
        }
        thread.refresh(driveSlot(command), speeds(command));
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
        final java.time.Duration watchdog;
        final RefreshSlot slot;

        DriveSlot(String name, Requirements required, CommandPriority priority, java.time.Duration watchdog) {
            this.name = name;
            this.required = required;
            this.priority = priority;
            this.watchdog = watchdog;
            this.slot = new RefreshSlot(name, required.set(), priority, CONTINUOUS, required.motors().length, this);
        }

        /** @return whether a command goes through this slot: the same motors in the same order, name, priority and watchdog */
        boolean fits(MotorCommand command) {
            List<MotorTarget> targets = command.targets();
            Port[] motors = required.motors();
            if (targets.size() != motors.length || command.priority() != priority || !command.name().equals(name)
                    || !command.watchdogTimeout().equals(watchdog)) {
                return false;
            }
            for (int i = 0; i < motors.length; i++) {
                if (!motors[i].name.equals(targets.get(i).port())) {
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
        Port[] used = new Port[targets.size()];
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
    private void stop(Port p, MotorState.StopMode mode) {
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
                    for (Port p : motors) {
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
        List<PendingStop> failed;
        synchronized (publishLock) {
            if (pendingStops.isEmpty()) {
                return;
            }
            failed = List.copyOf(pendingStops);
            pendingStops.clear();
        }
        for (PendingStop s : failed) {
            s.handed().completeExceptionally(why);
        }
    }

    /** Queues this cycle's stops behind the batch just published (or complete them, when it is already written). */
    private void queueStops() {
        List<CompletableFuture<Void>> done = null;
        synchronized (publishLock) {
            for (CompletableFuture<Void> handed : stopsThisCycle) {
                if (sentBatches >= publishedBatches) {
                    if (done == null) {
                        done = new ArrayList<>(stopsThisCycle.size());
                    }
                    done.add(handed);
                } else {
                    pendingStops.add(new PendingStop(publishedBatches, handed));
                }
            }
        }
        stopsThisCycle.clear();
        if (done != null) {
            done.forEach(f -> f.complete(null));
        }
    }

    /** The link side wrote every batch up to {@code batches}: completes the stops that waited for them. */
    private void written(long batches) {
        List<CompletableFuture<Void>> done = null;
        synchronized (publishLock) {
            sentBatches = Math.max(sentBatches, batches);
            for (java.util.Iterator<PendingStop> i = pendingStops.iterator(); i.hasNext(); ) {
                PendingStop s = i.next();
                if (s.batch() <= sentBatches) {
                    i.remove();
                    if (done == null) {
                        done = new ArrayList<>(2);
                    }
                    done.add(s.handed());
                }
            }
        }
        if (done != null) {
            done.forEach(f -> f.complete(null));
        }
    }

    private boolean reached(Port p, MotorTarget t, MotorState started, long elapsedNanos) {
        double speed = Math.abs(t.degreesPerSecond());
        if (t.degrees() == 0 || speed == 0) {
            return true;
        }
        if (p.stoppedAtLimit() == started) {
            return true;
        }
        if (stopsAtLimit()) {
            return false;
        }
        if (!hasEncoder(t.port())) {
            return elapsedNanos >= t.degrees() / speed * 1e9;
        }
        Start start = p.start();
        if (start == null || start.state() != started) {
            return false;
        }
        double lead = speed * cyclePeriodNanos / 2e9;
        return turned(p, start) >= t.degrees() - lead;
    }

    /** How far a rotation has turned by the time a command sent now reaches the brick. */
    private double turned(Port port, Start start) {
        double speed = actualDegreesPerSecond(start.state());
        double predicted = predictedDegrees(port, speed, start.sinceNanos());
        double resolution = encoderResolutionDegrees(port.name);
        if (resolution > 0 && start.sinceNanos() <= clock.nanoTime()) {
            // A coarse encoder (a reading is the nearest count): believe the motor's own speed since
            // it started, within the half count either side of the reading that the count allows.
            double byTime = start.degrees() + speed * (clock.nanoTime() + commandDelayNanos() - start.sinceNanos()) / 1e9;
            predicted = Math.max(predicted - resolution / 2, Math.min(predicted + resolution / 2, byTime));
        }
        return Math.abs(predicted - start.degrees());
    }

    private double turned(Port p) {
        Start start = p.start();
        return start == null ? 0 : turned(p, start);
    }

    /** How long a rotation may take before it counts as blocked: three times its time at speed, plus 2 s. */
    private static long deadlineNanos(MotorTarget t) {
        return Math.round(3 * t.degrees() / Math.abs(t.degreesPerSecond()) * 1e9) + 2_000_000_000L;
    }

    /**
     * Where the motor will be when a command sent now reaches the brick: the last reading moved on
     * by the speed for the reading's age (or since the motor started turning, if later) and the
     * command's delay (together at most three cycles and those delays, so a reading that stopped
     * coming is not extrapolated without end).
     * Feedback arrives a link delay late and a stop reaches the brick a command delay after it is
     * sent; stopping on the bare reading would overshoot by both.
     */
    private double predictedDegrees(Port port, double degreesPerSecond, long turningSince) {
        int version;
        double degrees;
        long at;
        do {
            version = port.readingBegin();
            degrees = port.readingDegrees;
            at = port.readingAtNanos;
        } while (!port.readingWhole(version) && spin());
        if (version == 0) {
            return 0.0; // no reading yet
        }
        long now = clock.nanoTime();
        if (turningSince > now) {
            return degrees;
        }
        long delay = commandDelayNanos();
        long from = Math.max(at, turningSince);
        long ahead = Math.min(Math.max(0, now - from) + delay, 3 * cyclePeriodNanos + 4 * linkDelayNanos() + delay);
        return degrees + degreesPerSecond * ahead / 1e9;
    }

    /** @return true, after a spin-wait hint (while a reading is being written) */
    private static boolean spin() {
        Thread.onSpinWait();
        return true;
    }

    /** @param always publish it even if it equals the wanted state (a new rotation, which the brick must start again) */
    private void setWanted(Port p, MotorState state, boolean always) {
        MotorState before = p.wanted;
        p.wanted = state;
        if (always || !state.equals(before)) {
            p.changed = state;
            anyChanged = true;
        }
    }

    /**
     * Publishes the states changed during this cycle for the link side, without saying which
     * cycle it is (a refusal of them then concerns every command: {@link #servedCycle()}).
     *
     * @return whether anything changed
     */
    public boolean flushOutputs() {
        return flushOutputs(Long.MAX_VALUE);
    }

    /**
     * Publishes the states changed during this cycle for the link side. Called by the action
     * thread at the end of each cycle.
     *
     * @param cycle the execution action thread's cycle that set them (the one now ending)
     * @return whether anything changed
     */
    public boolean flushOutputs(long cycle) {
        if (!anyChanged) {
            if (!stopsThisCycle.isEmpty()) {
                queueStops();
            }
            return false;
        }
        if (linkInline) {
            publishChanged(cycle);
        } else {
            synchronized (publishLock) {
                publishChanged(cycle);
            }
        }
        anyChanged = false;
        if (!stopsThisCycle.isEmpty()) {
            queueStops();
        }
        return true;
    }

    /** Moves this cycle's changed states to the published ones (under {@link #publishLock} unless the link side is inline). */
    private void publishChanged(long cycle) {
        publishedCycle = cycle;
        publishedBatches++;
        for (Port p : motors) {
            if (p.changed != null) {
                p.published = p.changed;
                p.changed = null;
            }
        }
        ANY_PUBLISHED.setRelease(this, true);
    }

    /**
     * Sets every motor to coast (its output idle, drawing no current) and publishes it: what a
     * robot leaves its motors in when it closes, as the bricks' own tools do on stop-and-disconnect.
     * Called by the closing thread once the execution action thread has stopped.
     */
    public void coastAll() {
        for (Port p : motors) {
            stop(p, MotorState.StopMode.COAST);
        }
        flushOutputs();
    }

    // ---- link side ----

    /**
     * Sends published states with {@link #runImpl}, then polls feedback. Called by the link
     * thread each cycle, or inline by a simulator.
     *
     * @throws IOException if the link failed; unsent states are kept and sent on the next call
     * @throws RuntimeException if the hardware refused them (a brick's error status); they are not sent again
     */
    public final void serviceLink() throws IOException {
        if ((boolean) ANY_PUBLISHED.getAcquire(this)) {
            if (linkInline) {
                takePublished();
            } else {
                synchronized (publishLock) {
                    takePublished();
                }
            }
        } else {
            for (Port p : motors) {
                p.draining = null; // nothing left from a service a driver's exception cut short
            }
        }
        if (stopsOnLinkSide()) {
            anticipateStops();
        }
        List<MotorState> batch = null;
        for (Port p : motors) {
            if (p.draining != null) {
                if (batch == null) {
                    batch = new ArrayList<>(motors.length);
                }
                batch.add(p.draining);
            }
        }
        if (batch != null) {
            // The states count as sent from here on, so that a driver that reads the brick in the
            // same exchange (a pipelined poll) reports on these states, not the ones before; a
            // rotation counts from where the motor will be when the brick takes it.
            for (Port p : motors) {
                MotorState s = p.draining;
                if (s == null) {
                    continue;
                }
                MotorState previous = p.sent();
                if (s.running()) {
                    Start was = p.start();
                    long since = was != null && was.state() == previous ? was.sinceNanos() : Long.MIN_VALUE;
                    double speed = previous == null ? 0 : actualDegreesPerSecond(previous);
                    p.start(new Start(s, predictedDegrees(p, speed, since), Long.MAX_VALUE));
                }
                p.sentBefore = previous;
                p.sent(s);
            }
            try {
                runImpl(batch);
                if (takenBatches > sentBatches) {
                    written(takenBatches);
                }
                long took = clock.nanoTime() - actedNanosAgo();
                for (Port p : motors) {
                    MotorState s = p.draining;
                    Start start = s == null ? null : p.start();
                    if (start != null && start.state() == s) {
                        p.start(new Start(s, start.degrees(), took));
                    }
                }
            } catch (IOException | RuntimeException e) {
                for (Port p : motors) {
                    if (p.draining != null) {
                        p.sent(p.sentBefore);
                    }
                }
                // A refusal (RuntimeException: the brick answered with an error status) is not sent
                // again: it would be refused again, every cycle; the commands that wanted it fail with
                // it, and so do the stops waiting for it to be written.
                if (e instanceof RuntimeException r) {
                    failPendingStops(r);
                } else {
                    synchronized (publishLock) {
                        for (Port p : motors) {
                            if (p.draining != null && p.published == null) {
                                p.published = p.draining;
                                ANY_PUBLISHED.setRelease(this, true);
                            }
                        }
                    }
                }
                throw e;
            } finally {
                for (Port p : motors) {
                    p.draining = null;
                    p.sentBefore = null;
                }
            }
        }
        pollFeedback();
    }

    /**
     * @return the execution action thread's cycle whose states the link side took last (link
     *         side): a refusal during a service concerns the commands admitted up to it, and those
     *         running when the service began; {@link Long#MAX_VALUE} when a flush did not say
     */
    public long servedCycle() {
        return servedCycle;
    }

    /** Takes every published state into the batch (under {@link #publishLock} unless the link side is inline). */
    private void takePublished() {
        servedCycle = publishedCycle;
        takenBatches = publishedBatches;
        for (Port p : motors) {
            p.draining = p.published;
            p.published = null;
        }
        ANY_PUBLISHED.setRelease(this, false);
    }

    /**
     * @return whether the link side stops limited rotations itself, just in time by its own
     *         prediction, rather than waiting for the execution action thread's decision (which a
     *         slow link carrying one exchange at a time can send an exchange late); default no
     */
    protected boolean stopsOnLinkSide() {
        return false;
    }

    /**
     * How long until the link side can next send a command after this service: a cycle, or the
     * exchange that the service itself runs if that takes longer. Drivers on slow links override it.
     *
     * @return nanoseconds
     */
    protected long nextSendNanos() {
        return cyclePeriodNanos;
    }

    /**
     * Adds a stop to the batch for every limited rotation that reaches its target, by prediction,
     * before the link side's next chance to send ({@link #nextSendNanos()}), and marks it stopped
     * at its limit. They go together, one batch, at the mean of the moments each should be sent (a
     * stop sent then reaches the brick as the motor reaches its target): a slow link could not send
     * a second batch in time, and two motors of one move or turn, started together at one speed,
     * should stop together. The link thread waits for that moment. Time here is the injected
     * clock's; the wait is a real one only on the wall clock.
     */
    private void anticipateStops() {
        long next = nextSendNanos();
        long[] due = null;
        for (Port p : motors) {
            MotorState s = p.sent();
            if (p.draining != null || s == null || !s.running() || Double.isInfinite(s.limitDegrees()) || !hasEncoder(p.name)) {
                continue;
            }
            Start start = p.start();
            if (start == null || start.state() != s) {
                continue;
            }
            double remaining = s.limitDegrees() - turned(p, start);
            double speed = Math.abs(actualDegreesPerSecond(s));
            long eta = speed == 0 ? Long.MAX_VALUE : (long) Math.max(0, remaining / speed * 1e9);
            if (eta < next) {
                if (due == null) {
                    due = new long[motors.length];
                    java.util.Arrays.fill(due, -1);
                }
                due[p.index] = eta;
            }
        }
        if (due == null) {
            return;
        }
        long wait = (long) java.util.Arrays.stream(due).filter(d -> d >= 0).average().orElse(0);
        if (wait > 0 && !linkInline) {
            // On a link thread of its own (which the action side unparks whenever it publishes):
            // wait out the time. Inline, on a simulation's cycling thread, time is the owner's to step.
            long until = clock.nanoTime() + wait;
            for (long left = wait; left > 0; left = until - clock.nanoTime()) {
                java.util.concurrent.locks.LockSupport.parkNanos(this, left);
            }
        }
        for (Port p : motors) {
            if (due[p.index] >= 0) {
                p.draining = MotorState.stopped(p.name, MotorState.StopMode.BRAKE);
                p.stoppedAtLimit(p.sent());
            }
        }
    }

    /**
     * @return the port's state
     * @throws IllegalArgumentException if this platform drives no motor on that port
     */
    private Port port(String port) {
        for (Port p : motors) {
            if (p.name.equals(port)) {
                return p;
            }
        }
        throw new IllegalArgumentException("robot '" + robot + "' has no motor on port " + port + "; its motor ports are " + ports);
    }

    /** @return the clock */
    protected Clock clock() {
        return clock;
    }

    private static final java.lang.invoke.VarHandle ANY_PUBLISHED;

    static {
        try {
            ANY_PUBLISHED = java.lang.invoke.MethodHandles.lookup().findVarHandle(GenericMotorPlatform.class, "anyPublished", boolean.class);
        } catch (ReflectiveOperationException e) {
            throw new ExceptionInInitializerError(e);
        }
    }
}
