package io.robomw.agents.host.visit;

import io.robomw.agents.host.protocol.Bodies;
import io.robomw.agents.host.wire.WireChannel;
import io.robomw.agents.host.core.HostActivity;
import io.robomw.agents.host.core.HostState;
import io.robomw.agents.host.home.OwedEvents;
import io.robomw.agents.host.protocol.AgentEvent;
import io.robomw.agents.host.protocol.AgentImage;
import io.robomw.agents.host.protocol.Frame;
import io.robomw.agents.host.protocol.StackTraces;
import io.robomw.agents.host.code.StateCodec;
import io.robomw.api.AgentStatus;
import io.robomw.api.Itinerary;
import io.robomw.api.spi.FailurePolicy;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.io.IOException;
import java.nio.charset.StandardCharsets;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.Optional;

/**
 * Agents' trips through a host: runs an agent's stop here ({@link #runStop}), then sends it on to
 * its next reachable stop ({@link #depart}), home when it was retracted ({@link #goHome}), or ends
 * its trip here and owes its home the result ({@link #finish}).
 *
 * <p>Each stop runs on a pooled runner thread named after the agent while it runs. The stop is
 * marked started in the store before its work begins, so a host killed during the work resumes the
 * agent after the stop ({@code interrupted}) rather than run it twice.
 */
public final class Trips {

    private static final Logger LOG = LoggerFactory.getLogger(Trips.class);
    /** How long an agent waits to leave until its reports from here are home. */
    private static final long REPORT_FLUSH_MILLIS = 5_000;
    private static final byte[] NO_STATE = new byte[0];

    private final HostState host;
    private final HopSender hops;
    private final OwedEvents owed;
    private final RobotTurns robot;
    /** How long a retracted agent tries to get home (the delivery expiry) before its trip ends where it is. */
    private final Duration homewardFor;

    /**
     * Where an agent went, or why it did not go anywhere.
     *
     * @param delivered whether the next host has it
     * @param target    that host
     * @param reason    why it was not delivered
     */
    public record Departure(boolean delivered, String target, String reason) {
    }

    public Trips(HostState host, HopSender hops, OwedEvents owed, RobotTurns robot, Duration homewardFor) {
        this.host = host;
        this.homewardFor = homewardFor;
        this.hops = hops;
        this.owed = owed;
        this.robot = robot;
    }

    /**
     * Runs an agent's stop at this host and moves it on. Called on a runner thread.
     *
     * @param h           the agent, accepted and stored
     * @param interrupted whether the stop's work had begun when the host last stopped (then it is not run again)
     */
    void runStop(HostedAgent h, boolean interrupted) {
        Thread t = Thread.currentThread();
        String poolName = t.getName();
        String role = "agent-" + h.shortId() + "-" + simpleName(h.className) + "@" + host.name;
        t.setName(role);
        boolean dying = false;
        try {
            host.messaging.met(h);
            Itinerary it = h.agent.itinerary();
            String stopHost = it.currentStop().map(Itinerary.Stop::host).orElse(host.address);
            if (interrupted) {
                it.record(stopHost, Itinerary.Outcome.INTERRUPTED, "host " + host.name + " stopped while this stop's work ran; it is not run twice");
                LOG.info("host {}: agent {} ({}) was mid-stop when the host stopped; going on without running the stop again", host.name, h.id, h.className);
            } else {
                boolean marked = false;
                try {
                    if (!h.startStored) {
                        host.store.started(h.id, h.hop);
                    }
                    marked = true;
                } catch (IOException e) {
                    LOG.error("host {}: cannot mark agent {}'s stop as started ({}); not running it", host.name, h.id, e.toString());
                    it.record(stopHost, Itinerary.Outcome.FAILED, "the host's store failed: " + e.getMessage());
                }
                if (marked) {
                    HostContext ctx = host.contextOf(h);
                    h.agent.attach(ctx);
                    if (!h.working()) {
                        // an operator's retract or dispose came after it arrived and before its work began: the work does not begin
                        it.record(stopHost, Itinerary.Outcome.INTERRUPTED, (h.retractRequested ? "retracted" : "disposed of")
                                + " by the operator before its work began at " + host.name);
                    } else {
                        try {
                            h.agent.onArrival();
                            Itinerary.Task task = it.currentStop().map(Itinerary.Stop::task).orElse(null);
                            if (task != null) {
                                task.execute(ctx);
                            } else {
                                h.agent.run();
                            }
                            it.record(stopHost, Itinerary.Outcome.DONE, "");
                            host.activity.record(h.id, h.className, HostActivity.STOP_DONE, host.address, "");
                        } catch (Throwable e) {
                            // Whatever the agent's code throws that a thread survives (an exception, a LinkageError, a
                            // StackOverflowError...) fails its stop, not the host; any other ends its trip (below).
                            host.failures.surviveOrRethrow(role, e);
                            if (h.leaveAskedAt != 0) {
                                // A retract or dispose interrupted the work: the stop was cut short on purpose, not failed.
                                LOG.info("host {}: agent {} ({}) ended its stop on the {} interrupt: {}", host.name, h.id, h.className,
                                        h.retractRequested ? "retract" : "dispose", e.toString());
                                it.record(stopHost, Itinerary.Outcome.INTERRUPTED, (h.retractRequested ? "retracted" : "disposed of") + " by the operator while"
                                        + " its work ran at " + host.name + ": " + e);
                            } else {
                                LOG.warn("host {}: agent {} ({}) failed at its stop: {}", host.name, h.id, h.className, e.toString());
                                it.record(stopHost, Itinerary.Outcome.FAILED, StackTraces.of(e));
                            }
                            host.activity.record(h.id, h.className, HostActivity.STOP_FAILED, host.address, e.toString());
                        } finally {
                            h.rested();
                        }
                    }
                }
            }
            robot.release();
            moveOn(h);
        } catch (Throwable e) {
            if (FailurePolicy.survivable(e)) {
                // The runner must not die silently with the agent stuck here: say so, and end its trip here unless it has left.
                host.failures.survived(role, e);
                LOG.warn("host {}: agent {} ({}) could not go on: {}; its trip ends here", host.name, h.id, h.className, e.toString());
                endHere(h, () -> {
                    h.agent.itinerary().record(host.address, Itinerary.Outcome.FAILED, StackTraces.of(e));
                    finish(h, AgentEvent.Kind.RESULT);
                });
            } else {
                // An error no thread survives (out of memory, an internal error of the VM): the agent's trip ends
                // here in failure, and the runner with it (the thread reports its death under the agent's name;
                // the pool starts another runner for the next agent), while the host serves on.
                dying = true;
                endHere(h, () -> fail(h, "agent " + h.id + " (" + h.className + ") died at host " + host.name + " (" + host.address
                        + ") of " + e + "; its trip ends there"));
                throw (VirtualMachineError) e;
            }
        } finally {
            robot.release();
            if (!dying) {
                t.setName(poolName);
            }
        }
    }

