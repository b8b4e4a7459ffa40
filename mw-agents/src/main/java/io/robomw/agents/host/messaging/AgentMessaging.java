package io.robomw.agents.host.messaging;

import io.robomw.agents.messaging.ForwardingMessaging;
import io.robomw.agents.messaging.MessagingNode;
import io.robomw.api.Message;
import io.robomw.api.MessageListener;
import io.robomw.api.Messaging;

import java.io.Serializable;
import java.time.Duration;
import java.util.List;
import java.util.Objects;
import java.util.UUID;
import java.util.concurrent.CopyOnWriteArrayList;
import java.util.function.UnaryOperator;

/**
 * One agent's view of its host's messaging node ({@code context().messaging()}): the paper's
 * operations, where the {@code host} of {@link #sendMessage} and {@link #waitForReply} may also
 * be an agent host's name ({@code "ft"}) or address ({@code rmi://127.0.0.1:1100/ft}), resolved
 * through the host's {@link HostDirectory}. The listeners the agent registers are removed when it
 * leaves the host or ends ({@link #release()}), so a departed agent's code is never called from
 * here; its subscriptions stay with the node, which delivers a topic nobody listens to nowhere.
 * The other calls go to the node as they are.
 *
 * <p>Thread-safe.
 */
public final class AgentMessaging implements ForwardingMessaging {

    private record Registered(String topic, MessageListener listener) {
    }

    private final MessagingNode node;
    private final UnaryOperator<String> resolve;
    private final List<Registered> listeners = new CopyOnWriteArrayList<>();
    private volatile boolean released;

    /**
     * @param node    the host's node
     * @param resolve turns a host name or agent host address into a messaging address
     */
    AgentMessaging(MessagingNode node, UnaryOperator<String> resolve) {
        this.node = node;
        this.resolve = resolve;
    }

    @Override
    public Messaging delegate(String operation) {
        return node;
    }

    @Override
    public UUID sendMessage(String name, String host, String pass, String topic, Serializable object, String function) {
        return node.sendMessage(name, resolve.apply(Objects.requireNonNull(host, "host")), pass, topic, object, function);
    }

    @Override
    public Message waitForReply(String topic, String host) {
        return node.waitForReply(topic, resolve.apply(host));
    }

    @Override
    public Message waitForReply(String topic, String host, Duration timeout) {
        return node.waitForReply(topic, resolve.apply(host), timeout);
    }

    @Override
    public void addMessageListener(String topic, String password, MessageListener listener) {
        if (released) {
            throw new IllegalStateException("this agent has left the host; register listeners from where it is now");
        }
        node.addMessageListener(topic, password, listener);
        listeners.add(new Registered(topic, listener));
    }

    @Override
    public void removeMessageListener(String topic, MessageListener listener) {
        node.removeMessageListener(topic, listener);
        listeners.removeIf(r -> r.topic().equals(topic) && r.listener() == listener);
    }

    /** Removes every listener the agent registered here: it left or ended. Idempotent. */
    void release() {
        released = true;
        for (Registered r : listeners) {
            node.removeMessageListener(r.topic(), r.listener());
        }
        listeners.clear();
    }
}
