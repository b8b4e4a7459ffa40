package io.robomw.platform.exec;

import io.robomw.api.Clock;
import io.robomw.api.CommandPreemptedException;
import io.robomw.api.RobotException;
import io.robomw.api.RobotLinkException;
import io.robomw.api.spi.CommandPriority;
import io.robomw.api.spi.FailurePolicy;
import io.robomw.api.spi.IdleStrategy;
import io.robomw.api.spi.OwnerThread;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.time.Duration;
import java.util.ArrayDeque;
import java.util.ArrayList;
import java.util.LinkedHashSet;
import java.util.List;
import java.util.Set;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.CopyOnWriteArrayList;
import java.util.concurrent.atomic.AtomicLong;
import java.util.function.Function;

/**
 * The paper's execution action thread: a real-time repository of containers, cycled at a fixed
 * rate. It knows which actuators are in motion, and which container holds each one.
 *
 * <h2>Rules</h2>
 * <ul>
 *   <li><b>Clash:</b> a container that needs an actuator another holds interrupts it (the most
 *   recent wins) and the interrupted caller gets {@link CommandPreemptedException}; unless the
 *   holder has a higher {@link CommandPriority}, or the same priority and
 *   {@link InterruptionBehavior#CANCEL_INCOMING}, in which case the newcomer is refused.</li>
 *   <li><b>Refresh:</b> a continuous container built with the same
 *   {@link Container.Builder#refreshes refresh key}, actuators and priority as the one holding its
 *   actuators does not interrupt it: it refreshes it in place (its actions set the new speeds, the
 *   watchdog restarts) and its own future completes at once. A {@link RefreshSlot} does the same
 *   without a container per refresh ({@link #refresh}): its values wait in the queue in their
 *   place among the containers, and refresh the running container or become a new one by these
 *   rules.</li>
 *   <li><b>Watchdog:</b> a container with a watchdog timeout ends when it has run that long
 *   without being refreshed or replaced.</li>
 *   <li><b>Cancel:</b> a container whose caller cancels its future (an interrupted or timed-out
 *   wait) ends at the next cycle as interrupted, so its end action stops its motors; one cancelled
 *   before it started never runs.</li>
 *   <li><b>Link failure:</b> after {@link #linkFailed}, every container ends with
 *   {@link RobotLinkException} and runs its end action (stopping its motors).</li>
 * </ul>
 *
 * <h2>Threads</h2>
 * {@link #submit}, {@link #refresh}, {@link #linkFailed} and {@link #driverFailed} may be called
 * from any thread, and wake the cycling thread. Everything else happens in {@link #cycle()}, called
 * either by the {@link OwnerThread} {@link #start()} starts (named {@code <robot>-action}, for a
 * platform that runs its own threads: {@link io.robomw.api.spi.Cycling#OWN_THREADS}) or by the
 * platform's owner (a simulation stepping its world), never by both. The thread's idle strategy
 * is fed by each cycle's work: while containers run it cycles at the period; a robot with nothing
 * to do sleeps until something is submitted (it does not wake a hundred times a second for
 * nothing). Action objects, logic objects, end actions and cycle listeners all run on the cycling
 * thread, one at a time; they must not block.
 *
 * <h2>Failures</h2>
 * What one unit of work throws (a container's action, logic or end action, a refresh, a cycle
 * listener) goes to the injected {@link FailurePolicy}: one it can survive (an exception, or an
 * error a driver or an agent's code can cause: a {@link LinkageError}, an {@link AssertionError},
 * a {@link StackOverflowError}) is reported and counted, ends its container with it, and the loop
 * goes on.
 *
 * <h2>When the thread itself dies</h2>
 * Any other {@link Throwable} (an {@link OutOfMemoryError}, an internal error of the VM) ends the
 * thread, never silently, as Agrona's {@code AgentRunner} ends an agent, but for motors
 * ({@link OwnerThread.Duty#onDeath}): every container ends with a {@link RobotException} naming it
 * and runs its end action, and the cycle listeners run once more, so the motor platform hands the
 * last stop to its link before the thread exits; the failure listeners are told; the policy hears
 * of the death; and the thread is marked failed: later commands fail at once with an error that
 * says so ({@link #failure()}). {@link #close()} waits until the thread has really ended.
 */
public final class ExecutionActionThread implements AutoCloseable {

    private static final Logger LOG = LoggerFactory.getLogger(ExecutionActionThread.class);

    /** How long the cycling thread sleeps, at most, while it has nothing to do and nobody wakes it. */
    static final Duration IDLE_WAIT = Duration.ofSeconds(1);

