package io.robomw.agents.host.home;

import io.robomw.agents.host.DeliveryPolicy;
import io.robomw.agents.host.HostAddress;
import io.robomw.agents.host.OwedDelivery;
import io.robomw.agents.host.protocol.AgentEvent;
import io.robomw.agents.net.OwnerThreads;
import io.robomw.api.spi.FailurePolicy;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.time.Duration;
import java.time.Instant;
import java.util.ArrayDeque;
import java.util.ArrayList;
import java.util.Comparator;
import java.util.HashMap;
import java.util.List;
import java.util.Map;
import java.util.UUID;
import java.util.concurrent.ConcurrentHashMap;
import java.util.concurrent.atomic.AtomicBoolean;
import java.util.function.Predicate;

/**
 * Carries events to agents' homes, one worker thread per home, in the order they were made.
 *
 * <p><b>Reliable events</b> (reports and results) are retried until the home acknowledges them,
 * with pauses that double up to the {@link DeliveryPolicy}'s longest back-off, and given up once
 * owed longer than its expiry (the store keeps them across restarts, with the time they were first
 * owed). An operator can list them ({@link #owed()}) and drop them ({@link #drop}). A home that does
 * not answer is logged once, then at most once per the policy's log interval while it still does
 * not, and once when it answers again: not at every retry.
 *
 * <p><b>Arrivals</b> are sent once, as news; an arrival still queued when a newer one of the same
 * agent is queued is dropped (the host does not send one at all when the agent came from its home
 * or arrived there: the home knows). The arrivals queued one after another for a home go in one
 * call ({@link Sender#deliverArrivals}, at most {@link #MAX_ARRIVALS_PER_CALL}), sent as soon as
 * the worker is free: nothing waits to fill a batch, but those that queue while a call is on its
 * way go together in the next (with a thousand agents hopping, dozens a call instead of a call
 * each). A reliable event queued between arrivals is sent in its place in the order.
 *
 * <p>An agent leaves a host only after its reports from there are home ({@link #awaitDelivered}),
 * so reports arrive in order even when the agent moves faster than they do.
 *
 * <p>A worker ends when its home has had nothing queued for {@link #IDLE_MILLIS}, so a host that
 * served many short-lived homes (each {@code mw dispatch} is one) keeps no thread for them.
 * Workers are never interrupted (an interrupt would break a journal write they make); they wait on
 * their own monitor, which {@link #close} and {@link #drop} notify. Thread-safe.
 */
final class HomeEvents implements AutoCloseable {

    private static final Logger LOG = LoggerFactory.getLogger(HomeEvents.class);
    /** How long a worker waits with nothing to deliver before it ends. */
    static final long IDLE_MILLIS = 10_000;

    /** The most arrivals sent to a home in one call. */
    static final int MAX_ARRIVALS_PER_CALL = 256;

    /** Sends events to a home. */
    interface Sender {
        /** Sends one event; throws if the home did not take it. */
        void deliver(String home, AgentEvent event) throws Exception;

        /**
         * Sends arrivals, news sent once (by default one {@link #deliver} each).
         *
         * @param arrivals 1 to {@link #MAX_ARRIVALS_PER_CALL} arrivals, in the order they were made
         * @throws Exception if the home did not take them (they are not sent again)
         */
        default void deliverArrivals(String home, List<AgentEvent> arrivals) throws Exception {
            for (AgentEvent a : arrivals) {
                deliver(home, a);
            }
        }
    }

    /** Told when a reliable event is no longer owed: the home acknowledged it, or it was dropped or given up. */
    interface Settled {
        void settled(AgentEvent event, boolean delivered);
    }

    /** One reliable event owed to a home. */
    private static final class Owed {
        final String home;
        final AgentEvent event;
        final long owedSince;
        final AtomicBoolean settled = new AtomicBoolean();
        volatile int attempts;
        volatile String lastError = "";

