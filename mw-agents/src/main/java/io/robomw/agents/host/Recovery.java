package io.robomw.agents.host;

import io.robomw.agents.host.code.StateRejectedException;
import io.robomw.agents.host.store.AgentStore;
import io.robomw.api.Agent;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.io.IOException;
import java.util.List;

/**
 * Resumes what a host's store held when it started: each agent where it stood (its stop not
 * started: run it; started: go on without running it again; departing: send it again to the same
 * host), and the events owed to homes.
 */
final class Recovery {

    private static final Logger LOG = LoggerFactory.getLogger(Recovery.class);

    private final HostState host;
    private final CodeLoaders code;
    private final Trips trips;
    private final OwedEvents owed;

    Recovery(HostState host, CodeLoaders code, Trips trips, OwedEvents owed) {
        this.host = host;
        this.code = code;
        this.trips = trips;
        this.owed = owed;
    }

    /**
     * Resumes the store's agents on runner threads and sends its owed events again.
     *
     * @param storeName the store, for the log
     */
    void resume(Object storeName) {
        int accepted = 0;
        int interrupted = 0;
        int departing = 0;
        for (AgentStore.StoredAgent s : host.store.recoveredAgents()) {
            AgentImage image = AgentImage.decode(s.image());
            HostedAgent h;
            try {
                ClassLoader loader = code.loaderFor(image.digest())
                        .orElseThrow(() -> new StateRejectedException("its archive " + image.digest() + " is missing from the store"));
                h = new HostedAgent(image, host.codec.read(image.state(), image.stateOffset(), image.stateLength(), loader, Agent.class), loader);
            } catch (StateRejectedException | IOException e) {
                LOG.error("host {}: cannot resume agent {} from the store: {}", host.name, image.id(), e.getMessage());
                continue;
            }
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
        List<AgentStore.PendingEvent> pending = host.store.recoveredEvents();
        for (AgentStore.PendingEvent p : pending) {
            owed.resend(Bodies.readOwedEvent(p.event()));
        }
        if (accepted + interrupted + departing + pending.size() > 0) {
            LOG.info("host {}: resumed {} agents from {} ({} not yet started, {} interrupted mid-stop, {} departing) and {} events owed to homes",
                    host.name, accepted + interrupted + departing, storeName, accepted, interrupted, departing, pending.size());
        }
    }
}