    private final String robot;
    /** The cycling thread's name, under which failures are reported. */
    private final String role;
    private final Clock clock;
    private final long periodNanos;
    private final FailurePolicy failures;
    // The queue, guarded by this object's own monitor (no lock object of its own: one object less
    // for each cycle to bring into the cache): the containers submitted and not yet admitted, in the
    // order of their tickets, the refresh slots and their places, and the ticket counter.
    private final ArrayDeque<Container> incoming = new ArrayDeque<>();
    /** How many containers {@link #incoming} holds (a robot that only drives never looks at it). */
    private int queuedContainers;
    /** Every slot refreshed through this thread (replaced as a whole when one is added or forgotten). */
    private RefreshSlot[] slots = new RefreshSlot[0];
    /** The ticket of the last container or slot queued (each gets the next). */
    private long lastTicket;
    /**
     * Whether anything may be queued, read without the lock by each cycle first (a primitive:
     * neither a cycle nor a refresh stores a reference into this long-lived object).
     */
    private volatile boolean anyIncoming;
    // Fields rather than atomic objects, read by every cycle: one object less each to bring into
    // the cache for each of the thousands of robots a simulation cycles in one pass.
    /** Set by {@link #linkFailed} (any thread), taken by the next cycle. */
    private volatile LinkFailure linkFailure;
    /** Set by {@link #driverFailed} (any thread), taken by the next cycle. */
    private volatile Refusal driverFailure;
    /** The cycle listeners, replaced as a whole when one is added. */
    private volatile Runnable[] cycleListeners = new Runnable[0];
    private final List<java.util.function.Consumer<RobotException>> failureListeners = new CopyOnWriteArrayList<>();
    /** Why the cycling thread died, once it has. */
    private volatile RobotException failure;
    /** The thread {@link #start} started, or {@code null} while its owner cycles it. */
    private volatile OwnerThread runner;
    /** Written only by the cycling thread (one at a time), with release semantics. */
    private volatile long cycles;
    private final AtomicLong overruns = new AtomicLong();
    private final AtomicLong errors = new AtomicLong();
    private volatile boolean closed;
    private volatile Set<String> inUse = Set.of();

    // Touched only by the cycling thread:
    private final Holders holders = new Holders();
    private final List<Container> active = new ArrayList<>();
    private final List<Container> scratch = new ArrayList<>();
    private boolean holdersChanged;
    /** The slowest step of the cycle under way, when it is timed: whose, what kind, how long. */
    private String slowestStep;
    private String slowestKind;
    private long slowestNanos;

    /**
     * @param robot    the robot's name, for the thread's name and messages
     * @param clock    the clock cycles are timed with
     * @param period   the cycle period (10 ms for the default 100 Hz)
     * @param failures where what the cycles catch is reported ({@link io.robomw.api.spi.PlatformConfig#failures()})
     */
    public ExecutionActionThread(String robot, Clock clock, Duration period, FailurePolicy failures) {
        if (period.isZero() || period.isNegative()) {
            throw new IllegalArgumentException("cycle period must be > 0, got " + period);
        }
        this.robot = robot;
        this.role = robot + "-action";
        this.clock = clock;
        this.periodNanos = period.toNanos();
        this.failures = java.util.Objects.requireNonNull(failures, "failures");
    }

    /**
     * An execution action thread that reports what it catches to a {@link FailurePolicy#logging()
     * logging policy} of its own (tests; a platform passes its configuration's policy).
     *
     * @param robot  the robot's name, for the thread's name and messages
     * @param clock  the clock cycles are timed with
     * @param period the cycle period (10 ms for the default 100 Hz)
     */
    public ExecutionActionThread(String robot, Clock clock, Duration period) {
        this(robot, clock, period, FailurePolicy.logging());
    }

    /** @return the cycle period */
    public Duration period() {
        return Duration.ofNanos(periodNanos);
    }

    /** @return the clock */
    public Clock clock() {
        return clock;
    }

    /**
     * Queues a container; it starts at the next cycle, subject to the clash rules.
     *
     * @param container the container
     * @return its completion future; cancelling it ends the container at the next cycle as
     *         interrupted (its end action stops its motors), or drops it if it has not started
     */
    public CompletableFuture<Void> submit(Container container) {
        RobotException failed = failure;
        if (failed != null) {
            container.completion().completeExceptionally(new RobotException("robot '" + robot + "' has failed: " + failed.getMessage()
                    + "; command '" + container.name() + "' was not run (close the robot and open it again)", failed));
            return container.completion();
        }
        if (closed) {
            container.completion().completeExceptionally(new RobotException("robot '" + robot + "' is closed; command '" + container.name() + "' was not run"));
            return container.completion();
        }
        synchronized (this) {
            container.ticket = ++lastTicket;
            incoming.add(container);
            queuedContainers++;
            anyIncoming = true;
        }
        wake();
        return container.completion();
    }