        Owed(String home, AgentEvent event, long owedSince) {
            this.home = home;
            this.event = event;
            this.owedSince = owedSince;
        }

        OwedDelivery view() {
            return new OwedDelivery(event.id(), event.seq(), event.kind().name(), home, Instant.ofEpochMilli(owedSince), attempts, lastError);
        }
    }

    private record Key(UUID id, long seq) {
    }

    /** One queued send: a reliable event, or an arrival sent once. */
    private record Outgoing(Owed owed, AgentEvent arrival) {
    }

    private final String hostName;
    private final Sender sender;
    private final Settled settled;
    private final DeliveryPolicy policy;
    private final FailurePolicy failures;
    /** The workers, one per home with something queued; guarded by itself. */
    private final Map<String, Worker> workers = new HashMap<>();
    private final Map<Key, Owed> owed = new ConcurrentHashMap<>();
    private final Map<UUID, Integer> outstanding = new ConcurrentHashMap<>();
    /** The newest queued arrival of each agent: an older one still queued is moot and not sent. */
    private final Map<UUID, Outgoing> latestArrival = new ConcurrentHashMap<>();
    private volatile boolean closed;

    /**
     * @param failures where a delivery thread's failure goes (its deliveries are taken over by a new one)
     */
    HomeEvents(String hostName, DeliveryPolicy policy, Sender sender, Settled settled, FailurePolicy failures) {
        this.hostName = hostName;
        this.failures = failures;
        this.policy = policy;
        this.sender = sender;
        this.settled = settled;
    }

    /**
     * Owes a home a report or result until it acknowledges it, or the delivery expires or is dropped.
     *
     * @param home      the agent's home
     * @param event     the event
     * @param owedSince when it was first owed (ms since the epoch; earlier than now for one resumed from the store)
     */
    void owe(String home, AgentEvent event, long owedSince) {
        Owed o = new Owed(home, event, owedSince);
        if (owed.putIfAbsent(new Key(event.id(), event.seq()), o) != null) {
            return; // already owed
        }
        outstanding.merge(event.id(), 1, Integer::sum);
        enqueue(home, new Outgoing(o, null));
    }

    /** Tells a home, once, that its agent arrived here. */
    void arrived(String home, AgentEvent arrival) {
        Outgoing o = new Outgoing(null, arrival);
        latestArrival.put(arrival.id(), o);
        enqueue(home, o);
    }

    private void enqueue(String home, Outgoing o) {
        synchronized (workers) {
            Worker w = workers.get(home);
            if (w == null) {
                w = new Worker(home);
                workers.put(home, w);
                w.thread.start();
            }
            w.add(o);
        }
    }

    /** @return what this host owes homes now, the oldest first */
    List<OwedDelivery> owed() {
        return owed.values().stream().sorted(Comparator.comparingLong((Owed o) -> o.owedSince).thenComparing(o -> o.event.seq()))
                .map(Owed::view).toList();
    }

    /**
     * Drops owed deliveries: the host stops trying and forgets them (its store too).
     *
     * @param which the ones to drop
     * @param why   why, for the log
     * @return the ones dropped
     */
    List<OwedDelivery> drop(Predicate<OwedDelivery> which, String why) {
        List<OwedDelivery> dropped = new ArrayList<>();
        for (Owed o : List.copyOf(owed.values())) {
            OwedDelivery v = o.view();
            if (which.test(v) && settle(o, false)) {
                dropped.add(v);
                LOG.warn("host {}: dropped the {} of agent {} (event {}) owed to {} since {} ({})", hostName, o.event.kind(), o.event.id(),
                        o.event.seq(), o.home, v.owedSince(), why);
            }
        }
        synchronized (workers) {
            workers.values().forEach(Worker::wake);
        }
        return dropped;
    }

