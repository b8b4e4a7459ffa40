package io.robomw.agents.host.home;

import io.robomw.agents.host.HostAddress;
import io.robomw.agents.host.core.CodeLoaders;
import io.robomw.agents.host.core.HostState;
import io.robomw.agents.host.protocol.AgentEvent;
import io.robomw.agents.host.protocol.AgentImage;
import io.robomw.agents.host.protocol.Bodies;
import io.robomw.agents.host.protocol.Reply;
import io.robomw.agents.host.visit.HostedAgent;
import io.robomw.agents.host.visit.Trips;
import io.robomw.agents.host.code.CodeArchive;
import io.robomw.agents.host.code.StateCodec;
import io.robomw.agents.host.code.StateRejectedException;
import io.robomw.api.Agency;
import io.robomw.api.Agent;
import io.robomw.api.AgentException;
import io.robomw.api.AgentRef;
import io.robomw.api.AgentStatus;
import io.robomw.api.Itinerary;
import io.robomw.api.PartialDispatchException;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.io.ByteArrayInputStream;
import java.io.IOException;
import java.io.ObjectInputStream;
import java.io.ObjectStreamClass;
import java.io.Serializable;
import java.nio.charset.StandardCharsets;
import java.util.ArrayList;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Map;
import java.util.UUID;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.CompletionException;

/**
 * A host as the home of the agents sent from it (the {@link io.robomw.api.Agency} side): sends
 * new agents and clones to their first stop and keeps an {@link AgentHandle} for each, and hears
 * back from them: the events other hosts send ({@link #onEvent}) and a retracted agent coming
 * home ({@link #onHomecoming}).
 */
public final class Home implements Agency {

    private static final Logger LOG = LoggerFactory.getLogger(Home.class);

    private final HostState host;
    private final CodeLoaders code;
    private final Trips trips;
    private final AgentRequests requests;

    public Home(HostState host, CodeLoaders code, Trips trips, AgentRequests requests) {
        this.host = host;
        this.code = code;
        this.trips = trips;
        this.requests = requests;
    }

    @Override
    public AgentRef sendAgent(String to, Agent agent) {
        HostAddress.parse(to);
        agent.itinerary().insertNext(to, null);
        return startTrip(agent);
    }

    @Override
    public AgentRef startTrip(Agent agent) {
        if (agent.itinerary().stops().isEmpty()) {
            throw new IllegalArgumentException("agent " + agent.getClass().getName() + " has no stops in its itinerary");
        }
        agent.onCreation(null);
        return launch(agent, UUID.randomUUID());
    }

    @Override
    public List<AgentRef> dispatchClones(Agent agent, String... hosts) {
        for (String h : hosts) {
            HostAddress.parse(h);
        }
        agent.onCreation(null);
        byte[] state;
        try {
            state = StateCodec.write(agent);
        } catch (IOException e) {
            throw new AgentException("agent " + agent.getClass().getName() + " cannot be cloned: its state is not serializable: " + e.getMessage(), e);
        }
        List<CompletableFuture<AgentRef>> sends = new ArrayList<>();
        for (String h : hosts) {
            sends.add(CompletableFuture.supplyAsync(() -> {
                Agent clone = copy(state, agent.getClass().getClassLoader());
                clone.itinerary().clear();
                clone.itinerary().addStop(h);
                return launch(clone, UUID.randomUUID());
            }, host.requests));
        }
        List<AgentRef> refs = new ArrayList<>();
        Map<String, String> unsent = new LinkedHashMap<>();
        for (int i = 0; i < hosts.length; i++) {
            try {
                refs.add(sends.get(i).join());
            } catch (CompletionException e) {
                unsent.put(hosts[i], e.getCause().getMessage());
            }
        }
        if (unsent.isEmpty()) {
            return refs;
        }
        String why = unsent.entrySet().stream().map(e -> e.getKey() + ": " + e.getValue()).collect(java.util.stream.Collectors.joining("; "));
        if (refs.isEmpty()) {
            throw new AgentException("no clone of " + agent.getClass().getName() + " could be sent to its " + hosts.length + " hosts: " + why);
        }
        // The clones that went are travelling: their handles go with the exception, so the caller can still wait for them.
        throw new PartialDispatchException("clones of " + agent.getClass().getName() + " could not be sent to " + unsent.size() + " of " + hosts.length
                + " hosts; the other " + refs.size() + " were sent and travel: " + why, refs, unsent);
    }

    /** A copy of an agent from this process's own state: no filter, the bytes were made here. */
    private static Agent copy(byte[] state, ClassLoader loader) {
        try (ObjectInputStream in = new ObjectInputStream(new ByteArrayInputStream(state)) {
            @Override
            protected Class<?> resolveClass(ObjectStreamClass desc) throws IOException, ClassNotFoundException {
                return Class.forName(desc.getName(), false, loader);
            }
        }) {
            return (Agent) in.readObject();
        } catch (IOException | ClassNotFoundException e) {
            throw new AgentException("cannot copy agent state: " + e, e);
        }
    }

    /** A clone of an agent at this host, made by the agent itself, sent with its own plan; this host is its home. */
    public AgentRef cloneOf(HostedAgent parent, Itinerary plan) {
        Agent clone;
        try {
            clone = host.codec.read(StateCodec.write(parent.agent), parent.loader, Agent.class);
        } catch (IOException | StateRejectedException e) {
            throw new AgentException("agent " + parent.id + " cannot be cloned: " + e.getMessage(), e);
        }
        clone.itinerary().copyPlan(plan);
        return launch(clone, UUID.randomUUID());
    }

