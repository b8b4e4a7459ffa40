package io.robomw.it.agents;

import io.robomw.api.Agent;
import io.robomw.api.Message;
import io.robomw.api.Messaging;

import java.util.concurrent.BlockingQueue;
import java.util.concurrent.LinkedBlockingQueue;
import java.util.concurrent.TimeUnit;

/**
 * Test agent (its class exists only in src-it's test classes, which agent hosts lack): at its
 * stop it listens to a topic with a password through its host's messaging, reports "listening",
 * and brings home the first message it hears ("heard PAYLOAD from SENDER"), waiting at most 60 s.
 */
public class ListenerAgent extends Agent {

    private static final long serialVersionUID = 1L;
    private final String topic;
    private final String password;

    public ListenerAgent(String topic, String password) {
        this.topic = topic;
        this.password = password;
    }

    @Override
    public void run() {
        Messaging m = context().messaging();
        BlockingQueue<Message> heard = new LinkedBlockingQueue<>();
        m.addMessageListener(topic, password, heard::add);
        m.subscribeMessage(topic, password);
        context().report("listening");
        try {
            Message first = heard.poll(60, TimeUnit.SECONDS);
            context().setResult(first == null ? "heard nothing" : "heard " + first.payload() + " from " + first.sender());
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
        }
    }
}