    /**
     * Queues a platform's safety stop ({@code RobotPlatform.stopAll()}'s container) and tells its
     * caller when it is over on both sides: the platform has handed it to the hardware
     * ({@code handed}, which its action completes, maybe at once, while the cycle that admits it
     * still admits what else is queued) <em>and</em> it no longer holds the actuators. A command
     * submitted once the returned future completes is admitted as usual, never refused by the
     * stop (a caller that waits for the stop and moves again at once would otherwise race the
     * cycle that admitted the stop).
     *
     * @param stop    the stop's container
     * @param handed  completed by the platform once the stop is on the wire, or failed with a
     *                {@link RobotLinkException} naming the robot
     * @param refused what {@code handed} fails with when this thread refused the container (failed
     *                or closed), given why; a stop pre-empted by a newer stop is not refused: the
     *                newer one goes on
     * @return completes once {@code handed} did and the stop ended; fails as soon as {@code handed} fails
     */
    public CompletableFuture<Void> submitStop(Container stop, CompletableFuture<Void> handed,
                                              Function<Throwable, RobotLinkException> refused) {
        CompletableFuture<Void> ended = submit(stop);
        ended.whenComplete((v, e) -> {
            if (e != null && !(e instanceof CommandPreemptedException)) {
                handed.completeExceptionally(refused.apply(e));
            }
        });
        CompletableFuture<Void> over = new CompletableFuture<>();
        handed.whenComplete((v, e) -> {
            if (e != null) {
                over.completeExceptionally(e);
            } else {
                ended.whenComplete((v2, e2) -> over.complete(null));
            }
        });
        return over;
    }

    /** Wakes the cycling thread from an idle wait, if it has one: there is work. */
    private void wake() {
        OwnerThread r = runner;
        if (r != null) {
            r.wake();
        }
    }

    /**
     * Refreshes a continuous command through its slot (see {@link RefreshSlot}): at the next cycle,
     * in its place among the commands submitted before and after, the values refresh the running
     * container the slot matches, or start a new one by the clash rules. Nobody waits for it: if the
     * thread has failed or is closed, the values are dropped, as a detached container's failed
     * future would be.
     *
     * @param slot   the slot (it belongs to this thread from its first refresh on)
     * @param values its new values, copied ({@link RefreshSlot#size()} of them)
     * @throws IllegalArgumentException if the slot belongs to another thread or the values do not fit it
     */
    public void refresh(RefreshSlot slot, double[] values) {
        if (values.length != slot.size()) {
            throw new IllegalArgumentException("refresh slot '" + slot.name() + "' takes " + slot.size() + " values, got " + values.length);
        }
        refresh(slot, values, 0, 0);
    }

    /**
     * The same for a slot of two values (a drive's two wheels), without an array a refresh.
     *
     * @param slot   the slot (it belongs to this thread from its first refresh on)
     * @param first  its first value
     * @param second its second value
     * @throws IllegalArgumentException if the slot belongs to another thread or does not take two values
     */
    public void refresh(RefreshSlot slot, double first, double second) {
        if (slot.size() != 2) {
            throw new IllegalArgumentException("refresh slot '" + slot.name() + "' takes " + slot.size() + " values, got 2");
        }
        refresh(slot, null, first, second);
    }

    /** Refreshes with {@code values}, or if that is {@code null} the two values {@code first} and {@code second}. */
    private void refresh(RefreshSlot slot, double[] values, double first, double second) {
        if (failure != null || closed) {
            LOG.debug("robot '{}': '{}' was not run: the robot {}", robot, slot.name(), closed ? "is closed" : "has failed");
            return;
        }
        Container separately = null;
        synchronized (this) {
            if (slot.owner != this) {
                if (slot.owner != null) {
                    throw new IllegalArgumentException("refresh slot '" + slot.name() + "' belongs to another robot's execution action thread");
                }
                adopt(slot);
            }
            if (!slot.queued) {
                slot.ticket = ++lastTicket;
                slot.queued = true;
                put(slot, values, first, second);
                anyIncoming = true;
                wake();
            } else if (slot.ticket == lastTicket) {
                put(slot, values, first, second); // the newest refresh replaces the one queued just before it
            } else {
                // Something was submitted after its queued values: these go behind that, on their own.
                separately = slot.handler().container(values == null ? new double[] {first, second} : values.clone());
            }
        }
        if (separately != null) {
            submit(separately);
        }
    }

    private static void put(RefreshSlot slot, double[] values, double first, double second) {
        if (values == null) {
            slot.put(first, second);
        } else {
            slot.put(values);
        }
    }

