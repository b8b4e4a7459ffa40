package io.robomw.agents.messaging;

import io.robomw.agents.messaging.spi.Channel;

import java.util.ArrayList;
import java.util.HashMap;
import java.util.HashSet;
import java.util.List;
import java.util.Map;
import java.util.Set;
import java.util.concurrent.ConcurrentHashMap;

/**
 * Which peers want which topics' publications. A connection's subscriptions last until it closes;
 * a datagram peer's expire unless refreshed. Bounded: a peer may hold at most
 * {@link PeerLimits#maxSubscriptionsPerPeer()} subscriptions and all peers together
 * {@link PeerLimits#maxSubscriptions()}; a topic nobody subscribes to any more is forgotten
 * entirely, so what a peer made the node hold is released when it unsubscribes, closes or expires.
 *
 * <p>Thread-safe: changes are serialised (they are rare); {@link #of} (every publication) reads a
 * concurrent map of immutable lists without locking.
 */
final class RemoteSubscribers {

    private final int maxPerPeer;
    private final int maxTotal;
    /** Guarded by {@code this}: subscriber to the time of its last (re)subscription, per topic. */
    private final Map<String, Map<Channel, Long>> byTopic = new HashMap<>();
    /** Guarded by {@code this}: the topics of each subscriber. */
    private final Map<Channel, Set<String>> byPeer = new HashMap<>();
    /** The subscribers of each topic as a list, remade when they change: publishing reads it for every message. */
    private final Map<String, List<Channel>> lists = new ConcurrentHashMap<>();
    private int total;
    /** Bumped after every change of {@link #lists}: a remembered list of an older version is not used. */
    private volatile int version;
    /** The list {@link #of} found last, for a stream of publications on one topic (the same String each time). */
    private volatile Recent recent;

    private record Recent(String topic, List<Channel> list, int version) {
    }

    RemoteSubscribers(PeerLimits limits) {
        this.maxPerPeer = limits.maxSubscriptionsPerPeer();
        this.maxTotal = limits.maxSubscriptions();
    }

    /**
     * Subscribes a peer, or refreshes its subscription.
     *
     * @return {@code null} if it is subscribed now, or why it was refused (a limit)
     */
    synchronized String subscribe(String topic, Channel channel, long nowNanos) {
        if (!channel.isOpen()) {
            // closed while this frame was handled: forget() has run or will find nothing to keep
            return null;
        }
        Map<Channel, Long> channels = byTopic.get(topic);
        if (channels != null && channels.replace(channel, nowNanos) != null) {
            return null;
        }
        Set<String> mine = byPeer.get(channel);
        if (mine != null && mine.size() >= maxPerPeer) {
            return "the peer already subscribes to " + mine.size() + " topics, the most one peer may (maxSubscriptionsPerPeer)";
        }
        if (total >= maxTotal) {
            return "peers already hold " + total + " subscriptions here, the most this node keeps (maxSubscriptions)";
        }
        byTopic.computeIfAbsent(topic, t -> new HashMap<>()).put(channel, nowNanos);
        byPeer.computeIfAbsent(channel, c -> new HashSet<>()).add(topic);
        total++;
        remake(topic);
        return null;
    }

    synchronized void unsubscribe(String topic, Channel channel) {
        Set<String> mine = byPeer.get(channel);
        if (mine != null && mine.remove(topic)) {
            if (mine.isEmpty()) {
                byPeer.remove(channel);
            }
            removeFromTopic(topic, channel);
        }
    }

    /** Forgets every subscription of a channel (it closed). */
    synchronized void forget(Channel channel) {
        Set<String> mine = byPeer.remove(channel);
        if (mine != null) {
            for (String topic : mine) {
                removeFromTopic(topic, channel);
            }
        }
    }

    /** Forgets datagram subscriptions not refreshed since {@code nowNanos - maxAgeNanos}. */
    synchronized void expire(long nowNanos, long maxAgeNanos) {
        for (Channel c : new ArrayList<>(byPeer.keySet())) {
            if (c.isConnection()) {
                continue;
            }
            for (String topic : new ArrayList<>(byPeer.get(c))) {
                Long at = byTopic.get(topic).get(c);
                if (nowNanos - at > maxAgeNanos) {
                    unsubscribe(topic, c);
                }
            }
        }
    }

    List<Channel> of(String topic) {
        Recent r = recent;
        int v = version;
        if (r != null && r.topic == topic && r.version == v) {
            return r.list; // no hashing and comparing of the topic's text
        }
        List<Channel> l = lists.get(topic);
        if (l == null) {
            l = List.of();
        }
        recent = new Recent(topic, l, v);
        return l;
    }

    synchronized int count(String topic) {
        Map<Channel, Long> channels = byTopic.get(topic);
        return channels == null ? 0 : (int) channels.keySet().stream().filter(Channel::isOpen).count();
    }

    /** @return how many subscriptions all peers hold together */
    synchronized int total() {
        return total;
    }

    /** @return how many topics have subscribers (each kept topic costs memory; none is kept without one) */
    synchronized int topics() {
        return byTopic.size();
    }

    private void removeFromTopic(String topic, Channel channel) {
        Map<Channel, Long> channels = byTopic.get(topic);
        if (channels != null && channels.remove(channel) != null) {
            total--;
            if (channels.isEmpty()) {
                byTopic.remove(topic);
            }
            remake(topic);
        }
    }

    private void remake(String topic) {
        Map<Channel, Long> channels = byTopic.get(topic);
        if (channels == null) {
            lists.remove(topic);
        } else {
            lists.put(topic, List.copyOf(channels.keySet()));
        }
        version++; // guarded by this; volatile, so a reader that sees the new version sees the new list
    }
}