    /**
     * Waits until the agent's reliable events are no longer owed, or the time is up.
     *
     * @param id        the agent
     * @param maxMillis the longest wait
     * @return whether they all were delivered or dropped
     */
    boolean awaitDelivered(UUID id, long maxMillis) {
        if (!outstanding.containsKey(id)) {
            return true; // the usual case, without the lock
        }
        long deadline = System.nanoTime() + maxMillis * 1_000_000;
        synchronized (outstanding) {
            while (outstanding.containsKey(id)) {
                long left = deadline - System.nanoTime();
                if (left <= 0 || closed) {
                    return false;
                }
                try {
                    outstanding.wait(Math.max(1, left / 1_000_000));
                } catch (InterruptedException e) {
                    Thread.currentThread().interrupt();
                    return false;
                }
            }
        }
        return true;
    }

    /** @return whether this call settled it (false if it already was) */
    private boolean settle(Owed o, boolean delivered) {
        if (!o.settled.compareAndSet(false, true)) {
            return false;
        }
        owed.remove(new Key(o.event.id(), o.event.seq()), o);
        settled.settled(o.event, delivered);
        synchronized (outstanding) {
            outstanding.computeIfPresent(o.event.id(), (k, n) -> n <= 1 ? null : n - 1);
            outstanding.notifyAll();
        }
        return true;
    }

    /** @return how many workers run now (one per home with something queued, until idle) */
    int workers() {
        synchronized (workers) {
            return workers.size();
        }
    }

    @Override
    public void close() {
        closed = true;
        List<Worker> all;
        synchronized (workers) {
            all = List.copyOf(workers.values());
        }
        all.forEach(Worker::wake);
        for (Worker w : all) {
            try {
                w.thread.join(2_000);
            } catch (InterruptedException e) {
                Thread.currentThread().interrupt();
            }
        }
        synchronized (outstanding) {
            outstanding.notifyAll();
        }
    }

    /** Delivers one home's events in order; logs its failures once per interval. */
    private final class Worker implements Runnable {
        final String home;
        final Thread thread;
        /** Guarded by this worker. */
        private final ArrayDeque<Outgoing> queue = new ArrayDeque<>();
        /** Whether the home failed the last try (for logging once per interval). */
        private boolean failing;
        private long nextLogNanos;
        /** The send being made (owned by the worker's thread). */
        private Outgoing current;

        Worker(String home) {
            this.home = home;
            // run() catches whatever ends it, in one place
            this.thread = OwnerThreads.thread("agent-events-" + hostName + "-to-" + HostAddress.parse(home).name(), this, failures);
        }

        synchronized void add(Outgoing o) {
            queue.add(o);
            notifyAll();
        }

        synchronized void wake() {
            notifyAll();
        }

        /** @return the next send, or null once the worker should end (closed, or idle and removed) */
        private Outgoing next() {
            long idleUntil = System.nanoTime() + IDLE_MILLIS * 1_000_000;
            while (!closed) {
                synchronized (this) {
                    Outgoing o = queue.poll();
                    if (o != null) {
                        return o;
                    }
                    long left = idleUntil - System.nanoTime();
                    if (left > 0) {
                        pause(left);
                        continue;
                    }
                }
                synchronized (workers) {
                    synchronized (this) {
                        if (queue.isEmpty()) {
                            workers.remove(home, this);
                            return null;
                        }
                    }
                }
            }
            return null;
        }

        /** Waits on this worker's monitor (held by the caller) for up to {@code nanos}; close, drop and new events wake it. */
        private void pause(long nanos) {
            try {
                wait(Math.max(1, nanos / 1_000_000));
            } catch (InterruptedException e) {
                Thread.currentThread().interrupt(); // not expected: workers are woken, not interrupted
            }
        }

