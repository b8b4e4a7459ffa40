package io.robomw.agents.messaging;

import io.robomw.agents.messaging.spi.Channel;

import java.util.List;
import java.util.Map;
import java.util.concurrent.ConcurrentHashMap;

/**
 * Which peers want which topics' publications. A connection's subscriptions last until it closes;
 * a datagram peer's expire unless refreshed. Thread-safe.
 */
final class RemoteSubscribers {

    private final Map<String, Map<Channel, Long>> byTopic = new ConcurrentHashMap<>();
    /** The subscribers of each topic as a list, remade when they change: publishing reads it for every message. */
    private final Map<String, List<Channel>> lists = new ConcurrentHashMap<>();

    void subscribe(String topic, Channel channel) {
        Map<Channel, Long> channels = byTopic.computeIfAbsent(topic, t -> new ConcurrentHashMap<>());
        if (channels.put(channel, System.nanoTime()) == null) {
            remake(topic);
        }
    }

    void unsubscribe(String topic, Channel channel) {
        Map<Channel, Long> channels = byTopic.get(topic);
        if (channels != null && channels.remove(channel) != null) {
            remake(topic);
        }
    }

    void forget(Channel channel) {
        byTopic.forEach((topic, channels) -> {
            if (channels.remove(channel) != null) {
                remake(topic);
            }
        });
    }

    /** Forgets datagram subscriptions not refreshed since {@code nowNanos - maxAgeNanos}. */
    void expire(long nowNanos, long maxAgeNanos) {
        byTopic.forEach((topic, channels) -> {
            if (channels.entrySet().removeIf(e -> !e.getKey().isConnection() && nowNanos - e.getValue() > maxAgeNanos)) {
                remake(topic);
            }
        });
    }

    List<Channel> of(String topic) {
        List<Channel> l = lists.get(topic);
        return l == null ? List.of() : l;
    }

    private void remake(String topic) {
        synchronized (lists) {
            Map<Channel, Long> channels = byTopic.get(topic);
            lists.put(topic, channels == null ? List.of() : List.copyOf(channels.keySet()));
        }
    }

    int count(String topic) {
        Map<Channel, Long> channels = byTopic.get(topic);
        return channels == null ? 0 : (int) channels.keySet().stream().filter(Channel::isOpen).count();
    }
}
