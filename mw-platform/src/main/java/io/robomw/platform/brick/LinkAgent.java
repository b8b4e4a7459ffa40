package io.robomw.platform.brick;

import io.robomw.api.RobotException;
import io.robomw.api.RobotLinkException;
import io.robomw.api.spi.Cycling;
import io.robomw.api.spi.MotorCommand;
import io.robomw.api.spi.FailurePolicy;
import io.robomw.api.spi.IdleStrategy;
import io.robomw.api.spi.OwnerThread;
import io.robomw.api.spi.PlatformConfig;
import io.robomw.platform.ThrottledWarnings;
import io.robomw.platform.exec.Container;
import io.robomw.platform.exec.ExecutionActionThread;
import io.robomw.platform.link.LinkLostException;
import io.robomw.platform.motor.MotorPlatform;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.io.IOException;
import java.time.Duration;
import java.util.Optional;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicLong;
import java.util.concurrent.atomic.AtomicReference;

/**
 * The one owner of a brick's link, as Agrona's {@code Agent} owns its work and its
 * {@code AgentRunner} the thread: it takes the motor states each action cycle publishes and hands
 * them to the driver, polls the driver for feedback, keeps the link's one {@link LinkState}, and
 * reopens a lost link. Everything about the link that used to be kept in several layers is here:
 * <ul>
 *   <li><b>Hand-off.</b> At the end of every action cycle the motor platform publishes the states
 *   that changed ({@link MotorPlatform#flushOutputs(long)}); the agent takes them whole, one
 *   batch per cycle, and its driver writes them, then polls ({@link io.robomw.platform.motor.MotorLinkSide});
 *   a stop's future completes once the batch carrying it is written.</li>
 *   <li><b>Link state.</b> An exchange that fails (on any thread: a sensor read too) takes the link
 *   {@link LinkState#DOWN DOWN}: every command is stopped ({@link ExecutionActionThread#linkFailed}),
 *   new ones are refused, exchanges fail at once, and stops waiting to be written fail naming the
 *   robot. Every {@link BrickChannel#REOPEN_INTERVAL} the agent reopens the link
 *   ({@link LinkState#REOPENING REOPENING}) until it is {@link LinkState#UP UP} again. One log line
 *   per change.</li>
 *   <li><b>Failures.</b> What the driver throws besides an I/O failure is either the brick's
 *   refusal (a {@link RobotException}: the commands it concerns fail with it, one log line a second
 *   at most) or the driver's own failure, reported to the injected {@link FailurePolicy} and
 *   counted; the agent goes on. A failure it cannot survive ends its thread, never silently
 *   ({@link OwnerThread.Duty#onDeath}): every command is stopped, the last stop is handed to the
 *   link from the dying thread, and the platform is marked failed ({@link #failure()}).</li>
 * </ul>
 *
 * <h2>Threads</h2>
 * With {@link Cycling#OWN_THREADS} the agent runs on an {@link OwnerThread} of its own, named
 * {@code <robot>-link}, woken whenever the action thread publishes, and otherwise coming round once
 * a cycle while motors move (the driver's polls say so) and every {@link #IDLE_WAIT} while they do
 * not (keep-alives, the polls of motors at rest); the link is paced on the wall clock
 * ({@link BrickChannel#LINK_TIME}). With {@link Cycling#BY_OWNER} (a simulation, whose platform has
 * no I/O) it starts no thread: each round runs inline on the cycling thread, right after the
 * cycle's hand-off, so a simulated run stays repeatable.
 */
public final class LinkAgent implements AutoCloseable {

    private static final Logger LOG = LoggerFactory.getLogger(LinkAgent.class);

    /** How long an idle agent waits for the action thread before it comes round on its own. */
    public static final Duration IDLE_WAIT = Duration.ofMillis(100);

