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

    void subscribe(String topic, Channel channel) {
        byTopic.computeIfAbsent(topic, t -> new ConcurrentHashMap<>()).put(channel, System.nanoTime());
    }

    void unsubscribe(String topic, Channel channel) {
        Map<Channel, Long> channels = byTopic.get(topic);
        if (channels != null) {
            channels.remove(channel);
        }
    }

    void forget(Channel channel) {
        byTopic.values().forEach(channels -> channels.remove(channel));
    }

    /** Forgets datagram subscriptions not refreshed since {@code nowNanos - maxAgeNanos}. */
    void expire(long nowNanos, long maxAgeNanos) {
        byTopic.values().forEach(channels -> channels.entrySet()
                .removeIf(e -> !e.getKey().isConnection() && nowNanos - e.getValue() > maxAgeNanos));
    }

    List<Channel> of(String topic) {
        Map<Channel, Long> channels = byTopic.get(topic);
        return channels == null ? List.of() : List.copyOf(channels.keySet());
    }

    int count(String topic) {
        Map<Channel, Long> channels = byTopic.get(topic);
        return channels == null ? 0 : (int) channels.keySet().stream().filter(Channel::isOpen).count();
    }
}