    /** Makes a slot this thread's, forgetting retired ones that wait no more; under this object's monitor. */
    private void adopt(RefreshSlot slot) {
        List<RefreshSlot> kept = new ArrayList<>(slots.length + 1);
        for (RefreshSlot s : slots) {
            if (!s.retired || s.queued) {
                kept.add(s);
            }
        }
        kept.add(slot);
        slot.owner = this;
        slots = kept.toArray(new RefreshSlot[0]);
    }

    /**
     * Reports that the link to the hardware failed: at the next cycle every container ends with
     * {@link RobotLinkException} and its end action stops its motors.
     *
     * @param link  the link, for the message
     * @param cause the failure
     */
    public void linkFailed(String link, Throwable cause) {
        RobotLinkException failure = new RobotLinkException("robot '" + robot + "': link " + link + " failed: "
                + cause.getMessage() + "; its motors were stopped", cause);
        synchronized (this) {
            // Replaces a report the cycle has not taken yet (the link failed, came back and failed again before the next
            // cycle): this one covers everything queued up to now, the earlier one only what was queued before it.
            LINK_FAILURE.setVolatile(this, new LinkFailure(failure, lastTicket));
        }
        wake();
    }

    /**
     * A link failure and the last ticket submitted when it was reported: containers submitted up to
     * it (queued while the link still looked up) end with it too, and refreshes queued up to it are
     * dropped, instead of being admitted to wait on a link that is gone (and to move the motors when
     * it comes back); those submitted after it (the safety stop that follows) are admitted. A brick's
     * link agent reports the failure under the same lock under which commands are handed over
     * while the link is up, so no command slips in between.
     */
    private record LinkFailure(RobotLinkException cause, long throughTicket) {
    }

    /**
     * Reports that the hardware refused what the driver sent (a brick's error status): at the next
     * cycle every running container ends with that exception, at once, and its end action stops
     * its motors. The link stays up: later commands are tried again.
     *
     * @param cause the refusal, as the user should read it (a {@code RobotException} naming the brick's status)
     */
    public void driverFailed(RuntimeException cause) {
        driverFailed(cause, Long.MAX_VALUE);
    }

    /**
     * Reports a refusal of what the driver sent for the containers admitted up to cycle
     * {@code throughCycle} (cycles numbered as {@link #cycles()} counts them, the first being 1):
     * at the next cycle those of them still running end with that exception, at once, and their
     * end actions stop their motors. A container admitted in a later cycle carries on: the refused
     * exchange was sent before it existed (a poll in flight when the brick recovered), and what it
     * wants goes to the hardware next, which ends it if it still refuses. Two refusals before the
     * next cycle end the containers of both, with the first one's exception.
     *
     * @param cause        the refusal, as the user should read it (a {@code RobotException} naming the brick's status)
     * @param throughCycle the last cycle whose admitted containers the refused exchange concerns
     */
    public void driverFailed(RuntimeException cause, long throughCycle) {
        java.util.Objects.requireNonNull(cause, "cause");
        while (true) {
            Refusal was = driverFailure;
            Refusal now = was == null ? new Refusal(cause, throughCycle)
                    : new Refusal(was.cause(), Math.max(was.throughCycle(), throughCycle));
            if (DRIVER_FAILURE.compareAndSet(this, was, now)) {
                wake();
                return;
            }
        }
    }

    /** A refusal waiting for the next cycle: the exception, and the last cycle whose admitted containers it ends. */
    private record Refusal(RuntimeException cause, long throughCycle) {
    }

    /**
     * @param listener run at the end of every cycle, on the cycling thread (a motor platform
     *                 hands its new outputs to its link there)
     */
    public void addCycleListener(Runnable listener) {
        synchronized (this) {
            Runnable[] more = java.util.Arrays.copyOf(cycleListeners, cycleListeners.length + 1);
            more[more.length - 1] = listener;
            cycleListeners = more;
        }
    }

    /**
     * @param listener told once, on the dying thread, when the cycling thread dies of a failure it
     *                 cannot survive (after every container was ended and the last stop handed to the link)
     */
    public void addFailureListener(java.util.function.Consumer<RobotException> listener) {
        failureListeners.add(listener);
    }

    /** @return why the cycling thread died, if it did */
    public java.util.Optional<RobotException> failure() {
        return java.util.Optional.ofNullable(failure);
    }

    /** @return the actuators held by running containers, as of the last cycle */
    public Set<String> actuatorsInUse() {
        return inUse;
    }

    /** @return cycles run so far */
    public long cycles() {
        return cycles;
    }

    /** @return cycles that took longer than the period */
    public long overruns() {
        return overruns.get();
    }

    /** @return exceptions thrown by actions, logic, end actions and listeners */
    public long errors() {
        return errors.get();
    }

