package io.robomw.console.rosbridge.graph;

import com.fasterxml.jackson.databind.node.ObjectNode;
import io.robomw.console.rosbridge.msg.MessageType;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.util.List;
import java.util.Set;
import java.util.concurrent.ConcurrentHashMap;
import java.util.concurrent.CopyOnWriteArrayList;
import java.util.function.Consumer;

/**
 * One topic of the bridge's graph: its name and type, who publishes on it (the nodes rosapi
 * lists), and who receives it. A publication goes to every listener on the publishing thread.
 * A latched topic ({@code /tf_static}, or one a client advertised with {@code latch: true}) keeps
 * its last message and gives it to each new subscriber, as a transient-local ROS 2 publisher does.
 *
 * <p>Demand: whoever produces the topic's messages (a robot's odometry, a sensor) can watch
 * whether anyone subscribes ({@link #onDemand}), so nothing is sampled or encoded for nobody.
 * Thread-safe.
 */
public final class Topic {

    private static final Logger LOG = LoggerFactory.getLogger(Topic.class);

    private final String name;
    private final MessageType type;
    private final boolean latched;
    private final java.util.Map<String, Integer> publishers = new ConcurrentHashMap<>();
    private final java.util.Map<TopicListener, String> receiverNodes = new ConcurrentHashMap<>();
    private final List<TopicListener> listeners = new CopyOnWriteArrayList<>();
    private final List<TopicListener> internal = new CopyOnWriteArrayList<>();
    private final List<Consumer<Boolean>> demandWatchers = new CopyOnWriteArrayList<>();
    private volatile Publication last;

    Topic(String name, MessageType type, boolean latched) {
        this.name = name;
        this.type = type;
        this.latched = latched;
    }

    /** @return its name, absolute ({@code /nxt/odom}) */
    public String name() {
        return name;
    }

    /** @return its message type */
    public MessageType type() {
        return type;
    }

    /** @return whether new subscribers get its last message */
    public boolean latched() {
        return latched;
    }

    /**
     * Publishes a message to every listener.
     *
     * @param msg the message, complete for the topic's type; not changed afterwards
     * @return the publication
     */
    public Publication publish(ObjectNode msg) {
        Publication p = new Publication(name, msg, System.nanoTime());
        if (latched) {
            last = p;
        }
        for (TopicListener l : internal) {
            deliver(l, p);
        }
        for (TopicListener l : listeners) {
            deliver(l, p);
        }
        return p;
    }

    private void deliver(TopicListener l, Publication p) {
        try {
            l.deliver(p);
        } catch (RuntimeException e) {
            LOG.warn("rosbridge: a receiver of {} failed on a message and keeps receiving: {}", name, e.toString(), e);
        }
    }

    /** @return whether any client subscribes */
    public boolean hasSubscribers() {
        return !listeners.isEmpty();
    }

    /**
     * Adds a client's subscription; a latched topic hands it its last message at once.
     *
     * @param listener the subscription
     * @param node     the subscribing node's name, as rosapi lists subscribers
     */
    public synchronized void subscribe(TopicListener listener, String node) {
        boolean first = listeners.isEmpty();
        listeners.add(listener);
        receiverNodes.put(listener, node);
        Publication l = last;
        if (l != null) {
            deliver(listener, l);
        }
        if (first) {
            demandChanged(true);
        }
    }

    /**
     * @param listener a subscription added before
     */
    public synchronized void unsubscribe(TopicListener listener) {
        receiverNodes.remove(listener);
        if (listeners.remove(listener) && listeners.isEmpty()) {
            demandChanged(false);
        }
    }

    /**
     * Adds a receiver inside the bridge (a robot's cmd_vel, a messaging topic). It does not count
     * as demand.
     *
     * @param listener the receiver
     * @param node     the node it stands for
     */
    public void addSink(TopicListener listener, String node) {
        internal.add(listener);
        receiverNodes.put(listener, node);
    }

    /**
     * @param listener a receiver added before
     */
    public void removeSink(TopicListener listener) {
        internal.remove(listener);
        receiverNodes.remove(listener);
    }

    /** @return whether anything receives it: a client or a sink */
    public boolean received() {
        return !listeners.isEmpty() || !internal.isEmpty();
    }

    /**
     * @param watcher told {@code true} when the first client subscribes and {@code false} when the
     *                last one leaves; told the current state at once
     */
    public synchronized void onDemand(Consumer<Boolean> watcher) {
        demandWatchers.add(watcher);
        watcher.accept(hasSubscribers());
    }

    private void demandChanged(boolean demanded) {
        for (Consumer<Boolean> w : demandWatchers) {
            try {
                w.accept(demanded);
            } catch (RuntimeException e) {
                LOG.warn("rosbridge: the producer of {} failed to {} sampling: {}", name, demanded ? "start" : "stop", e.toString(), e);
            }
        }
    }

    /**
     * @param node a node that publishes on it; a node may be added more than once (several
     *             clients' advertisements all belong to the bridge's node), and stays a publisher
     *             until removed as often
     */
    public void addPublisher(String node) {
        publishers.merge(node, 1, Integer::sum);
    }

    /** @param node a node that publishes on it one time less */
    public void removePublisher(String node) {
        publishers.computeIfPresent(node, (k, n) -> n <= 1 ? null : n - 1);
    }

    /** @return the nodes that publish on it */
    public Set<String> publishers() {
        return Set.copyOf(publishers.keySet());
    }

    /** @return the nodes that receive it */
    public Set<String> subscribers() {
        return Set.copyOf(receiverNodes.values());
    }

    /** @return whether no one publishes on it and nothing receives it */
    boolean abandoned() {
        return publishers.isEmpty() && listeners.isEmpty() && internal.isEmpty();
    }
}
