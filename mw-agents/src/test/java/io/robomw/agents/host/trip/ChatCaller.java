package io.robomw.agents.host.trip;

import io.robomw.api.Agent;
import io.robomw.api.Message;
import io.robomw.api.Messaging;

import java.time.Duration;
import java.util.UUID;

/**
 * Test agent: at its stop it asks the agent host named {@code peer} (by name, or by address) on
 * {@link ChatResponder}'s protected topic, brings the reply home, and publishes "news" on the
 * topic once answered.
 */
public class ChatCaller extends Agent {

    private static final long serialVersionUID = 1L;
    private final String peer;

    public ChatCaller(String peer) {
        this.peer = peer;
    }

    @Override
    public void run() {
        Messaging m = context().messaging();
        String receiver = peer.contains("/") ? peer.substring(peer.lastIndexOf('/') + 1) : peer;
        UUID id = m.sendMessage(receiver, peer, ChatResponder.PASSWORD, ChatResponder.TOPIC, "ping", "ask");
        Message reply = m.waitForReply(id, Duration.ofSeconds(10));
        m.publishMessage(ChatResponder.TOPIC, "news", "tell", ChatResponder.PASSWORD);
        context().setResult((java.io.Serializable) reply.payload());
    }
}