    private final PlatformConfig config;
    private final String robot;
    private final String role;
    private final ExecutionActionThread actionThread;
    private final MotorPlatform motors;
    private final BrickChannel channel;
    private final AutoCloseable link;
    private final FailurePolicy failures;
    private final ThrottledWarnings refusals;
    private final boolean inline;
    private final AtomicReference<LinkState> state = new AtomicReference<>(LinkState.UP);
    /**
     * Held while the link is found lost (the state going down and the action thread told to stop every command) and while
     * a command is handed over only if the link is up ({@link #submitWhileUp}, {@link #submitDetachedWhileUp}): a command either sees the link down, or is stopped
     * with the others; never admitted after the stop to wait for a link that is gone.
     */
    private final Object linkChange = new Object();
    private final AtomicLong driverErrors = new AtomicLong();
    /** When the link was last reopened, or found lost ({@link BrickChannel#LINK_TIME}). */
    private volatile long lastReopen;
    /** Why the agent's thread died, once it has. */
    private volatile RobotLinkException failure;
    private volatile OwnerThread runner;
    private volatile boolean closed;

    /**
     * Takes the channel over (its exchanges now ask this agent whether the link is up, and tell it
     * when they fail) and listens to the action thread's cycles. Call {@link #start()} next.
     *
     * @param config       the platform's configuration: robot, cycle period, who cycles, failure policy
     * @param actionThread the robot's execution action thread
     * @param motors       the motor platform whose states it hands to the driver
     * @param channel      the brick's channel, or {@code null} for a platform without I/O (a simulator's)
     * @param link         closed last, when the agent closes (a driver's goodbye, then the channel); or
     *                     {@code null} to close the channel
     */
    public LinkAgent(PlatformConfig config, ExecutionActionThread actionThread, MotorPlatform motors, BrickChannel channel,
                     AutoCloseable link) {
        this.config = config;
        this.robot = config.robotName();
        this.role = robot + "-link";
        this.actionThread = actionThread;
        this.motors = motors;
        this.channel = channel;
        this.link = link != null ? link : channel;
        this.failures = config.failures();
        this.refusals = new ThrottledWarnings(LOG, Duration.ofSeconds(1), config.clock());
        this.inline = config.cycling() == Cycling.BY_OWNER;
        if (inline) {
            motors.linkServicedInline();
        }
        if (channel != null) {
            channel.ownedBy(new ChannelOwner());
        }
        actionThread.addCycleListener(this::afterCycle);
    }

    /**
     * Starts the agent's thread, for {@link Cycling#OWN_THREADS}; with {@link Cycling#BY_OWNER} it
     * does nothing (the rounds run inline). Only once.
     *
     * @return this
     */
    public synchronized LinkAgent start() {
        if (!inline && runner == null) {
            runner = OwnerThread.start(role, Thread.NORM_PRIORITY, new Servicing(),
                    IdleStrategy.wakeable(BrickChannel.LINK_TIME, config.cyclePeriod(), IDLE_WAIT), failures);
        }
        return this;
    }

    /** @return the link's state */
    public LinkState state() {
        return state.get();
    }

    /**
     * Hands a command to the action thread only if the link is up, in one step with respect to the link being found lost on
     * another thread: either the loss comes first (nothing is handed over: the caller refuses the command) or the command is
     * stopped with every other one when the loss is reported. Without it, a command that saw the link up just before the loss
     * and was queued just after the stop would wait for the link to come back and run then, long after its caller was told
     * the link was down.
     *
     * @param command the command's container
     * @return its future, or {@code null} if the link was not up and nothing was handed over
     */
    public CompletableFuture<Void> submitWhileUp(Container command) {
        synchronized (linkChange) {
            return state.get() == LinkState.UP ? actionThread.submit(command) : null;
        }
    }

    /**
     * {@link MotorPlatform#submitDetached} a command nobody waits for, only if the link is up, in one step with respect to the
     * link being found lost (as {@link #submitWhileUp}): a drive refreshed as the link is lost is dropped with the others
     * instead of moving the motors when the link comes back. Allocates nothing (a drive at a program's rate comes here).
     *
     * @param command the command
     * @return whether it was handed over
     */
    public boolean submitDetachedWhileUp(MotorCommand command) {
        synchronized (linkChange) {
            if (state.get() != LinkState.UP) {
                return false;
            }
            motors.submitDetached(command, actionThread);
            return true;
        }
    }

