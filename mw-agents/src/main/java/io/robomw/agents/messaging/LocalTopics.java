package io.robomw.agents.messaging;

import io.robomw.agents.messaging.security.TopicKeys;
import io.robomw.api.MessageListener;
import io.robomw.api.MessagingException;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import javax.crypto.SecretKey;
import java.util.List;
import java.util.Map;
import java.util.concurrent.ConcurrentHashMap;
import java.util.concurrent.CopyOnWriteArrayList;

/**
 * The topics this node receives: each with its key (fixed by the first registration, with or
 * without a password), its listeners, and whether it is subscribed to publications. A later
 * registration with another password is refused and logged. Thread-safe.
 */
final class LocalTopics {

    private static final Logger LOG = LoggerFactory.getLogger(LocalTopics.class);

    /** One topic. {@code key} is {@code null} for an open topic. */
    static final class Topic {
        final String name;
        final SecretKey key;
        final List<MessageListener> listeners = new CopyOnWriteArrayList<>();
        volatile boolean subscribed;

        Topic(String name, SecretKey key) {
            this.name = name;
            this.key = key;
        }
    }

    private final String node;
    private final Map<String, Topic> topics = new ConcurrentHashMap<>();

    LocalTopics(String node) {
        this.node = node;
    }

    /**
     * @param topic a topic
     * @param key   the key of the password given, or {@code null}
     * @return the topic, registered with that key if it was new
     * @throws MessagingException if the topic is registered with another password (or without one)
     */
    Topic register(String topic, SecretKey key) {
        Topic t = topics.computeIfAbsent(topic, name -> new Topic(name, key));
        requireKey(t, key);
        return t;
    }

    /**
     * Registers a listener (and the topic, with that key, if it was new), atomically with
     * {@link #unlisten}: a topic is never forgotten while a listener is being added to it.
     *
     * @param topic    a topic
     * @param key      the key of the password given, or {@code null}
     * @param listener the listener
     * @throws MessagingException if the topic is registered with another password (or without one)
     */
    void listen(String topic, SecretKey key, MessageListener listener) {
        topics.compute(topic, (name, t) -> {
            Topic topicNow = t != null ? t : new Topic(name, key);
            requireKey(topicNow, key);
            topicNow.listeners.add(listener);
            return topicNow;
        });
    }

    /**
     * Removes a listener; a topic left with no listener and no subscription is forgotten, so that
     * it is no longer listed ({@code mw topics}) and a message to it is refused at once.
     *
     * @param topic    a topic
     * @param listener the listener
     */
    void unlisten(String topic, MessageListener listener) {
        topics.computeIfPresent(topic, (name, t) -> {
            t.listeners.remove(listener);
            return t.listeners.isEmpty() && !t.subscribed ? null : t;
        });
    }

    /**
     * @param topic a topic
     * @param key   the key a sender used
     * @throws MessagingException if the topic is registered here with another password
     */
    void checkIfRegistered(String topic, SecretKey key) {
        Topic t = topics.get(topic);
        if (t != null) {
            requireKey(t, key);
        }
    }

    Topic get(String topic) {
        return topics.get(topic);
    }

    /** @return the names of the topics registered here (listened to or subscribed), sorted */
    List<String> names() {
        return topics.keySet().stream().sorted().toList();
    }

    List<String> subscribed() {
        return topics.values().stream().filter(t -> t.subscribed).map(t -> t.name).toList();
    }

    private void requireKey(Topic t, SecretKey key) {
        if (!TopicKeys.same(t.key, key)) {
            String why = t.key == null ? "it is an open topic here, and a password was given"
                    : key == null ? "it is password-protected here, and no password was given" : "the password is wrong";
            LOG.warn("node '{}': refused a registration on topic '{}': {}", node, t.name, why);
            throw new MessagingException("node '" + node + "' refused topic '" + t.name + "': " + why
                    + "; use the password the topic was first registered with");
        }
    }
}