    /** Ends an agent's trip here unless it has left, as {@code end} says; if that fails too, the agent stays in the store. */
    private void endHere(HostedAgent h, Runnable end) {
        if (h.departure.isDone() || host.closed) {
            return;
        }
        try {
            end.run();
        } catch (Throwable again) {
            LOG.error("host {}: agent {} could not end its trip here either ({}); it stays in the store for the next start", host.name, h.id,
                    again.toString());
        }
    }

    /** After a stop: home if retracted, the end if disposed of, else on to the next reachable stop or the end of the trip. */
    void moveOn(HostedAgent h) {
        host.messaging.left(h);
        h.agent.attach(host.contextOf(h));
        if (h.retractRequested) {
            goHome(h);
            return;
        }
        if (h.disposeRequested) {
            finish(h, AgentEvent.Kind.DISPOSED);
            return;
        }
        Departure d = depart(h);
        if (d.delivered()) {
            return; // HopSender removed it from the agents here when the next host acknowledged
        }
        if (h.retractRequested && !host.closed) {
            goHome(h); // retracted while it waited to hop
            return;
        }
        if (h.disposeRequested && !host.closed) {
            finish(h, AgentEvent.Kind.DISPOSED);
            return;
        }
        if (!host.closed) {
            LOG.info("host {}: agent {} ends its trip here: {}", host.name, h.id, d.reason());
            finish(h, AgentEvent.Kind.RESULT);
        }
    }

