package io.robomw.agents.host.home;

import io.robomw.agents.host.DeliveryPolicy;
import io.robomw.agents.host.OwedDelivery;
import io.robomw.agents.host.core.HostActivity;
import io.robomw.agents.host.core.HostState;
import io.robomw.agents.host.messaging.HostMessaging;
import io.robomw.agents.host.protocol.AgentEvent;
import io.robomw.agents.host.protocol.Bodies;
import io.robomw.agents.host.protocol.Op;
import io.robomw.agents.host.protocol.Reply;
import io.robomw.agents.host.rmi.Peers;
import io.robomw.agents.host.visit.HostedAgent;
import io.robomw.agents.host.code.StateCodec;
import io.robomw.agents.host.store.AgentStore;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.io.IOException;
import java.io.Serializable;
import java.util.ArrayList;
import java.util.List;
import java.util.Set;
import java.util.UUID;
import java.util.concurrent.ConcurrentHashMap;
import java.util.function.Predicate;

/**
 * What a host tells agents' homes: reports and results, kept in the store until the home
 * acknowledges them (or the delivery expires, or an operator drops it) and carried by
 * {@link HomeEvents}; and arrivals, sent once as news. They go to the home's own address over RMI,
 * or through a broker where the home is announced ({@link BrokerEvents}).
 * Thread-safe.
 */
public final class OwedEvents implements AutoCloseable {

    private static final Logger LOG = LoggerFactory.getLogger(OwedEvents.class);

    private final HostState host;
    private final Peers peers;
    private final HomeEvents events;
    /** Homes that refused {@link Op#ARRIVALS} (builds before it): sent one EVENT per arrival. */
    private final Set<String> singleArrivals = ConcurrentHashMap.newKeySet();

    public OwedEvents(HostState host, Peers peers, DeliveryPolicy policy) {
        this.host = host;
        this.peers = peers;
        this.events = new HomeEvents(host.name, policy, new HomeEvents.Sender() {
            @Override
            public void deliver(String home, AgentEvent event) throws Exception {
                OwedEvents.this.deliver(home, event);
            }

            @Override
            public void deliverArrivals(String home, List<AgentEvent> arrivals) throws Exception {
                OwedEvents.this.deliverArrivals(home, arrivals);
            }
        }, this::settled, host.failures);
    }

    /** Stores an event owed to a home (durably, with a journal) and sends it until the home has it. */
    public void owe(String home, AgentEvent event) {
        long now = System.currentTimeMillis();
        try {
            host.store.eventPending(new AgentStore.PendingEvent(event.id(), event.seq(), now, Bodies.owedEvent(home, event)));
        } catch (IOException ex) {
            LOG.warn("host {}: cannot store {} of agent {} ({}); sending it anyway", host.name, event.kind(), event.id(), ex.toString());
        }
        events.owe(home, event, now);
    }

    /** Sends an agent's report home, in order with its other reports and its result. */
    public void report(HostedAgent h, Serializable value) {
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
    public void arrived(HostedAgent h) {
        events.arrived(h.home, new AgentEvent(h.id, 0, AgentEvent.Kind.ARRIVED, host.address, new byte[0]));
    }

    /**
     * Sends again an event the store still owed when the host started.
     *
     * @param owed      the event and its home
     * @param owedSince when it was first owed, as stored
     */
    public void resend(Bodies.OwedEvent owed, long owedSince) {
        events.owe(owed.home(), owed.event(), owedSince);
    }

    /** @return what this host owes homes now, the oldest first */
    public List<OwedDelivery> owed() {
        return events.owed();
    }

    /**
     * @param which the deliveries to drop
     * @param why   why, for the log
     * @return the ones dropped
     */
    public List<OwedDelivery> drop(Predicate<OwedDelivery> which, String why) {
        return events.drop(which, why);
    }

    /** @return how many delivery threads run now */
    public int deliveryThreads() {
        return events.workers();
    }

    /**
     * Waits until the agent's reports from here are home (or dropped), or the time is up.
     *
     * @param id        the agent
     * @param maxMillis the longest wait
     */
    public void awaitDelivered(UUID id, long maxMillis) {
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

    /**
     * Sends arrivals in one ARRIVALS call; a home of a build before it (it refuses the operation) is
     * sent one EVENT each, then and from then on; a home announced at a broker, one event each through it.
     */
    private void deliverArrivals(String home, List<AgentEvent> arrivals) throws Exception {
        HostMessaging messaging = host.messaging;
        if ((messaging != null && messaging.brokerFor(home) != null) || singleArrivals.contains(home)) {
            deliverEach(home, arrivals);
            return;
        }
        List<Bodies.Arrival> body = new ArrayList<>(arrivals.size());
        for (AgentEvent a : arrivals) {
            body.add(new Bodies.Arrival(a.id(), a.location()));
        }
        Reply r = peers.call(home, Op.ARRIVALS, Bodies.arrivals(body));
        if (r.status() == Reply.Status.REFUSED && r.text().contains("unknown operation code " + Op.ARRIVALS.code())) {
            LOG.info("host {}: home {} does not take several arrivals in one call ({}); sending it one event each", host.name, home, r.text());
            singleArrivals.add(home);
            deliverEach(home, arrivals);
            return;
        }
        if (r.status() != Reply.Status.OK) {
            throw new IOException(home + " answered " + r.status() + " to " + arrivals.size() + " arrivals: " + r.text());
        }
    }

    private void deliverEach(String home, List<AgentEvent> arrivals) throws Exception {
        for (AgentEvent a : arrivals) {
            deliver(home, a);
        }
    }

    private void settled(AgentEvent event, boolean delivered) {
        try {
            host.store.eventDelivered(event.id(), event.seq());
        } catch (IOException e) {
            LOG.warn("host {}: cannot record that the {} of agent {} is no longer owed: {}", host.name, event.kind(), event.id(), e.toString());
        }
    }

    @Override
    public void close() {
        events.close();
    }
}