    /**
     * Runs one cycle, in this order:
     * <ol>
     *   <li>If the link failed, end every container with {@link RobotLinkException} (and, at
     *   admission below, those queued before the failure was reported); if the hardware
     *   refused a command ({@link #driverFailed}), end every container it concerns (those admitted
     *   up to the cycle it names) with that refusal.</li>
     *   <li>Admit queued containers and refresh slots in the order they were submitted, applying
     *   the clash and refresh rules, and start each admitted one (its action objects run); what an
     *   action submits meanwhile is admitted in this cycle too. A container whose caller cancelled
     *   its future before it started is dropped.</li>
     *   <li>End, as interrupted (their end actions stop their motors), containers whose caller
     *   cancelled their future, and those whose watchdog expired.</li>
     *   <li>Evaluate the logic objects of every running container; end those whose logic all holds.</li>
     *   <li>Run the cycle listeners.</li>
     * </ol>
     *
     * @return the number of containers running after the cycle (0 = nothing to do)
     */
    public int cycle() {
        long start = clock.nanoTime();
        // On its own thread a cycle's steps are timed, so an overrun names the slowest (WPILib's epochs).
        boolean timed = runner != null;
        slowestNanos = 0;
        LinkFailure failure = linkFailure == null ? null : (LinkFailure) LINK_FAILURE.getAndSet(this, null);
        if (failure != null) {
            for (Container c : snapshot()) {
                finish(c, true, failure.cause());
            }
        }
        Refusal refused = driverFailure == null ? null : (Refusal) DRIVER_FAILURE.getAndSet(this, null);
        if (refused != null) {
            for (Container c : snapshot()) {
                if (c.admittedIn <= refused.throughCycle()) {
                    finish(c, true, refused.cause());
                }
            }
        }
        // One at a time, in the order submitted: an action may submit more, which this cycle admits too.
        while (anyIncoming) {
            Object next = takeNext();
            if (next == null) {
                break;
            }
            long t0 = timed ? clock.nanoTime() : 0;
            if (next instanceof Container c) {
                if (c.completion().isCancelled()) {
                    continue; // its caller cancelled it before it started: it never runs
                }
                if (failure != null && c.ticket <= failure.throughTicket()) {
                    // queued before the link was reported lost: it ends as those running did, never started
                    c.completion().completeExceptionally(failure.cause());
                    continue;
                }
                admit(c, start);
                if (timed) {
                    epoch(c.name(), "admission", t0);
                }
            } else {
                RefreshSlot slot = (RefreshSlot) next;
                if (failure != null && slot.ticket <= failure.throughTicket()) {
                    // refreshed before the link was reported lost: dropped, as what it refreshes was stopped (nobody waits for it)
                    continue;
                }
                admit(slot, start);
                if (timed) {
                    epoch(slot.name(), "refresh", t0);
                }
            }
        }
        if (active.size() == 1) {
            // One container (a robot's running drive): nothing to copy, as ending it ends the loop.
            Container c = active.get(0);
            long t0 = timed ? clock.nanoTime() : 0;
            if (!cancelled(c) && !watchdog(c, start)) {
                evaluate(c, start);
            }
            if (timed) {
                epoch(c.name(), "logic", t0);
            }
        } else {
            for (Container c : snapshot()) {
                if (!cancelled(c)) {
                    watchdog(c, start);
                }
            }
            for (Container c : snapshot()) {
                long t0 = timed ? clock.nanoTime() : 0;
                evaluate(c, start);
                if (timed) {
                    epoch(c.name(), "logic", t0);
                }
            }
        }
        long listenersStarted = timed ? clock.nanoTime() : 0;
        for (Runnable listener : cycleListeners) {
            try {
                listener.run();
            } catch (Throwable t) {
                survive("a cycle listener", t);
            }
        }
        if (timed) {
            epoch("the cycle listeners (the hand-off to the link)", null, listenersStarted);
        }
        if (holdersChanged) {
            inUse = holders.actuators();
            holdersChanged = false;
        }
        CYCLES.setRelease(this, cycles + 1);
        if (runner != null && clock.nanoTime() - start > periodNanos) { // overruns of its own thread; a simulation's cycles take what they take
            long n = overruns.incrementAndGet();
            if (Long.bitCount(n) == 1) {
                LOG.warn("robot '{}': execution action thread overran its {} µs period ({} overruns so far); its slowest step was {} ({} µs)",
                        robot, periodNanos / 1000, n, slowestKind == null ? slowestStep : "the " + slowestKind + " of '" + slowestStep + "'",
                        slowestNanos / 1000);
            }
        }
        return active.size();
    }