    /**
     * Sends an agent on to its next reachable stop, following its itinerary's policy for stops
     * that cannot be reached. Stops at this host run here without a network hop.
     *
     * <p>The agent's state is written straight into the transfer call's frame, sized by its image
     * when it last travelled ({@link AgentImage#frame}): no copy on its way to the wire.
     */
    public Departure depart(HostedAgent h) {
        Itinerary it = h.agent.itinerary();
        List<String> unreachable = new ArrayList<>();
        while (!host.closed) {
            if (h.retractRequested || h.disposeRequested) {
                return new Departure(false, null, "an operator asked it to " + (h.retractRequested ? "go home" : "end its trip"));
            }
            Optional<Itinerary.Stop> next = it.goToNext();
            if (next.isEmpty()) {
                return new Departure(false, null, unreachable.isEmpty() ? "its itinerary is done" : "no further stop could be reached: " + String.join("; ", unreachable));
            }
            String target = next.get().host();
            if (!target.contains("://")) {
                // a stop named by its host's name, as messages name hosts: resolved at the host that sends the agent there
                try {
                    target = host.messaging.hostAddress(target, h);
                } catch (RuntimeException e) {
                    it.record(target, Itinerary.Outcome.UNREACHABLE, e.getMessage());
                    unreachable.add(target + " (" + e.getMessage() + ")");
                    LOG.warn("host {}: agent {} cannot go to {}: {}", host.name, h.id, target, e.getMessage());
                    if (it.unreachablePolicy() == Itinerary.UnreachablePolicy.RETURN_HOME) {
                        return new Departure(false, null, "its stop " + target + " could not be found and its policy is to return home");
                    }
                    continue;
                }
            }
            try {
                h.agent.onDispatching();
            } catch (Throwable e) {
                host.failures.surviveOrRethrow(Thread.currentThread().getName(), e);
                LOG.warn("host {}: agent {} onDispatching threw {}", host.name, h.id, e.toString());
            }
            owed.awaitDelivered(h.id, REPORT_FLUSH_MILLIS);
            h.agent.attach(null);
            AgentImage image = new AgentImage(h.id, h.hop + 1, AgentImage.Kind.TRIP, h.home.equals(host.address), h.home, h.digest, h.eventSeq, NO_STATE);
            Frame frame;
            try {
                frame = image.frame(h.agent, h.imageSize, host.frameBuffers, host.codec, hops.stateFormOf(target));
            } catch (IOException e) {
                h.agent.attach(host.contextOf(h));
                return new Departure(false, null, "its state is not serializable: " + e.getMessage());
            }
            h.imageSize = frame.bodyLength();
            String why = hops.send(h, image, frame, target, it);
            // The transfer is over, delivered or not: nothing reads the frame any more.
            host.frameBuffers.give(frame.bytes);
            if (why == null) {
                if (frame.bodyLength() > WireChannel.SPIN_MAX_BODY) {
                    // It takes longer than a runner's spin to come back, and the spin would take a processor from the host reading it.
                    host.runnerHandoff.parkNext();
                }
                host.activity.record(h.id, h.className, HostActivity.DEPARTED, host.address, target);
                return new Departure(true, target, null);
            }
            h.agent.attach(host.contextOf(h));
            it.record(target, Itinerary.Outcome.UNREACHABLE, why);
            unreachable.add(target + " (" + why + ")");
            LOG.warn("host {}: agent {} cannot reach {}: {}", host.name, h.id, target, why);
            if (it.unreachablePolicy() == Itinerary.UnreachablePolicy.RETURN_HOME) {
                return new Departure(false, null, "its stop " + target + " could not be reached and its policy is to return home");
            }
        }
        return new Departure(false, null, "the host is closing");
    }

    /**
     * Ends an agent's trip here: its result (or why it failed, or that it was disposed of) is owed
     * to its home.
     *
     * @param kind {@link AgentEvent.Kind#RESULT} or {@link AgentEvent.Kind#DISPOSED}
     */
    void finish(HostedAgent h, AgentEvent.Kind kind) {
        HostContext ctx = host.contextOf(h);
        h.agent.attach(ctx);
        try {
            h.agent.onDisposing();
        } catch (Throwable e) {
            host.failures.surviveOrRethrow(Thread.currentThread().getName(), e);
            LOG.warn("host {}: agent {} onDisposing threw {}", host.name, h.id, e.toString());
        }
        h.agent.attach(null);
        byte[] payload;
        AgentEvent.Kind k = kind;
        Optional<Itinerary.Visit> failed = h.agent.itinerary().history().stream()
                .filter(v -> v.outcome() == Itinerary.Outcome.FAILED).reduce((first, second) -> second);
        if (kind == AgentEvent.Kind.RESULT && h.result == null && failed.isPresent()) {
            // Nothing to bring home, and a stop failed: that failure is the outcome of the trip.
            k = AgentEvent.Kind.FAILED;
            payload = ("brought no result home: its stop at " + failed.get().host() + " failed: " + StackTraces.firstLine(failed.get().detail()))
                    .getBytes(StandardCharsets.UTF_8);
        } else if (kind == AgentEvent.Kind.RESULT) {
            try {
                payload = StateCodec.write(h.result);
            } catch (IOException e) {
                k = AgentEvent.Kind.FAILED;
                payload = ("ended at " + host.name + " but its result is not serializable: " + e.getMessage()).getBytes(StandardCharsets.UTF_8);
            }
        } else {
            payload = ("was disposed of at " + host.address).getBytes(StandardCharsets.UTF_8);
        }
        end(h, k, payload);
    }

    /**
     * Ends an agent's trip here in failure, without calling its code again (it failed beyond what
     * its callbacks may catch): its home's result fails with {@code why}.
     */
    void fail(HostedAgent h, String why) {
        h.agent.attach(null);
        end(h, AgentEvent.Kind.FAILED, why.getBytes(StandardCharsets.UTF_8));
    }