    /** @return why the agent's thread died, if it did: the platform has failed */
    public Optional<RobotLinkException> failure() {
        return Optional.ofNullable(failure);
    }

    /** @return how many times the driver threw something other than an I/O failure (refusals included) */
    public long driverErrors() {
        return driverErrors.get();
    }

    /** @return the link, for messages */
    public String describe() {
        return channel != null ? channel.describe() : config.platformName();
    }

    /** The action thread's cycle ended: its changed states are published; the agent takes them now (inline) or is woken. */
    private void afterCycle() {
        // A listener runs before the cycle is counted: this is cycle cycles() + 1.
        boolean changed = motors.flushOutputs(actionThread.cycles() + 1);
        if (inline) {
            if (!closed) {
                round();
            }
        } else if (changed) {
            wake();
        }
    }

    private void wake() {
        OwnerThread r = runner;
        if (r != null) {
            r.wake();
        }
    }

    /**
     * One round: reopens a lost link when it is time, else hands the published states to the
     * driver and polls it.
     *
     * @return its work: 0 when it had nothing to do (the link is down)
     */
    private int round() {
        if (state.get() != LinkState.UP) {
            if (!reopenDue() || !state.compareAndSet(LinkState.DOWN, LinkState.REOPENING)) {
                return 0;
            }
            lastReopen = BrickChannel.LINK_TIME.nanoTime();
            LOG.debug("robot '{}': reopening {}", robot, describe());
            motors.linkSide().linkReopened();
            if (channel != null) {
                try {
                    channel.reopen();
                } catch (IOException e) {
                    lost(e);
                    return 0;
                }
                up();
            }
            // Without a channel, the service below is the trial: it brings the link up, or down again.
        }
        return service();
    }

    private boolean reopenDue() {
        return channel == null || BrickChannel.LINK_TIME.nanoTime() - lastReopen >= BrickChannel.REOPEN_INTERVAL.toNanos();
    }

    /** Hands the published states to the driver and polls it; one unit of work, every failure of which is handled here. */
    private int service() {
        // Containers admitted in cycles up to this one were running before the service began.
        long began = actionThread.cycles();
        int work;
        try {
            work = motors.linkSide().service();
        } catch (ChannelBusyException e) {
            // A sensor read held the channel too long: nothing is known to be wrong with the link.
            // The states taken were put back and go with the next service.
            LOG.debug("robot '{}': {}", robot, e.getMessage());
            return 1;
        } catch (IOException e) {
            lost(e);
            return 0;
        } catch (Throwable t) {
            refused(t, began);
            work = 1;
        }
        up();
        return work;
    }

    /**
     * The brick answered but refused (an error status), or the driver failed: the link is fine.
     * The commands running now fail with the brick's own words, at once: those whose states the
     * service took and those running when it began, not those admitted since (a poll refused just
     * before the brick recovered must not fail them). The log gets one line a second at most about
     * refusals (the stack trace at debug level); the driver's own failures go to the failure
     * policy. One the thread cannot survive ends it.
     */
    private void refused(Throwable t, long began) {
        if (!FailurePolicy.survivable(t)) {
            throw (VirtualMachineError) t;
        }
        driverErrors.incrementAndGet();
        actionThread.driverFailed(t instanceof RuntimeException r ? r : new RobotException("robot '" + robot + "': the driver failed: " + t, t),
                Math.max(began, motors.linkSide().servedCycle()));
        if (t instanceof RobotException) {
            refusals.warn("{}", t.getMessage());
            LOG.debug("robot '{}': the driver's refusal", robot, t);
        } else {
            failures.survived(role, t);
        }
    }

    /** The link works (again): one line if it was being reopened. */
    private void up() {
        if (state.get() == LinkState.REOPENING && state.compareAndSet(LinkState.REOPENING, LinkState.UP)) {
            LOG.info("robot '{}': link {} is up again", robot, describe());
        }
    }

