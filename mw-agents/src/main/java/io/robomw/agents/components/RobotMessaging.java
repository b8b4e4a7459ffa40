package io.robomw.agents.components;

import io.robomw.agents.messaging.ForwardingMessaging;
import io.robomw.agents.messaging.MessagingNode;
import io.robomw.agents.messaging.MessagingSettings;
import io.robomw.api.MessageListener;
import io.robomw.api.Messaging;
import io.robomw.api.MessagingException;
import io.robomw.api.spi.MessagingComponent;
import io.robomw.api.spi.MessagingConfig;
import io.robomw.api.spi.SecretRef;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.io.Serializable;
import java.util.List;
import java.util.Map;
import java.util.UUID;
import java.util.concurrent.ConcurrentHashMap;
import java.util.function.Function;

/**
 * A robot's communication component: a {@link MessagingNode} set up as the robot file's
 * {@code messaging:} section says, started when the robot opens if the section names listen or
 * connect addresses, else on first use on loopback at an ephemeral port ({@link MessagingConfig#DEFAULT_LISTEN}).
 * The start is logged once, with the addresses.
 *
 * <p>A topic whose password the section names by reference ({@code topics: {alerts:
 * {password_file: ...}}}) uses that password whenever a call passes {@code null} for it, so
 * programs need not carry secrets; a password passed explicitly always wins. The calls without a
 * password go to the node as they are.
 *
 * <p>Thread-safe.
 */
public final class RobotMessaging implements MessagingComponent, ForwardingMessaging {

    private static final Logger LOG = LoggerFactory.getLogger(RobotMessaging.class);

    private final MessagingConfig config;
    private final MessagingSettings settings;
    private final Function<String, String> environment;
    private final Map<String, String> passwords = new ConcurrentHashMap<>();
    private final Object lock = new Object();
    private volatile MessagingNode node;
    private boolean closed;

    /**
     * @param config      the robot's messaging settings
     * @param settings    the node's settings
     * @param environment how environment variables are read (for {@code password_env})
     * @throws MessagingException if the settings name listen addresses and one cannot be bound
     */
    public RobotMessaging(MessagingConfig config, MessagingSettings settings, Function<String, String> environment) {
        this.config = config;
        this.settings = settings;
        this.environment = environment;
        if (!config.startsOnFirstUse()) {
            node("open");
        }
    }

    /** @return the node, started (on first use when not yet) */
    public MessagingNode node() {
        return node("node");
    }

    private MessagingNode node(String firstUse) {
        MessagingNode n = node;
        if (n != null) {
            return n;
        }
        synchronized (lock) {
            if (closed) {
                throw new MessagingException("the messaging node '" + config.nodeName() + "' of " + config.source() + " is closed");
            }
            if (node == null) {
                MessagingNode.Builder b = MessagingNode.builder(config.nodeName()).settings(settings);
                (config.listen().isEmpty() ? List.of(MessagingConfig.DEFAULT_LISTEN) : config.listen()).forEach(b::bind);
                config.connect().forEach(b::connect);
                node = b.build();
                LOG.info("messaging node '{}' ({}) started at {}{}", config.nodeName(), config.source(), node.boundAddresses(),
                        config.startsOnFirstUse() ? " on first use (" + firstUse + ")" : "");
            }
            return node;
        }
    }

    @Override
    public List<String> addresses() {
        MessagingNode n = node;
        return n == null ? List.of() : n.boundAddresses().stream().map(Object::toString).toList();
    }

    /**
     * @param topic a topic
     * @param given the password a caller passed, or {@code null}
     * @return the password to use: the given one, else the one the settings name for the topic, else {@code null}
     */
    String password(String topic, String given) {
        if (given != null || topic == null) {
            return given;
        }
        SecretRef ref = config.topicPasswords().get(topic);
        if (ref == null) {
            return null;
        }
        try {
            return passwords.computeIfAbsent(topic, t -> ref.read(environment));
        } catch (IllegalStateException e) {
            throw new MessagingException("topic '" + topic + "': " + e.getMessage(), e);
        }
    }

    /** @return the node, started now if this is its first use */
    @Override
    public Messaging delegate(String operation) {
        return node(operation);
    }

    @Override
    public UUID sendMessage(String name, String host, String pass, String topic, Serializable object, String function) {
        return node("sendMessage").sendMessage(name, host, password(topic, pass), topic, object, function);
    }

    @Override
    public void publishMessage(String topic, Serializable object, String function, String password) {
        node("publishMessage").publishMessage(topic, object, function, password(topic, password));
    }

    @Override
    public void subscribeMessage(String topic, String password) {
        node("subscribeMessage").subscribeMessage(topic, password(topic, password));
    }

    @Override
    public void addMessageListener(String topic, String password, MessageListener listener) {
        node("addMessageListener").addMessageListener(topic, password(topic, password), listener);
    }

    /** Does not start the node: a listener was never added to one that has not started. */
    @Override
    public void removeMessageListener(String topic, MessageListener listener) {
        MessagingNode n = node;
        if (n != null) {
            n.removeMessageListener(topic, listener);
        }
    }

    @Override
    public void close() {
        MessagingNode n;
        synchronized (lock) {
            closed = true;
            n = node;
        }
        if (n != null) {
            n.close();
        }
    }

    @Override
    public String toString() {
        return "messaging of " + config.nodeName() + " (" + config.source() + ")";
    }
}