    /** Owes the trip's visits and its last event to the agent's home, and forgets the agent here. */
    private void end(HostedAgent h, AgentEvent.Kind k, byte[] payload) {
        h.status = k == AgentEvent.Kind.RESULT ? AgentStatus.COMPLETED : k == AgentEvent.Kind.DISPOSED ? AgentStatus.DISPOSED : AgentStatus.FAILED;
        // The visits first, then the event that ends the trip: the home has them when its result future completes.
        owed.owe(h.home, new AgentEvent(h.id, h.eventSeq++, AgentEvent.Kind.VISITS, host.address, Bodies.visits(h.agent.itinerary().history())));
        AgentEvent event = new AgentEvent(h.id, h.eventSeq++, k, host.address, payload);
        host.activity.record(h.id, h.className, k == AgentEvent.Kind.RESULT ? HostActivity.RESULT : k == AgentEvent.Kind.DISPOSED ? HostActivity.DISPOSED
                : HostActivity.FAILED, host.address, k == AgentEvent.Kind.RESULT ? HostActivity.describe(h.result) : new String(payload, StandardCharsets.UTF_8));
        owed.owe(h.home, event);
        try {
            host.store.departed(h.id, h.hop + 1);
        } catch (IOException e) {
            LOG.warn("host {}: cannot record agent {} ended: {}", host.name, h.id, e.toString());
        }
        host.hosted.remove(h.id, h);
        h.departure.complete(null);
    }

    /** Sends a retracted agent home, retrying until its home takes it. */
    void goHome(HostedAgent h) {
        host.activity.record(h.id, h.className, HostActivity.RETRACTED, host.address, "going home to " + h.home);
        try {
            h.agent.onDispatching();
        } catch (Throwable e) {
            host.failures.surviveOrRethrow(Thread.currentThread().getName(), e);
            LOG.warn("host {}: agent {} onDispatching threw {}", host.name, h.id, e.toString());
        }
        h.agent.attach(null);
        AgentImage image = new AgentImage(h.id, h.hop + 1, AgentImage.Kind.HOMECOMING, h.home.equals(host.address), h.home, h.digest, h.eventSeq, NO_STATE);
        Frame frame;
        try {
            frame = image.frame(h.agent, h.imageSize, host.frameBuffers, host.codec, hops.stateFormOf(h.home));
        } catch (IOException e) {
            finish(h, AgentEvent.Kind.RESULT);
            return;
        }
        String why = hops.send(h, image, frame, h.home, homeward());
        host.frameBuffers.give(frame.bytes);
        if (why != null && !host.closed) {
            LOG.warn("host {}: retracted agent {} could not be sent home to {} within {} ({}); its trip ends here", host.name, h.id, h.home,
                    homewardFor, why);
            h.agent.itinerary().record(h.home, Itinerary.Outcome.UNREACHABLE, "retracted, but its home did not take it back: " + why);
            finish(h, AgentEvent.Kind.RESULT);
        }
    }

    /**
     * Sends again an agent that was departing when the host stopped, to the host it was going to.
     *
     * @param h     the agent
     * @param image the image it was departing with, as stored
     */
    void resumeDeparture(HostedAgent h, AgentImage image) {
        String target = image.kind() == AgentImage.Kind.HOMECOMING ? h.home
                : h.agent.itinerary().currentStop().map(Itinerary.Stop::host).orElse(null);
        if (target == null) {
            moveOn(h);
            return;
        }
        Itinerary plan = image.kind() == AgentImage.Kind.HOMECOMING ? homeward() : h.agent.itinerary();
        String why = hops.send(h, image, Frame.of(image.encode()), target, plan);
        if (why == null) {
            return;
        }
        if (host.closed) {
            return; // still departing in the store: sent again at the next start
        }
        h.agent.itinerary().record(target, Itinerary.Outcome.UNREACHABLE, why);
        if (image.kind() == AgentImage.Kind.HOMECOMING || h.agent.itinerary().unreachablePolicy() == Itinerary.UnreachablePolicy.RETURN_HOME) {
            finish(h, AgentEvent.Kind.RESULT);
        } else {
            moveOn(h);
        }
    }

    /** The way home of a retracted agent: retried every second until the home takes it, for as long as a delivery to it is owed. */
    private Itinerary homeward() {
        int retries = (int) Math.min(Integer.MAX_VALUE, Math.max(1, homewardFor.toSeconds()));
        return new Itinerary().onUnreachable(Itinerary.UnreachablePolicy.RETRY).retry(retries, Duration.ofSeconds(1));
    }

    private static String simpleName(String className) {
        return className.substring(className.lastIndexOf('.') + 1);
    }
}
