package io.robomw.agents.host.visit;

import io.robomw.agents.host.core.CodeLoaders;
import io.robomw.agents.host.core.HostActivity;
import io.robomw.agents.host.core.HostState;
import io.robomw.agents.host.home.AgentHandle;
import io.robomw.agents.host.home.Home;
import io.robomw.agents.host.home.OwedEvents;
import io.robomw.agents.host.protocol.AgentImage;
import io.robomw.agents.host.protocol.Reply;
import io.robomw.agents.host.code.StateRejectedException;
import io.robomw.api.Agent;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.io.IOException;
import java.util.Optional;
import java.util.concurrent.CompletableFuture;

/**
 * Takes agents other hosts send here: decodes the image in place in the request (it may be
 * megabytes), refuses a hop already seen, finds the class loader of the agent's archive (or asks
 * for the archive), reads the state through the filter, stores the agent before acknowledging,
 * and starts its stop on a runner thread. A homecoming (a retracted agent) goes to its
 * {@link Home}.
 */
public final class Transfers {

    private static final Logger LOG = LoggerFactory.getLogger(Transfers.class);

    private final HostState host;
    private final CodeLoaders code;
    private final Trips trips;
    private final Home home;
    private final OwedEvents owed;
    /** Makes the second duplicate check and the store one step, so two copies of a hop cannot both be accepted. */
    private final Object acceptLock = new Object();

    public Transfers(HostState host, CodeLoaders code, Trips trips, Home home, OwedEvents owed) {
        this.host = host;
        this.code = code;
        this.trips = trips;
        this.home = home;
        this.owed = owed;
    }

    /**
     * A transfer, with a runner thread woken as it comes in rather than once it is accepted: waking
     * a parked thread takes tens of microseconds here, about as long as checking, reading and
     * storing the agent, so the two overlap. The runner waits until the agent is stored (its stop
     * never starts before that) and goes back to the pool if the transfer is not accepted. A warm
     * A→B→A round trip with a 0 B payload: p50 104–163 → 90–129 µs in alternating probe runs.
     *
     * @param peer   the sending peer
     * @param raw    holds the transfer's body (the request as received: not copied)
     * @param offset where the body starts
     * @param length its length
     * @return the reply
     */
    public Reply acceptWithRunner(String peer, byte[] raw, int offset, int length) {
        CompletableFuture<HostedAgent> accepted = new CompletableFuture<>();
        host.runners.execute(() -> {
            // The runner usually starts before the agent is stored: spin for it as an idle runner
            // would (bounded, and only while the host has had few agents at once lately), rather than park and be woken again.
            long until = System.nanoTime() + (host.fewAgentsLately() ? host.runnerSpinNanos : 0);
            while (!accepted.isDone() && System.nanoTime() - until < 0) {
                Thread.yield();
            }
            HostedAgent h = accepted.join();
            if (h != null) {
                trips.runStop(h, false);
            }
        });
        HostedAgent[] started = new HostedAgent[1];
        try {
            return accept(peer, raw, offset, length, started);
        } finally {
            accepted.complete(started[0]);
        }
    }

    /**
     * @param started where to put the accepted agent for a runner already woken, or {@code null} to start one
     */
    public Reply accept(String peer, byte[] raw, int offset, int length, HostedAgent[] started) {
        AgentImage image;
        try {
            image = AgentImage.decode(raw, offset, length);
        } catch (IllegalArgumentException e) {
            return host.refuse("refused a transfer from peer '" + peer + "': " + e.getMessage());
        }
        if (image.hop() <= host.store.highestHop(image.id())) {
            return new Reply(Reply.Status.DUPLICATE, new byte[0]);
        }
        if (image.kind() == AgentImage.Kind.HOMECOMING) {
            return home.onHomecoming(peer, image);
        }
        ClassLoader loader;
        try {
            Optional<ClassLoader> l = code.loaderFor(image.digest());
            if (l.isEmpty()) {
                return new Reply(Reply.Status.NEED_ARCHIVE, new byte[0]);
            }
            loader = l.get();
        } catch (IOException e) {
            return host.refuse("refused agent " + image.id() + " from peer '" + peer + "': its archive " + image.digest() + " is not a jar: " + e.getMessage());
        }
        Agent agent;
        try {
            agent = host.codec.read(image.state(), image.stateOffset(), image.stateLength(), loader, Agent.class);
        } catch (StateRejectedException e) {
            return host.refuse("refused agent " + image.id() + " from peer '" + peer + "': " + e.getMessage());
        }
        if (agent == null) {
            return host.refuse("refused agent " + image.id() + " from peer '" + peer + "': its state is null");
        }
        HostedAgent h = new HostedAgent(image, agent, loader);
        h.imageSize = length;
        // Messages may come as soon as the sender has the acknowledgement, before the stop starts.
        agent.attach(host.contextOf(h));
        synchronized (acceptLock) {
            if (image.hop() <= host.store.highestHop(image.id())) {
                return new Reply(Reply.Status.DUPLICATE, new byte[0]);
            }
            try {
                // Its stop begins as soon as it is stored (its runner is waiting, or is started just below):
                // stored and marked started in one durable write.
                host.store.acceptedStarting(image.id(), image.hop(), raw, offset, length);
                h.startStored = true;
            } catch (IOException e) {
                LOG.error("host {}: cannot store agent {}: {}; refusing it (the sender keeps it)", host.name, image.id(), e.toString());
                return Reply.of(Reply.Status.REFUSED, "host " + host.name + " cannot store the agent: " + e.getMessage());
            }
            host.hosted.put(h.id, h);
        }
        if (h.home.equals(host.address)) {
            // Back at its home: the handle is here, no news to send.
            AgentHandle handle = host.handles.get(h.id);
            if (handle != null) {
                handle.arrived(host.address);
            }
        } else if (!image.fromHome()) {
            // The home learns from the transfer's acknowledgement when it sent the agent itself;
            // otherwise it is told, once, as news (a later arrival makes an unsent one moot).
            owed.arrived(h);
        }
        host.activity.record(h.id, h.className, HostActivity.ARRIVED, host.address, "hop " + h.hop + " from " + peer);
        if (started != null) {
            started[0] = h;
        } else {
            host.runners.execute(() -> trips.runStop(h, false));
        }
        return Reply.ok();
    }
}
