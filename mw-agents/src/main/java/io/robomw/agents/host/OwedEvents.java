package io.robomw.agents.host;

import io.robomw.agents.host.code.StateCodec;
import io.robomw.agents.host.store.AgentStore;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.io.IOException;
import java.io.Serializable;
import java.util.UUID;

/**
 * What a host tells agents' homes: reports and results, kept in the store until the home
 * acknowledges them and carried by {@link HomeEvents}; and arrivals, sent once as news. They go
 * to the home's own address over RMI, or through a broker where the home is announced
 * ({@link BrokerEvents}).
 * Thread-safe.
 */
final class OwedEvents implements AutoCloseable {

    private static final Logger LOG = LoggerFactory.getLogger(OwedEvents.class);

    private final HostState host;
    private final Peers peers;
    private final HomeEvents events;

    OwedEvents(HostState host, Peers peers) {
        this.host = host;
        this.peers = peers;
        this.events = new HomeEvents(host.name, this::deliver, this::delivered);
    }

    /** Stores an event owed to a home (durably, with a journal) and sends it until the home has it. */
    void owe(String home, AgentEvent event) {
        try {
            host.store.eventPending(new AgentStore.PendingEvent(event.id(), event.seq(), Bodies.owedEvent(home, event)));
        } catch (IOException ex) {
            LOG.warn("host {}: cannot store {} of agent {} ({}); sending it anyway", host.name, event.kind(), event.id(), ex.toString());
        }
        events.send(home, event, true);
    }

    /** Sends an agent's report home, in order with its other reports and its result. */
    void report(HostedAgent h, Serializable value) {
        byte[] payload;
        try {
            payload = StateCodec.write(value);
        } catch (IOException e) {
            throw new IllegalArgumentException("report value of agent " + h.id + " is not serializable: " + e.getMessage(), e);
        }
        host.activity.record(h.id, h.className, HostActivity.REPORT, host.address, HostActivity.describe(value));
        long seq;
        synchronized (h) {
            seq = h.eventSeq++;
        }
        owe(h.home, new AgentEvent(h.id, seq, AgentEvent.Kind.REPORT, host.address, payload));
    }

    /** Tells an agent's home, once, that it arrived here (a later arrival makes an unsent one moot). */
    void arrived(HostedAgent h) {
        events.send(h.home, new AgentEvent(h.id, 0, AgentEvent.Kind.ARRIVED, host.address, new byte[0]), false);
    }

    /** Sends again an event the store still owed when the host started. */
    void resend(Bodies.OwedEvent owed) {
        events.send(owed.home(), owed.event(), true);
    }

    /**
     * Waits until the agent's reports from here are home, or the time is up.
     *
     * @param id        the agent
     * @param maxMillis the longest wait
     */
    void awaitDelivered(UUID id, long maxMillis) {
        events.awaitDelivered(id, maxMillis);
    }

    private void deliver(String home, AgentEvent event) throws Exception {
        HostMessaging messaging = host.messaging;
        String broker = messaging == null ? null : messaging.brokerFor(home);
        if (broker != null) {
            messaging.deliverThroughBroker(broker, home, event);
            return;
        }
        Reply r = peers.call(home, Op.EVENT, event.encode());
        if (r.status() != Reply.Status.OK) {
            throw new IOException(home + " answered " + r.status() + ": " + r.text());
        }
    }

    private void delivered(AgentEvent event) {
        try {
            host.store.eventDelivered(event.id(), event.seq());
        } catch (IOException e) {
            LOG.warn("host {}: cannot record an event delivered: {}", host.name, e.toString());
        }
    }

    @Override
    public void close() {
        events.close();
    }
}