    /** Keeps the slowest step of this cycle: a container's name and what it did, timed since {@code t0}. */
    private void epoch(String step, String kind, long t0) {
        long took = clock.nanoTime() - t0;
        if (took > slowestNanos) {
            slowestNanos = took;
            slowestStep = step;
            slowestKind = kind;
        }
    }

    /**
     * Ends a container whose caller cancelled its future (an interrupted or timed-out wait): as
     * interrupted, so its end action stops its motors.
     *
     * @return whether it did
     */
    private boolean cancelled(Container c) {
        if (!c.completion().isCancelled()) {
            return false;
        }
        LOG.debug("robot '{}': '{}' was cancelled by its caller; ending it", robot, c.name());
        finish(c, true, null);
        return true;
    }

    /**
     * Ends a container whose watchdog expired.
     *
     * @return whether it did
     */
    private boolean watchdog(Container c, long now) {
        if (!c.watchdogExpired(now)) {
            return false;
        }
        LOG.warn("robot '{}': watchdog stopped '{}': not refreshed within {} ms", robot, c.name(), c.watchdog().toMillis());
        finish(c, true, new RobotException("robot '" + robot + "': watchdog stopped '" + c.name() + "': it was not refreshed within "
                + c.watchdog().toMillis() + " ms"));
        return true;
    }

    /** Evaluates a running container's logic objects and ends it when they all hold (or one throws). */
    private void evaluate(Container c, long now) {
        boolean done;
        try {
            done = c.evaluate(now);
        } catch (Throwable t) {
            fail(c, t);
            return;
        }
        if (done) {
            finish(c, false, null);
        }
    }

    /** The running containers, copied into a reused list so the loops may end them as they go. */
    private List<Container> snapshot() {
        scratch.clear();
        for (int i = 0; i < active.size(); i++) {
            scratch.add(active.get(i)); // not addAll: it copies through a new array every time
        }
        return scratch;
    }

    /**
     * @return the queued container or slot with the lowest ticket (a slot's values taken for the
     *         cycle), or {@code null} if nothing is queued
     */
    private Object takeNext() {
        synchronized (this) {
            Container first = queuedContainers == 0 ? null : incoming.peekFirst();
            RefreshSlot slot = null;
            int queuedSlots = 0;
            for (RefreshSlot s : slots) {
                if (s.queued) {
                    queuedSlots++;
                    if (slot == null || s.ticket < slot.ticket) {
                        slot = s;
                    }
                }
            }
            Object next;
            if (slot != null && (first == null || slot.ticket < first.ticket)) {
                slot.take();
                queuedSlots--;
                next = slot;
            } else if (first != null) {
                next = incoming.pollFirst();
                queuedContainers--;
            } else {
                next = null;
            }
            if (queuedSlots == 0 && queuedContainers == 0) {
                anyIncoming = false; // the usual cycle of a driving robot: one lock, not a second to find the queue empty
            }
            return next;
        }
    }

    /**
     * Admits a slot's values: a refresh in place of the running container that holds its actuators
     * if that one is refreshed by it, else a new container by the clash rules.
     */
    private void admit(RefreshSlot slot, long now) {
        Container holder = soleHolder(slot.actuators);
        if (holder != null && holder.refreshedBy(slot.refreshKey(), slot.requirements(), slot.priority())) {
            try {
                holder.restartWatchdog(now);
                slot.handler().refresh(slot.taken, now);
            } catch (Throwable t) {
                fail(holder, t);
            }
            return;
        }
        Container c;
        try {
            c = slot.handler().container(slot.taken);
        } catch (Throwable t) {
            survive("command '" + slot.name() + "'", t);
            return;
        }
        admit(c, now);
    }

    /** @return the one running container that holds any of these actuators, or {@code null} if none or several do */
    private Container soleHolder(String[] requirements) {
        Container only = null;
        for (String actuator : requirements) {
            Container holder = holders.get(actuator);
            if (holder == null || holder == only) {
                continue;
            }
            if (only != null) {
                return null;
            }
            only = holder;
        }
        return only;
    }

