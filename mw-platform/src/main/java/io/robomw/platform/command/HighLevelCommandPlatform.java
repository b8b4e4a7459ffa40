package io.robomw.platform.command;

import io.robomw.api.Clock;
import io.robomw.api.RobotException;
import io.robomw.api.RobotLinkException;
import io.robomw.api.spi.CommandPriority;
import io.robomw.api.spi.HighLevelCommand;
import io.robomw.platform.exec.Container;

import java.util.HashMap;
import java.util.Locale;
import java.util.Map;
import java.util.Set;
import java.util.TreeSet;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.ConcurrentHashMap;
import java.util.concurrent.atomic.AtomicLong;

/**
 * The motor platform's counterpart for robots that move by their firmware's own commands: turns
 * {@link HighLevelCommand}s into containers for the execution action thread, so they follow its
 * rules (clash: the newest command on an actuator group wins; priorities: a safety stop is never
 * pre-empted; watchdog: a continuous command that is not refreshed ends), and hands them to the
 * driver. A platform writer subclasses it and implements {@link #start}, {@link #refresh} and
 * {@link #stop} (encode the firmware's command and queue it for the link), and reports from the
 * link side with {@link #finished} and {@link #failed}.
 *
 * <h2>One command's life</h2>
 * <ol>
 *   <li>Its container is admitted: {@link #start} sends it (a {@link Run} stands for it).</li>
 *   <li>Each cycle its logic checks the run: done when the driver reported it {@link #finished};
 *   a {@link RobotException} naming the command when the driver reported it {@link #failed}, or
 *   when it runs past {@code 3 × expected duration + 2 s} (the robot stopped answering with
 *   progress).</li>
 *   <li>A continuous command repeated with the same name and actuators refreshes the running one:
 *   {@link #refresh} sends the new values, and its watchdog restarts.</li>
 *   <li>When it ends any other way than finishing (interrupted by a newer command or a stop, failed,
 *   its watchdog expired, the link failed), {@link #stop} ends it on the robot and sends its
 *   {@link HighLevelCommand#stopText()}.</li>
 * </ol>
 *
 * <h2>Threads</h2>
 * {@link #container} and {@link #stopContainer} are called on any thread and build containers;
 * {@link #start}, {@link #refresh} and {@link #stop} run on the execution action thread and must
 * not block (queue the bytes for the link); {@link #finished} and {@link #failed} may be called from
 * any thread (the link's reader). A run's state crosses threads through volatile fields.
 */
public abstract class HighLevelCommandPlatform {

    /** The actuator group a stop always covers, even before any command named it. */
    public static final String LEGS = "legs";

    private final String robot;
    private final Clock clock;
    private final AtomicLong ids = new AtomicLong();
    private final Set<String> groups = ConcurrentHashMap.newKeySet();
    // Touched only by the execution action thread:
    private final Map<String, Run> running = new HashMap<>();

    /**
     * @param robot the robot's name, for messages
     * @param clock the clock the action thread runs on
     */
    protected HighLevelCommandPlatform(String robot, Clock clock) {
        this.robot = robot;
        this.clock = clock;
        groups.add(LEGS);
    }

    /** What a run is doing. */
    public enum State {
        /** Built, not yet sent. */
        WAITING,
        /** Sent; the robot is doing it. */
        RUNNING,
        /** The robot reported it done. */
        FINISHED,
        /** The robot reported an error for it. */
        FAILED,
        /** It ended without finishing (interrupted, stopped, failed); nothing more will come of it. */
        ENDED
    }

    /**
     * One high-level command as the platform runs it. A continuous command keeps its run across
     * refreshes; {@link #command()} is then the latest one.
     */
    public static final class Run {
        private final long id;
        private volatile HighLevelCommand command;
        private volatile State state = State.WAITING;
        private volatile String failure;
        private volatile long startedAt;

        private Run(long id, HighLevelCommand command) {
            this.id = id;
            this.command = command;
        }

        /** @return a number unique within the platform, for the driver's tags */
        public long id() {
            return id;
        }

        /** @return the command (for a refreshed continuous command, the latest) */
        public HighLevelCommand command() {
            return command;
        }

        /** @return what it is doing */
        public State state() {
            return state;
        }

        @Override
        public String toString() {
            return "Run[" + id + " " + command.name() + " " + state + "]";
        }
    }

    /** @return the robot's name */
    public String robot() {
        return robot;
    }

    /** @return the clock */
    protected Clock clock() {
        return clock;
    }

    /**
     * Sends a command to the robot. Called on the execution action thread when its container
     * starts; must not block. Report its end with {@link #finished} or {@link #failed}.
     *
     * @param run the run
     */
    protected abstract void start(Run run);

    /**
     * Sends the newer values of a running continuous command ({@link Run#command()} is already
     * the newer command). Called on the execution action thread; must not block.
     *
     * @param run the run
     */
    protected abstract void refresh(Run run);

