package io.robomw.agents.host;

import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.util.Map;
import java.util.UUID;
import java.util.concurrent.BlockingQueue;
import java.util.concurrent.ConcurrentHashMap;
import java.util.concurrent.LinkedBlockingQueue;
import java.util.concurrent.TimeUnit;

/**
 * Carries events to agents' homes, one worker thread per home, in the order they were made.
 * Reports and results are retried until the home acknowledges them (with growing pauses, while
 * the host runs; the store keeps them across restarts); arrivals are sent once, as news, and an
 * arrival still queued when a newer one of the same agent is queued is dropped (the host does not
 * send one at all when the agent came from its home or arrived there: the home knows). An agent
 * leaves a host only after its reports from there are home ({@link #awaitDelivered}), so reports
 * arrive in order even when the agent moves faster than they do.
 */
final class HomeEvents implements AutoCloseable {

    private static final Logger LOG = LoggerFactory.getLogger(HomeEvents.class);
    private static final long MAX_BACKOFF_MILLIS = 5_000;

    /** Sends one event; throws if the home did not take it. */
    interface Sender {
        void deliver(String home, AgentEvent event) throws Exception;
    }

    /** Told when a durable event has been acknowledged. */
    interface Delivered {
        void delivered(AgentEvent event);
    }

    private record Outgoing(AgentEvent event, boolean reliable) {
    }

    private final String hostName;
    private final Sender sender;
    private final Delivered delivered;
    private final Map<String, Worker> workers = new ConcurrentHashMap<>();
    private final Map<UUID, Integer> outstanding = new ConcurrentHashMap<>();
    /** The newest queued arrival of each agent: an older one still queued is moot and not sent. */
    private final Map<UUID, Outgoing> latestArrival = new ConcurrentHashMap<>();
    private volatile boolean closed;

    HomeEvents(String hostName, Sender sender, Delivered delivered) {
        this.hostName = hostName;
        this.sender = sender;
        this.delivered = delivered;
    }

    /**
     * @param home     the agent's home
     * @param event    the event
     * @param reliable retry until acknowledged (reports, results) or send once (arrivals)
     */
    void send(String home, AgentEvent event, boolean reliable) {
        Outgoing o = new Outgoing(event, reliable);
        if (reliable) {
            outstanding.merge(event.id(), 1, Integer::sum);
        } else {
            latestArrival.put(event.id(), o);
        }
        workers.computeIfAbsent(home, Worker::new).queue.add(o);
    }

    /**
     * Waits until the agent's reliable events have been acknowledged, or the time is up.
     *
     * @param id        the agent
     * @param maxMillis the longest wait
     * @return whether they all were
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

    private void done(AgentEvent e) {
        synchronized (outstanding) {
            outstanding.computeIfPresent(e.id(), (k, n) -> n <= 1 ? null : n - 1);
            outstanding.notifyAll();
        }
    }

    @Override
    public void close() {
        closed = true;
        workers.values().forEach(w -> w.thread.interrupt());
        for (Worker w : workers.values()) {
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

    private final class Worker implements Runnable {
        final String home;
        final BlockingQueue<Outgoing> queue = new LinkedBlockingQueue<>();
        final Thread thread;

        Worker(String home) {
            this.home = home;
            this.thread = new Thread(this, "agent-events-" + hostName + "-to-" + HostAddress.parse(home).name());
            thread.setDaemon(true);
            thread.start();
        }

        @Override
        public void run() {
            while (!closed) {
                Outgoing o;
                try {
                    o = queue.poll(1, TimeUnit.SECONDS);
                } catch (InterruptedException e) {
                    return;
                }
                if (o == null) {
                    continue;
                }
                if (!o.reliable() && !latestArrival.remove(o.event().id(), o)) {
                    continue; // a newer arrival of the same agent is queued: this one is moot
                }
                long backoff = 50;
                while (!closed) {
                    try {
                        sender.deliver(home, o.event());
                        if (o.reliable()) {
                            delivered.delivered(o.event());
                            done(o.event());
                        }
                        break;
                    } catch (InterruptedException e) {
                        return;
                    } catch (Exception e) {
                        if (!o.reliable()) {
                            LOG.debug("host {}: arrival news for agent {} not delivered to {}: {}", hostName, o.event().id(), home, e.getMessage());
                            break;
                        }
                        LOG.warn("host {}: {} of agent {} not delivered to its home {} ({}); retrying in {} ms",
                                hostName, o.event().kind(), o.event().id(), home, e.getMessage(), backoff);
                        try {
                            Thread.sleep(backoff); // a retry pause, not a wait for a condition
                        } catch (InterruptedException ie) {
                            return;
                        }
                        backoff = Math.min(MAX_BACKOFF_MILLIS, backoff * 2);
                    }
                }
            }
        }
    }
}