    /** Sends a new agent from here (its home) to its first reachable stop; blocks until that host has it. */
    private AgentRef launch(Agent agent, UUID id) {
        Class<?> type = agent.getClass();
        CodeArchive archive = code.archiveOf(type);
        AgentImage origin = new AgentImage(id, 0, AgentImage.Kind.TRIP, true, host.address, archive.digest(), 1, new byte[0]);
        HostedAgent h = new HostedAgent(origin, agent, type.getClassLoader());
        AgentHandle handle = new AgentHandle(requests, id, type.getName(), type.getClassLoader(), host.address);
        host.handles.put(id, handle);
        Trips.Departure d = trips.depart(h);
        if (d.delivered()) {
            handle.location(d.target());
            host.messaging.met(d.target());
            return handle;
        }
        host.handles.remove(id);
        throw new AgentException("agent " + type.getName() + " " + id + " could not be sent: " + d.reason());
    }

    /**
     * News of an agent sent from here: it arrived somewhere, reported, ended with a result,
     * failed, or was disposed of.
     *
     * @param peer the host that sends it
     * @param body the event, {@link AgentEvent#encode}
     * @return the reply (OK also for an event of an agent not sent from here: there is nothing to retry)
     */
    public Reply onEvent(String peer, byte[] body) {
        AgentEvent e;
        try {
            e = AgentEvent.decode(body);
        } catch (IllegalArgumentException ex) {
            return host.refuse("refused an event from peer '" + peer + "': " + ex.getMessage());
        }
        AgentHandle h = host.handles.get(e.id());
        if (h == null) {
            LOG.debug("host {}: {} for agent {} which was not sent from here; dropped", host.name, e.kind(), e.id());
            return Reply.ok();
        }
        switch (e.kind()) {
            case ARRIVED -> h.arrived(e.location());
            case VISITS -> {
                try {
                    h.history(Bodies.readVisits(e.payload()));
                } catch (IllegalArgumentException ex) {
                    host.refuse("dropped the visits of agent " + e.id() + " from peer '" + peer + "': " + ex.getMessage());
                }
            }
            case REPORT, RESULT -> {
                Serializable value;
                try {
                    value = host.codec.read(e.payload(), h.loader, Serializable.class);
                } catch (StateRejectedException ex) {
                    host.refuse("dropped a " + e.kind() + " of agent " + e.id() + " from peer '" + peer + "': " + ex.getMessage());
                    if (e.kind() == AgentEvent.Kind.RESULT) {
                        h.failed(e.location(), AgentStatus.FAILED, "ended at " + e.location() + " but its result was refused at home: " + ex.getMessage());
                    }
                    return Reply.ok();
                }
                if (e.kind() == AgentEvent.Kind.REPORT) {
                    h.report(e.seq(), e.location(), value);
                } else {
                    h.completed(e.location(), value);
                }
            }
            case FAILED -> h.failed(e.location(), AgentStatus.FAILED, new String(e.payload(), StandardCharsets.UTF_8));
            case DISPOSED -> h.failed(e.location(), AgentStatus.DISPOSED, new String(e.payload(), StandardCharsets.UTF_8));
        }
        return Reply.ok();
    }

    /**
     * News that agents sent from here arrived elsewhere, several in one call.
     *
     * @param peer the host that sends it
     * @param body {@link Bodies#arrivals}
     * @return the reply (OK also when some of the agents were not sent from here: there is nothing to retry)
     */
    public Reply onArrivals(String peer, byte[] body) {
        List<Bodies.Arrival> arrivals;
        try {
            arrivals = Bodies.readArrivals(body);
        } catch (IllegalArgumentException ex) {
            return host.refuse("refused arrivals from peer '" + peer + "': " + ex.getMessage());
        }
        for (Bodies.Arrival a : arrivals) {
            AgentHandle h = host.handles.get(a.id());
            if (h == null) {
                LOG.debug("host {}: arrival of agent {} which was not sent from here; dropped", host.name, a.id());
            } else {
                h.arrived(a.where());
            }
        }
        return Reply.ok();
    }

    /**
     * A retracted agent of this home comes back: its state completes the retract.
     *
     * @param peer  the host that sends it
     * @param image its image, decoded in place
     * @return the reply
     */
    public Reply onHomecoming(String peer, AgentImage image) {
        AgentHandle handle = host.handles.get(image.id());
        if (handle == null) {
            return host.refuse("refused homecoming agent " + image.id() + " from peer '" + peer + "': it was not sent from here");
        }
        try {
            Agent agent = host.codec.read(image.state(), image.stateOffset(), image.stateLength(), handle.loader, Agent.class);
            // Seen, so a repeat of this transfer is a duplicate; not held: the agent is back with its handle, not hosted here.
            host.store.accepted(image.id(), image.hop(), new byte[0], 0, 0);
            host.store.departed(image.id(), image.hop() + 1);
            handle.retracted(handle.location(), agent); // where it was last: the host that sent it home (peer is only its name)
            return Reply.ok();
        } catch (StateRejectedException | IOException e) {
            return host.refuse("refused homecoming agent " + image.id() + " from peer '" + peer + "': " + e.getMessage());
        }
    }
}
