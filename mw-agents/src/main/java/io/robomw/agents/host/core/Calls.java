package io.robomw.agents.host.core;

import io.robomw.agents.host.AgentInfo;
import io.robomw.agents.host.OwedSelector;
import io.robomw.agents.host.home.AgentHandle;
import io.robomw.agents.host.home.Home;
import io.robomw.agents.host.home.OwedEvents;
import io.robomw.agents.host.protocol.Bodies;
import io.robomw.agents.host.protocol.Op;
import io.robomw.agents.host.protocol.Reply;
import io.robomw.agents.host.rmi.HostEndpoint;
import io.robomw.agents.host.visit.HostedAgent;
import io.robomw.agents.host.visit.Transfers;
import io.robomw.agents.host.code.StateCodec;
import io.robomw.agents.host.code.StateRejectedException;
import io.robomw.api.AgentMessage;
import io.robomw.api.AgentStatus;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.io.IOException;
import java.io.Serializable;
import java.util.Arrays;
import java.util.List;
import java.util.UUID;
import java.util.concurrent.TimeUnit;

/**
 * The calls a host serves, once {@link HostEndpoint} has verified them: passes a transfer on to
 * {@link Transfers} in place, the rest by operation; lists the agents here, and serves the
 * messages and the retract and dispose requests for agents here. A call for an agent that has
 * left is answered with where it went ({@link Reply.Status#MOVED}) when the host remembers.
 */
public final class Calls implements HostEndpoint.Handler {

    private static final Logger LOG = LoggerFactory.getLogger(Calls.class);

    private final HostState host;
    private final Transfers transfers;
    private final CodeLoaders code;
    private final Home home;
    private final OwedEvents owed;

    public Calls(HostState host, Transfers transfers, CodeLoaders code, Home home, OwedEvents owed) {
        this.host = host;
        this.owed = owed;
        this.transfers = transfers;
        this.code = code;
        this.home = home;
    }

    /** Serves a verified call; a transfer is decoded in place (it may be megabytes), other bodies are copied out. */
    @Override
    public Reply handle(String peer, Op op, byte[] message, int offset, int length) {
        if (op == Op.TRANSFER && !host.closed) {
            return transfers.acceptWithRunner(peer, message, offset, length);
        }
        byte[] body = Arrays.copyOfRange(message, offset, offset + length);
        if (host.closed) {
            return Reply.of(Reply.Status.REFUSED, "host " + host.name + " is closing");
        }
        return switch (op) {
            case TRANSFER -> transfers.accept(peer, body, 0, body.length, null);
            case PUT_ARCHIVE -> code.onArchive(peer, body);
            case LIST -> Reply.ok(Bodies.listReply(agents()));
            case EVENT -> home.onEvent(peer, body);
            case ARRIVALS -> home.onArrivals(peer, body);
            case MESSAGE -> onMessage(peer, body);
            case RETRACT, DISPOSE -> onRequest(peer, op, body);
            case DESCRIBE -> Reply.ok(host.messaging.describeSelf().encode());
            case WATCH -> onWatch(body);
            case OWED -> Reply.ok(Bodies.owedReply(owed.owed()));
            case DROP_OWED -> onDropOwed(peer, body);
        };
    }

    /** What a watcher sees: body = the last event number it saw (u64), or nothing for all. */
    private Reply onWatch(byte[] body) {
        long since = body.length >= 8 ? java.nio.ByteBuffer.wrap(body).getLong() : 0;
        return Reply.ok(host.activity.watchReply(host.name, host.robot == null ? "" : host.robot.name(), host.hosted.values(), since, owed.owed()));
    }

    private Reply onDropOwed(String peer, byte[] body) {
        OwedSelector which;
        try {
            which = Bodies.readDropOwed(body);
        } catch (IllegalArgumentException e) {
            return host.refuse("refused a DROP_OWED from peer '" + peer + "': " + e.getMessage());
        }
        return Reply.ok(Bodies.owedReply(owed.drop(which::matches, "dropped by peer '" + peer + "' (" + which + ")")));
    }

    /** @return the agents at this host now */
    public List<AgentInfo> agents() {
        return host.hosted.values().stream().map(HostedAgent::info).toList();
    }

    /** Where an agent went, for calls that arrive after it left. */
    private Reply whereIs(UUID id) {
        AgentHandle sentFromHere = host.handles.get(id);
        if (sentFromHere != null && sentFromHere.ended()) {
            // its home, after its trip ended: not "moved" to where it went last (which would send a chasing call back here)
            return Reply.of(Reply.Status.GONE, "agent " + id + " has ended its trip (" + sentFromHere.status() + " at " + sentFromHere.location() + ")");
        }
        String to = host.forwardOf(id);
        return to != null ? Reply.of(Reply.Status.MOVED, to) : Reply.of(Reply.Status.GONE, "agent " + id + " is not at host " + host.name);
    }

    /** The agent, once it has settled: one that is leaving is waited for until it has left (then it is not here). */
    private HostedAgent present(UUID id) {
        HostedAgent h = host.hosted.get(id);
        if (h != null && h.status == AgentStatus.IN_TRANSIT) {
            try {
                h.departure.get(host.timeoutMillis, TimeUnit.MILLISECONDS);
            } catch (Exception e) {
                return h;
            }
            return host.hosted.get(id);
        }
        return h;
    }