        @Override
        public void run() {
            try {
                for (Outgoing o = next(); o != null; o = next()) {
                    current = o;
                    if (o.owed() == null) {
                        sendArrivals(o);
                    } else {
                        deliver(o.owed());
                    }
                }
            } catch (Throwable t) {
                LOG.warn("host {}: the delivery thread to {} failed ({}); a new one takes over its deliveries", hostName, home, t.toString());
                failures.died(thread.getName(), t);
                List<Outgoing> left;
                synchronized (workers) {
                    workers.remove(home, this);
                    synchronized (this) {
                        left = new ArrayList<>();
                        if (current != null && current.owed() != null && !current.owed().settled.get()) {
                            left.add(current);
                        }
                        left.addAll(queue);
                        queue.clear();
                    }
                }
                if (!closed) {
                    left.forEach(o -> enqueue(home, o));
                }
            }
        }

        /** Sends an arrival and those queued right after it (up to the next reliable event), in one call. */
        private void sendArrivals(Outgoing first) {
            List<AgentEvent> batch = new ArrayList<>();
            if (latestArrival.remove(first.arrival().id(), first)) {
                batch.add(first.arrival());
            } // else a newer arrival of the same agent is queued: this one is moot
            synchronized (this) {
                for (Outgoing o = queue.peek(); o != null && o.owed() == null && batch.size() < MAX_ARRIVALS_PER_CALL; o = queue.peek()) {
                    queue.poll();
                    if (latestArrival.remove(o.arrival().id(), o)) {
                        batch.add(o.arrival());
                    }
                }
            }
            if (batch.isEmpty()) {
                return;
            }
            try {
                sender.deliverArrivals(home, batch);
            } catch (Throwable e) {
                OwnerThreads.rethrowFatal(e);
                LOG.debug("host {}: arrival news for {} agents (the first {}) not delivered to {}: {}", hostName, batch.size(), batch.get(0).id(), home,
                        e.getMessage());
            }
        }

        private void deliver(Owed o) {
            long backoffMillis = DeliveryPolicy.FIRST_BACKOFF.toMillis();
            while (!closed && !o.settled.get()) {
                long age = System.currentTimeMillis() - o.owedSince;
                if (age > policy.expiry().toMillis()) {
                    if (settle(o, false)) {
                        LOG.warn("host {}: gave up delivering the {} of agent {} (event {}) to its home {}: owed for {}, longer than the delivery"
                                + " expiry {} ({} tries, the last: {}); it is dropped", hostName, o.event.kind(), o.event.id(), o.event.seq(), home,
                                Duration.ofMillis(age), policy.expiry(), o.attempts, o.lastError);
                    }
                    return;
                }
                try {
                    sender.deliver(home, o.event);
                    if (settle(o, true) && failing) {
                        failing = false;
                        LOG.info("host {}: home {} takes deliveries again", hostName, home);
                    }
                    return;
                } catch (Throwable e) {
                    OwnerThreads.rethrowFatal(e); // anything else is the home's failure to take it: tried again
                    o.attempts++;
                    o.lastError = e.getMessage() != null ? e.getMessage() : e.toString();
                    logFailure(o);
                    long until = System.nanoTime() + backoffMillis * 1_000_000;
                    synchronized (this) {
                        for (long left = until - System.nanoTime(); left > 0 && !closed && !o.settled.get(); left = until - System.nanoTime()) {
                            pause(left);
                        }
                    }
                    backoffMillis = Math.min(policy.maxBackoff().toMillis(), backoffMillis * 2);
                }
            }
        }

        private void logFailure(Owed o) {
            long now = System.nanoTime();
            if (failing && now - nextLogNanos < 0) {
                return;
            }
            long owedHere = owed.values().stream().filter(x -> x.home.equals(home)).count();
            LOG.warn("host {}: home {} {} ({}); {} deliveries owed to it, the oldest since {}; retrying with pauses up to {}, each given up after {}",
                    hostName, home, failing ? "still does not take deliveries" : "does not take deliveries", o.lastError, owedHere,
                    Instant.ofEpochMilli(owed.values().stream().filter(x -> x.home.equals(home)).mapToLong(x -> x.owedSince).min().orElse(o.owedSince)),
                    policy.maxBackoff(), policy.expiry());
            failing = true;
            nextLogNanos = now + policy.logInterval().toNanos();
        }
    }
}