    /**
     * Ends a command on the robot that ended here without finishing, and sends its
     * {@link HighLevelCommand#stopText()}. Called on the execution action thread; must not block.
     *
     * @param run the run
     */
    protected abstract void stop(Run run);

    /**
     * The robot reported the command done. Any thread.
     *
     * @param run the run
     */
    protected final void finished(Run run) {
        if (run.state == State.RUNNING) {
            run.state = State.FINISHED;
        }
    }

    /**
     * The robot reported an error for the command. Any thread.
     *
     * @param run     the run
     * @param message what the robot said, for the caller's exception
     */
    protected final void failed(Run run, String message) {
        if (run.state == State.RUNNING || run.state == State.WAITING) {
            run.failure = message;
            run.state = State.FAILED;
        }
    }

    /**
     * Builds the container of a high-level command.
     *
     * @param command the command
     * @return its container
     */
    public Container container(HighLevelCommand command) {
        groups.addAll(command.actuators());
        Run mine = new Run(ids.incrementAndGet(), command);
        Container.Builder b = Container.builder(command.name())
                .requires(command.actuators())
                .priority(command.priority())
                .watchdog(command.continuous() ? command.watchdogTimeout() : java.time.Duration.ZERO);
        b.action(now -> {
            Run holder = running.get(command.actuators().iterator().next());
            if (command.continuous() && holder != null && holder != mine && holder.command.continuous()
                    && holder.command.name().equals(command.name())) {
                holder.command = command;
                refresh(holder);
                return;
            }
            mine.startedAt = now;
            mine.state = State.RUNNING;
            for (String a : command.actuators()) {
                running.put(a, mine);
            }
            start(mine);
        });
        long deadline = command.continuous() ? Long.MAX_VALUE
                : Math.round(3 * command.expectedDuration().toNanos() + 2e9);
        b.logic(now -> {
            State s = mine.state;
            if (s == State.FINISHED) {
                if (command.continuous()) {
                    throw new RobotException("robot '" + robot + "': the robot ended continuous command '" + command.name()
                            + "' by itself (its own watchdog, or another client); send it again to go on");
                }
                return true;
            }
            if (s == State.FAILED) {
                throw new RobotException("robot '" + robot + "': command '" + command.name() + "' (" + mine.command.text() + ") failed: " + mine.failure);
            }
            if (now - mine.startedAt > deadline) {
                throw new RobotException(String.format(Locale.ROOT,
                        "robot '%s': command '%s' (%s) did not finish within %.1f s (expected %.1f s); the robot stopped reporting progress",
                        robot, command.name(), command.text(), deadline / 1e9, command.expectedDuration().toNanos() / 1e9));
            }
            return false;
        });
        if (command.continuous()) {
            b.refreshes("high-level:" + command.name());
        }
        b.onEnd(interrupted -> {
            for (String a : command.actuators()) {
                running.remove(a, mine);
            }
            State s = mine.state;
            mine.state = s == State.FINISHED ? State.FINISHED : State.ENDED;
            if (s == State.RUNNING || s == State.FAILED) {
                stop(mine);
            }
        });
        return b.build();
    }

    /**
     * @return a safety-priority container that requires every actuator group any command has
     *         named (and {@value #LEGS}), so every running command ends with its stop, and holds
     *         them for one cycle so that no normal command queued in the same cycle starts again
     */
    public Container stopContainer() {
        return stopContainer(new CompletableFuture<>());
    }

    /**
     * {@link #stopContainer()}, telling when the stops are on the wire.
     *
     * @param handed completed once everything the driver sent up to the stop (the stops of the
     *               commands it ended) has been written to the link ({@link #sentSoFar}); failed
     *               with a {@link RobotLinkException} naming the robot if it could not be
     * @return the container
     */
    public Container stopContainer(CompletableFuture<Void> handed) {
        return Container.builder("stop")
                .requires(new TreeSet<>(groups))
                .priority(CommandPriority.SAFETY)
                // After the holders' end actions sent their stops (they end before a newcomer starts).
                .action(now -> sentSoFar().whenComplete((v, e) -> {
                    if (e == null) {
                        handed.complete(null);
                    } else {
                        handed.completeExceptionally(new RobotLinkException("robot '" + robot + "': its stop could not be written to the link: "
                                + e.getMessage(), e));
                    }
                }))
                .logic(now -> true)
                .build();
    }

    /**
     * What a stop waits for: completes once everything {@link #start}, {@link #refresh} and
     * {@link #stop} sent so far has been written to the link; fails if the link is down or is lost
     * first. The default (a platform without a link of its own, such as a simulator's, whose
     * commands act within the cycle) is done at once. Called on the execution action thread.
     *
     * @return the future
     */
    protected CompletableFuture<Void> sentSoFar() {
        return CompletableFuture.completedFuture(null);
    }
}
