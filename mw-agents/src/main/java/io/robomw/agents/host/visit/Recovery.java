package io.robomw.agents.host.visit;

import io.robomw.agents.host.core.CodeLoaders;
import io.robomw.agents.host.core.HostState;
import io.robomw.agents.host.home.OwedEvents;
import io.robomw.agents.host.protocol.AgentImage;
import io.robomw.agents.host.protocol.Bodies;
import io.robomw.agents.host.code.StateRejectedException;
import io.robomw.agents.host.store.AgentStore;
import io.robomw.api.Agent;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.io.IOException;
import java.util.ArrayList;
import java.util.List;

/**
 * Resumes what a host's store held when it started: each agent where it stood (its stop not
 * started: run it; started: go on without running it again; departing: send it again to the same
 * host), and the events owed to homes.
 */
public final class Recovery {

    private static final Logger LOG = LoggerFactory.getLogger(Recovery.class);

    private final HostState host;
    private final CodeLoaders code;
    private final Trips trips;
    private final OwedEvents owed;

    public Recovery(HostState host, CodeLoaders code, Trips trips, OwedEvents owed) {
        this.host = host;
        this.code = code;
        this.trips = trips;
        this.owed = owed;
    }

    /**
     * Resumes the store's agents on runner threads and sends its owed events again. Everything is
     * read before anything resumes, so a store this host cannot read resumes nothing.
     *
     * @throws IOException naming the store if a stored agent's image or an owed event cannot be read
     *                     (an unknown code, or cut short): the store was written by another RoboMW, or damaged
     */
    public void resume() throws IOException {
        List<AgentStore.StoredAgent> stored = host.store.recoveredAgents();
        List<AgentImage> images = new ArrayList<>(stored.size());
        for (AgentStore.StoredAgent s : stored) {
            try {
                images.add(AgentImage.decode(s.image()));
            } catch (IllegalArgumentException e) {
                throw new IOException("agent store " + host.store.location() + ": the stored agent " + s.id() + " (" + s.phase()
                        + ") has an image this host cannot read: " + e.getMessage(), e);
            }
        }
        List<AgentStore.PendingEvent> pending = host.store.recoveredEvents();
        List<Bodies.OwedEvent> events = new ArrayList<>(pending.size());
        for (AgentStore.PendingEvent p : pending) {
            try {
                events.add(Bodies.readOwedEvent(p.event()));
            } catch (IllegalArgumentException e) {
                throw new IOException("agent store " + host.store.location() + ": event " + p.seq() + " owed to the home of agent " + p.id()
                        + " cannot be read: " + e.getMessage(), e);
            }
        }
        int accepted = 0;
        int interrupted = 0;
        int departing = 0;
        for (int i = 0; i < stored.size(); i++) {
            AgentStore.StoredAgent s = stored.get(i);
            AgentImage image = images.get(i);
            HostedAgent h;
            try {
                ClassLoader loader = code.loaderFor(image.digest())
                        .orElseThrow(() -> new StateRejectedException("its archive " + image.digest() + " is missing from the store"));
                h = new HostedAgent(image, host.codec.read(image.state(), image.stateOffset(), image.stateLength(), loader, Agent.class), loader);
            } catch (StateRejectedException | IOException e) {
                LOG.error("host {}: cannot resume agent {} from the store: {}", host.name, image.id(), e.getMessage());
                continue;
            }
            // Its image numbers its events from where they were when it arrived: events it owed since are numbered past that.
            h.eventSeq = Math.max(h.eventSeq, host.store.nextEventSeq(h.id));
            switch (s.phase()) {
                case ACCEPTED -> {
                    accepted++;
                    host.hosted.put(h.id, h);
                    host.runners.execute(() -> trips.runStop(h, false));
                }
                case STARTED -> {
                    interrupted++;
                    host.hosted.put(h.id, h);
                    host.runners.execute(() -> trips.runStop(h, true));
                }
                case DEPARTING -> {
                    departing++;
                    h.hop = image.hop() - 1;
                    host.hosted.put(h.id, h);
                    host.runners.execute(() -> trips.resumeDeparture(h, image));
                }
            }
        }
        for (int i = 0; i < events.size(); i++) {
            owed.resend(events.get(i), pending.get(i).owedSince());
        }
        if (accepted + interrupted + departing + events.size() > 0) {
            LOG.info("host {}: resumed {} agents from {} ({} not yet started, {} interrupted mid-stop, {} departing) and {} events owed to homes",
                    host.name, accepted + interrupted + departing, host.store.location(), accepted, interrupted, departing, events.size());
        }
    }
}
