package io.robomw.platform.motor;

import io.robomw.api.Clock;
import io.robomw.api.RobotException;
import io.robomw.api.spi.CommandPriority;
import io.robomw.api.spi.MotorCommand;
import io.robomw.api.spi.MotorTarget;
import io.robomw.platform.exec.Container;

import java.io.IOException;
import java.util.ArrayList;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Map;
import java.util.Set;
import java.util.concurrent.ConcurrentHashMap;

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
 * Encoder readings and published states cross between the sides through concurrent maps.
 *
 * <p>A command whose targets are all continuous ({@code drive}) refreshes a running continuous
 * command on the same motors in place, so a program repeating it at 10 Hz costs one container,
 * not ten a second.
 *
 * <h2>Reaching a target</h2>
 * A logic object per motor watches its rotation since the container started, and stops the motor
 * when the rotation is within half a cycle's travel of the target. The last encoder reading is
 * extrapolated by the commanded speed over its age, so a link's feedback delay does not become
 * overshoot. A motor without encoder is
 * stopped by time: {@code degrees / speed} after the start.
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
    private final List<String> portOrder;
    private final Map<String, MotorState> wanted = new LinkedHashMap<>();
    private final Map<String, MotorState> published = new ConcurrentHashMap<>();
    private final Map<String, MotorState> changed = new LinkedHashMap<>();
    private final Map<String, Reading> degrees = new ConcurrentHashMap<>();
    private final Map<String, Double> startDegrees = new LinkedHashMap<>();
    private final Map<String, MotorState> sentStates = new ConcurrentHashMap<>();
    private final Map<String, MotorState> stoppedAtLimit = new ConcurrentHashMap<>();
    private volatile long cyclePeriodNanos = 10_000_000L;

    /**
     * @param robot the robot's name, for messages
     * @param clock the clock the action thread runs on
     * @param ports every motor port this platform drives
     */
    protected GenericMotorPlatform(String robot, Clock clock, List<String> ports) {
        this.robot = robot;
        this.clock = clock;
        this.ports = Set.copyOf(ports);
        this.portOrder = List.copyOf(ports);
        for (String port : ports) {
            wanted.put(port, MotorState.stopped(port, MotorState.StopMode.BRAKE));
        }
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
        MotorState last = sentStates.get(port);
        if (last != null && last.running() && !Double.isInfinite(last.limitDegrees())) {
            stoppedAtLimit.put(port, last);
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
        degrees.put(port, new Reading(reading, clock.nanoTime()));
    }

    /** An encoder reading and the clock time it was reported at. */
    private record Reading(double degrees, long atNanos) {
    }

    /**
     * @param port a motor port
     * @return the last encoder reading, degrees
     */
    public double motorDegrees(String port) {
        requirePort(port);
        Reading r = degrees.get(port);
        return r == null ? 0.0 : r.degrees();
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
        List<String> names = new ArrayList<>();
        for (MotorTarget t : targets) {
            requirePort(t.port());
            names.add(t.port());
        }
        Container.Builder b = Container.builder(command.name())
                .requires(names)
                .priority(command.priority())
                .watchdog(command.watchdogTimeout());
        long[] startedAt = new long[1];
        MotorState[] started = new MotorState[targets.size()];
        b.action(now -> {
            startedAt[0] = now;
            for (int i = 0; i < targets.size(); i++) {
                MotorTarget t = targets.get(i);
                startDegrees.put(t.port(), motorDegrees(t.port()));
                started[i] = new MotorState(t.port(), t.degrees() == 0 ? 0 : t.degreesPerSecond(), t.degrees(), MotorState.StopMode.BRAKE);
                setWanted(started[i], !t.continuous());
            }
        });
        for (int i = 0; i < targets.size(); i++) {
            MotorTarget t = targets.get(i);
            if (t.continuous()) {
                continue;
            }
            int index = i;
            b.logic(now -> {
                if (reached(t, started[index], now - startedAt[0])) {
                    setWanted(MotorState.stopped(t.port(), MotorState.StopMode.BRAKE), false);
                    return true;
                }
                long deadline = deadlineNanos(t);
                if (now - startedAt[0] > deadline) {
                    throw new RobotException(String.format(java.util.Locale.ROOT,
                            "robot '%s': motor %s did not finish turning %.0f° at %.0f°/s within %.1f s (turned about %.0f° by its encoder); is it blocked?",
                            robot, t.port(), t.degrees(), Math.abs(t.degreesPerSecond()), deadline / 1e9, turned(t)));
                }
                return false;
            });
        }
        if (targets.stream().allMatch(MotorTarget::continuous)) {
            b.logic(now -> false);
            b.refreshes("continuous");
        }
        b.onEnd(interrupted -> {
            for (MotorTarget t : targets) {
                setWanted(MotorState.stopped(t.port(), MotorState.StopMode.BRAKE), false);
            }
        });
        return b.build();
    }

    /**
     * @return a safety-priority container that stops every motor at once and holds them for one
     *         cycle, so that no normal command queued in the same cycle can restart them
     */
    public Container stopContainer() {
        return Container.builder("stop")
                .requires(ports)
                .priority(CommandPriority.SAFETY)
                .action(now -> ports.forEach(p -> setWanted(MotorState.stopped(p, MotorState.StopMode.BRAKE), false)))
                .logic(now -> true)
                .build();
    }

    private boolean reached(MotorTarget t, MotorState started, long elapsedNanos) {
        double speed = Math.abs(t.degreesPerSecond());
        if (t.degrees() == 0 || speed == 0) {
            return true;
        }
        if (stopsAtLimit()) {
            return stoppedAtLimit.get(t.port()) == started;
        }
        if (!hasEncoder(t.port())) {
            return elapsedNanos >= t.degrees() / speed * 1e9;
        }
        double lead = speed * cyclePeriodNanos / 2e9;
        return turned(t) >= t.degrees() - lead;
    }

    private double turned(MotorTarget t) {
        return Math.abs(estimatedDegrees(t) - startDegrees.getOrDefault(t.port(), 0.0));
    }

    /** How long a rotation may take before it counts as blocked: three times its time at speed, plus 2 s. */
    private static long deadlineNanos(MotorTarget t) {
        return Math.round(3 * t.degrees() / Math.abs(t.degreesPerSecond()) * 1e9) + 2_000_000_000L;
    }

    /**
     * The encoder reading moved on by the commanded speed for the reading's age (at most three
     * cycles): feedback arrives at least one link round trip late, and stopping on stale readings
     * would overshoot by that much.
     */
    private double estimatedDegrees(MotorTarget t) {
        Reading r = degrees.get(t.port());
        if (r == null) {
            return 0.0;
        }
        long age = Math.min(Math.max(0, clock.nanoTime() - r.atNanos()), 3 * cyclePeriodNanos);
        return r.degrees() + t.degreesPerSecond() * age / 1e9;
    }

    /** @param always publish it even if it equals the wanted state (a new rotation, which the brick must start again) */
    private void setWanted(MotorState state, boolean always) {
        MotorState before = wanted.put(state.port(), state);
        if (always || !state.equals(before)) {
            changed.put(state.port(), state);
        }
    }

    /**
     * Publishes the states changed during this cycle for the link side. Called by the action
     * thread at the end of each cycle.
     *
     * @return whether anything changed
     */
    public boolean flushOutputs() {
        if (changed.isEmpty()) {
            return false;
        }
        published.putAll(changed);
        changed.clear();
        return true;
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
        if (!published.isEmpty()) {
            List<MotorState> batch = new ArrayList<>();
            for (String port : portOrder) {
                MotorState s = published.remove(port);
                if (s != null) {
                    batch.add(s);
                }
            }
            try {
                runImpl(batch);
                for (MotorState s : batch) {
                    sentStates.put(s.port(), s);
                }
            } catch (IOException e) {
                for (MotorState s : batch) {
                    published.putIfAbsent(s.port(), s);
                }
                throw e;
            }
            // A refusal (RuntimeException: the brick answered with an error status) is not sent
            // again: it would be refused again, every cycle; the commands that wanted it fail with it.
        }
        pollFeedback();
    }

    private void requirePort(String port) {
        if (!ports.contains(port)) {
            throw new IllegalArgumentException("robot '" + robot + "' has no motor on port " + port + "; its motor ports are " + ports);
        }
    }

    /** @return the clock */
    protected Clock clock() {
        return clock;
    }
}