    private void admit(Container c, long now) {
        c.admittedIn = cycles + 1;
        // The holders of its actuators, in the order of its requirements, each once; no set is made
        // when one container holds them all (a refresh of a continuous command, ten times a second).
        Container only = null;
        Set<Container> clashing = Set.of();
        for (String actuator : c.requirements()) {
            Container holder = holders.get(actuator);
            if (holder == null || holder == only || clashing.contains(holder)) {
                continue;
            }
            if (only == null && clashing.isEmpty()) {
                only = holder;
            } else {
                if (clashing.isEmpty()) {
                    clashing = new LinkedHashSet<>();
                    clashing.add(only);
                }
                clashing.add(holder);
            }
        }
        if (only != null && clashing.isEmpty()) {
            Container holder = only;
            if (holder.refreshedBy(c)) {
                try {
                    holder.refresh(now, c);
                    c.completion().complete(null);
                } catch (Throwable t) {
                    try {
                        survive("command '" + c.name() + "'", t);
                    } finally {
                        c.completion().completeExceptionally(t);
                    }
                    finish(holder, true, t);
                }
                return;
            }
            clashing = Set.of(only);
        }
        for (Container holder : clashing) {
            boolean holderWins = holder.priority().compareTo(c.priority()) > 0
                    || (holder.priority() == c.priority() && holder.interruptionBehavior() == InterruptionBehavior.CANCEL_INCOMING);
            if (holderWins) {
                LOG.debug("robot '{}': refused '{}', held by '{}'", robot, c.name(), holder.name());
                c.completion().completeExceptionally(CommandPreemptedException.refused(c.name(), holder.name()));
                return;
            }
        }
        for (Container holder : clashing) {
            finish(holder, true, new CommandPreemptedException(holder.name(), c.name()));
        }
        for (String actuator : c.requirements()) {
            holders.put(actuator, c);
        }
        holdersChanged = true;
        active.add(c);
        try {
            c.start(now);
        } catch (Throwable t) {
            fail(c, t);
        }
    }

    /** One container's unit of work failed: the policy hears of it (and re-throws what the thread cannot survive), the container ends with it. */
    private void fail(Container c, Throwable t) {
        survive("command '" + c.name() + "'", t);
        finish(c, true, t);
    }

    /**
     * Reports what one unit of work threw to the failure policy, and counts it; re-throws a
     * failure the thread cannot survive, so the loop ends ({@link #died}).
     *
     * @param what the unit of work, for the report ("command 'move'")
     */
    private void survive(String what, Throwable t) {
        errors.incrementAndGet();
        failures.surviveOrRethrow(role + ", " + what, t);
    }

    /** Removes the container first, so an end action that submits or fails cannot see it again. */
    private void finish(Container c, boolean interrupted, Throwable cause) {
        if (!active.remove(c)) {
            return;
        }
        for (String actuator : c.requirements()) {
            holders.remove(actuator, c);
        }
        holdersChanged = true;
        Throwable endFailed = null;
        try {
            c.end(interrupted);
        } catch (Throwable t) {
            endFailed = t;
        }
        if (cause == null) {
            c.completion().complete(null);
        } else {
            c.completion().completeExceptionally(cause);
        }
        if (endFailed != null) {
            survive("the end action of '" + c.name() + "'", endFailed);
        }
    }

    /**
     * @return the next queued container, or {@code null} once none is left (queued slots' values
     *         are dropped: nobody waits for them), for a thread that ends
     */
    private Container takeQueued() {
        synchronized (this) {
            for (RefreshSlot s : slots) {
                s.queued = false;
            }
            Container c = incoming.pollFirst();
            if (c == null) {
                anyIncoming = false;
            } else {
                queuedContainers--;
            }
            return c;
        }
    }

    /**
     * Starts the real-time thread that cycles at the period, on this thread's clock, for a
     * platform that runs its own threads ({@link io.robomw.api.spi.Cycling#OWN_THREADS}; a platform
     * whose owner cycles it, a simulation, never calls this). While containers run it cycles once
     * a period; with none, it sleeps until a submit, a refresh, a link failure, a refusal or
     * {@link #close()} wakes it. Only once.
     *
     * @throws IllegalStateException if the thread was already started
     */
    public void start() {
        start(IDLE_WAIT);
    }

    /**
     * {@link #start()}, with the longest sleep of an idle thread nobody wakes.
     *
     * @param idleWait how long the thread sleeps, at most, after a cycle with nothing to do
     */
    synchronized void start(Duration idleWait) {
        if (runner != null) {
            throw new IllegalStateException("the execution action thread of '" + robot + "' was already started");
        }
        runner = OwnerThread.start(role, Thread.MAX_PRIORITY, new Cycler(),
                IdleStrategy.periodic(clock, Duration.ofNanos(periodNanos), idleWait), failures);
    }

    /** The cycling thread's duty: a cycle per round; its work is what runs or waits to. */
    private final class Cycler implements OwnerThread.Duty {
        @Override
        public int doWork() {
            int running = cycle();
            return anyIncoming || linkFailure != null || driverFailure != null ? running + 1 : running;
        }

        @Override
        public void onDeath(Throwable failure) {
            died(failure);
        }
    }