    private Reply onMessage(String peer, byte[] body) {
        Bodies.Message sent;
        try {
            sent = Bodies.readMessage(body);
        } catch (IllegalArgumentException e) {
            return host.refuse("refused a message from peer '" + peer + "': " + e.getMessage());
        }
        UUID id = sent.id();
        HostedAgent h = present(id);
        if (h == null) {
            return whereIs(id);
        }
        Serializable value;
        try {
            value = host.codec.read(sent.content(), h.loader, Serializable.class);
        } catch (StateRejectedException e) {
            return host.refuse("refused a message for agent " + id + ": " + e.getMessage());
        }
        Message m = new Message(value);
        boolean handled;
        try {
            handled = h.agent.handleMessage(m);
        } catch (Throwable e) {
            // the agent's code: what a thread survives refuses this message; the rest ends the thread serving it
            host.failures.surviveOrRethrow(Thread.currentThread().getName(), e);
            return Reply.of(Reply.Status.REFUSED, "agent " + id + " threw while handling the message: " + e);
        }
        if (!handled) {
            if (sent.oneway()) {
                LOG.info("host {}: agent {} did not handle a one-way message; dropped", host.name, id);
            }
            return Reply.of(Reply.Status.NOT_HANDLED, "agent " + id + " (" + h.className + ") did not handle the message");
        }
        try {
            return Reply.ok(m.reply == null ? new byte[0] : StateCodec.write(m.reply));
        } catch (IOException e) {
            return Reply.of(Reply.Status.REFUSED, "agent " + id + "'s reply is not serializable: " + e.getMessage());
        }
    }

    /** A message as an agent handles it; the first reply it sends is the answer. */
    private static final class Message implements AgentMessage {
        private final Serializable content;
        private volatile Serializable reply;

        Message(Serializable content) {
            this.content = content;
        }

        @Override
        public Serializable content() {
            return content;
        }

        @Override
        public void sendReply(Serializable r) {
            if (reply == null) {
                reply = r;
            }
        }
    }

    private Reply onRequest(String peer, Op op, byte[] body) {
        UUID id;
        try {
            id = Bodies.readAgentRequest(body);
        } catch (IllegalArgumentException e) {
            return host.refuse("refused a " + op + " from peer '" + peer + "': " + e.getMessage());
        }
        HostedAgent h = present(id);
        if (h == null) {
            return whereIs(id);
        }
        if (op == Op.RETRACT) {
            h.retractRequested = true;
        } else {
            h.disposeRequested = true;
        }
        h.leaveAskedAt = System.currentTimeMillis();
        // read before the interrupt: the callback it ends clears it as it returns, and the robot would be left running
        boolean drives = h.drives;
        Thread interrupted = h.interruptWork();
        if (interrupted == null) {
            h.leaveAskedAt = 0;
            LOG.info("host {}: {} requested for agent {}; it takes effect before its next callback", host.name, op, id);
            return Reply.ok();
        }
        // An operator means now (as the Aglets runtime stops an aglet's threads when it leaves): the
        // callback is interrupted, the robot's current command stopped, and the agent leaves once it returns.
        LOG.info("host {}: {} requested for agent {}; its callback is interrupted{} and the {} takes effect when it returns", host.name, op, id,
                drives ? " and the robot's command stopped" : "", op);
        if (drives && host.robot != null) {
            java.util.concurrent.CompletableFuture.runAsync(() -> stopRobotFor(h, op), host.requests);
        }
        java.util.concurrent.CompletableFuture.delayedExecutor(LEAVE_GRACE.toMillis(), java.util.concurrent.TimeUnit.MILLISECONDS, host.requests)
                .execute(() -> overGrace(h, op, interrupted));
        return Reply.ok();
    }

    /** How long an interrupted callback may take to return before the host says it does not answer its interrupt (and interrupts it again). */
    static final java.time.Duration LEAVE_GRACE = java.time.Duration.ofSeconds(5);

    private void stopRobotFor(HostedAgent h, Op op) {
        try {
            host.robot.stop();
        } catch (RuntimeException e) {
            LOG.warn("host {}: cannot stop robot {} for the {} of agent {}: {}", host.name, host.robot.name(), op, h.id, e.getMessage());
        }
    }

    /** The grace is over: if the callback still runs, say so once, with where it is, and interrupt it again. */
    private void overGrace(HostedAgent h, Op op, Thread thread) {
        if (h.interruptWork() != thread) {
            return; // it returned (or another callback runs now)
        }
        StackTraceElement[] at = thread.getStackTrace();
        String where = at.length == 0 ? "?" : java.util.Arrays.stream(at).limit(3).map(String::valueOf).collect(java.util.stream.Collectors.joining(" < "));
        LOG.warn("host {}: agent {} ({}) has not returned from its callback {} after the {} interrupted it (at {}); interrupted again. The {} takes"
                + " effect when it returns: Java cannot end a thread that ignores interrupts", host.name, h.id, h.className, LEAVE_GRACE, op, where, op);
    }
}
