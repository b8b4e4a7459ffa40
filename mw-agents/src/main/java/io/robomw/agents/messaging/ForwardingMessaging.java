package io.robomw.agents.messaging;

import io.robomw.api.Message;
import io.robomw.api.MessageListener;
import io.robomw.api.Messaging;

import java.io.Serializable;
import java.time.Duration;
import java.util.UUID;

/**
 * {@link Messaging} whose calls go to another one, its {@link #delegate delegate} (after Guava's
 * {@code Forwarding*} decorators, and as {@code Robot}'s messaging calls go to its component): a
 * component that adds to some calls (resolves host names, supplies a topic's password, keeps
 * track of an agent's listeners) overrides those and inherits the rest, instead of forwarding
 * each of the paper's operations by hand.
 */
public interface ForwardingMessaging extends Messaging {

    /**
     * @param operation the call being made ({@code "sendMessage"}), for a component that starts
     *                  what it forwards to on first use and says why
     * @return where the call goes
     */
    Messaging delegate(String operation);

    @Override
    default UUID sendMessage(String name, String host, String pass, String topic, Serializable object, String function) {
        return delegate("sendMessage").sendMessage(name, host, pass, topic, object, function);
    }

    @Override
    default Message waitForReply(String topic, String host) {
        return delegate("waitForReply").waitForReply(topic, host);
    }

    @Override
    default Message waitForReply(String topic, String host, Duration timeout) {
        return delegate("waitForReply").waitForReply(topic, host, timeout);
    }

    @Override
    default Message waitForReply(UUID correlationId, Duration timeout) {
        return delegate("waitForReply").waitForReply(correlationId, timeout);
    }

    @Override
    default void replyMessage(Message request, Serializable object, String function) {
        delegate("replyMessage").replyMessage(request, object, function);
    }

    @Override
    default void publishMessage(String topic, Serializable object, String function, String password) {
        delegate("publishMessage").publishMessage(topic, object, function, password);
    }

    @Override
    default void subscribeMessage(String topic, String password) {
        delegate("subscribeMessage").subscribeMessage(topic, password);
    }

    @Override
    default void addMessageListener(String topic, String password, MessageListener listener) {
        delegate("addMessageListener").addMessageListener(topic, password, listener);
    }

    @Override
    default void removeMessageListener(String topic, MessageListener listener) {
        delegate("removeMessageListener").removeMessageListener(topic, listener);
    }
}