    /**
     * The cycling thread cannot go on: stops every motor it can, says why, and marks the robot
     * failed. Runs on the dying thread; must not throw. (The failure policy hears of the death from
     * the thread's runner.)
     */
    void died(Throwable t) {
        errors.incrementAndGet();
        RobotException why = new RobotException("robot '" + robot + "': its execution action thread died of " + t
                + "; every command was stopped", t);
        FAILURE.compareAndSet(this, null, why);
        for (Container c : List.copyOf(active)) {
            try {
                finish(c, true, why);
            } catch (Throwable e) {
                c.completion().completeExceptionally(why);
            }
        }
        for (Container c; (c = takeQueued()) != null; ) {
            c.completion().completeExceptionally(why);
        }
        for (Runnable listener : cycleListeners) {
            try {
                listener.run(); // the motor platform hands the last stop to its link
            } catch (Throwable e) {
                errors.incrementAndGet();
            }
        }
        for (java.util.function.Consumer<RobotException> l : failureListeners) {
            try {
                l.accept(why);
            } catch (Throwable e) {
                errors.incrementAndGet();
            }
        }
    }

    /**
     * Stops the thread (waiting until it has really ended: a cycle blocked on something is
     * interrupted), then ends every container, queued or running, as interrupted, and runs the
     * cycle listeners once more (the motor platform hands the stops to its link). Idempotent.
     */
    @Override
    public void close() {
        if (closed) {
            return;
        }
        closed = true;
        OwnerThread r = runner;
        if (r != null) {
            r.close(); // on the cycling thread itself (an end action closing the robot) it only ends the loop
        }
        RobotException closing = new RobotException("robot '" + robot + "' was closed");
        for (Container c; (c = takeQueued()) != null; ) {
            c.completion().completeExceptionally(closing);
        }
        for (Container c : List.copyOf(active)) {
            try {
                finish(c, true, closing);
            } catch (Throwable t) {
                c.completion().completeExceptionally(closing); // the policy was told, and re-threw what nobody survives
            }
        }
        for (Runnable listener : cycleListeners) {
            try {
                listener.run();
            } catch (Throwable t) {
                errors.incrementAndGet();
                if (FailurePolicy.survivable(t)) {
                    failures.survived(role + ", a cycle listener while closing", t);
                }
            }
        }
    }

    /**
     * Which container holds each actuator in use: a robot has a handful, so two arrays scanned
     * (an actuator's name is most often the very string the last command used) cost less than a
     * hash map's table and entries. Cycling thread only.
     */
    private static final class Holders {
        private String[] actuators = new String[4];
        private Container[] containers = new Container[4];
        private int size;

        private int indexOf(String actuator) {
            for (int i = 0; i < size; i++) {
                if (actuators[i] == actuator) {
                    return i;
                }
            }
            int hash = actuator.hashCode();
            for (int i = 0; i < size; i++) {
                if (actuators[i].hashCode() == hash && actuators[i].equals(actuator)) {
                    return i;
                }
            }
            return -1;
        }

        Container get(String actuator) {
            int i = indexOf(actuator);
            return i < 0 ? null : containers[i];
        }

        void put(String actuator, Container c) {
            int i = indexOf(actuator);
            if (i >= 0) {
                containers[i] = c;
                return;
            }
            if (size == actuators.length) {
                actuators = java.util.Arrays.copyOf(actuators, size * 2);
                containers = java.util.Arrays.copyOf(containers, size * 2);
            }
            actuators[size] = actuator;
            containers[size] = c;
            size++;
        }

        /** Removes the actuator if that container holds it. */
        void remove(String actuator, Container c) {
            int i = indexOf(actuator);
            if (i >= 0 && containers[i] == c) {
                size--;
                actuators[i] = actuators[size];
                containers[i] = containers[size];
                actuators[size] = null;
                containers[size] = null;
            }
        }

        Set<String> actuators() {
            return Set.of(java.util.Arrays.copyOf(actuators, size));
        }
    }

    private static final java.lang.invoke.VarHandle LINK_FAILURE;
    private static final java.lang.invoke.VarHandle DRIVER_FAILURE;
    private static final java.lang.invoke.VarHandle CYCLES;
    private static final java.lang.invoke.VarHandle FAILURE;

    static {
        try {
            java.lang.invoke.MethodHandles.Lookup l = java.lang.invoke.MethodHandles.lookup();
            LINK_FAILURE = l.findVarHandle(ExecutionActionThread.class, "linkFailure", LinkFailure.class);
            DRIVER_FAILURE = l.findVarHandle(ExecutionActionThread.class, "driverFailure", Refusal.class);
            CYCLES = l.findVarHandle(ExecutionActionThread.class, "cycles", long.class);
            FAILURE = l.findVarHandle(ExecutionActionThread.class, "failure", RobotException.class);
        } catch (ReflectiveOperationException e) {
            throw new ExceptionInInitializerError(e);
        }
    }
}