    /**
     * An exchange failed (on any thread): the link is down. From up, every command is stopped and
     * the stops waiting to be written fail; from reopening, the attempt failed. Idempotent.
     */
    private void lost(IOException cause) {
        LinkState was;
        synchronized (linkChange) {
            do {
                was = state.get();
                if (was == LinkState.DOWN) {
                    return;
                }
            } while (!state.compareAndSet(was, LinkState.DOWN));
            lastReopen = BrickChannel.LINK_TIME.nanoTime();
            if (was == LinkState.UP) {
                // under the lock: a command handed over while up is either refused or among those this stops
                actionThread.linkFailed(describe(), cause);
            }
        }
        if (was == LinkState.UP) {
            LOG.warn("robot '{}': link {} is down: {}; its commands were stopped, and it is reopened every {} ms", robot, describe(),
                    cause.getMessage(), BrickChannel.REOPEN_INTERVAL.toMillis());
        } else {
            LOG.debug("robot '{}': reopening {} failed: {}", robot, describe(), cause.getMessage());
        }
        motors.failPendingStops(new RobotLinkException("robot '" + robot + "': its stop was not handed to the hardware: link "
                + describe() + " failed: " + cause.getMessage() + "; it goes out when the link returns", cause));
        wake();
    }

    /** What the channel asks and tells this agent. */
    private final class ChannelOwner implements BrickChannel.Owner {
        @Override
        public void ensureUp() throws IOException {
            if (state.get() != LinkState.UP) {
                throw new LinkLostException(describe(), "robot '" + robot + "': the link is down; it is reopened every "
                        + BrickChannel.REOPEN_INTERVAL.toMillis() + " ms");
            }
        }

        @Override
        public void lost(IOException cause) {
            LinkAgent.this.lost(cause);
        }
    }

    /** The agent's duty on its own thread. */
    private final class Servicing implements OwnerThread.Duty {
        @Override
        public int doWork() {
            return round();
        }

        @Override
        public void onDeath(Throwable t) {
            died(t);
        }
    }

    /**
     * The agent's thread cannot go on: stops every command, hands the stop to the link one last
     * time from here, and marks the platform failed. Runs on the dying thread; must not throw.
     */
    private void died(Throwable t) {
        driverErrors.incrementAndGet();
        failure = new RobotLinkException("robot '" + robot + "': its link thread died of " + t + "; every command was stopped", t);
        try {
            actionThread.linkFailed(describe(), t);
            // The last stop: a safety stop through the action thread, then handed to the link from here.
            actionThread.submit(motors.stopContainer()).get(10 * config.cyclePeriod().toNanos() + 1_000_000_000L, TimeUnit.NANOSECONDS);
        } catch (Throwable e) {
            // the action thread is gone too, or the stop timed out: hand over what it published
        }
        try {
            motors.flushOutputs();
            motors.linkSide().service();
        } catch (Throwable e) {
            LOG.error("robot '{}': the last stop could not be handed to the link: {}", robot, e.toString());
        }
        motors.failPendingStops(failure);
    }

    /**
     * Stops the agent's thread, then, on the closing thread (the action thread has ended: its
     * containers were stopped and their brakes published), hands the last states to the link,
     * leaves every output idle (coasting, as the bricks' own tools do when a program stops) and
     * closes the link. Idempotent.
     */
    @Override
    public void close() {
        if (closed) {
            return;
        }
        closed = true;
        OwnerThread r = runner;
        if (r != null) {
            r.close();
        }
        motors.flushOutputs();
        if (state.get() == LinkState.UP && failure == null) {
            service();
        }
        motors.coastAll();
        if (state.get() == LinkState.UP && failure == null) {
            service();
        }
        motors.failPendingStops(new RobotLinkException("robot '" + robot + "': it was closed before its stop was handed to the hardware", null));
        if (link != null) {
            try {
                link.close();
            } catch (Exception e) {
                LOG.warn("robot '{}': closing its link: {}", robot, e.toString());
            }
        }
    }
}
