package io.robomw.agents.host.trip;

import io.robomw.api.Agent;
import io.robomw.api.Message;
import io.robomw.api.Messaging;

import java.util.concurrent.BlockingQueue;
import java.util.concurrent.LinkedBlockingQueue;
import java.util.concurrent.TimeUnit;

/**
 * Test agent: at its stop it answers requests on a protected topic ("ask" -> "pong from HOST"),
 * subscribes to the topic, reports "ready", and brings home the first publication it hears
 * ("heard ..."), waiting at most 20 s.
 */
public class ChatResponder extends Agent {

    private static final long serialVersionUID = 1L;
    public static final String TOPIC = "chat";
    public static final String PASSWORD = "chat-password";

    @Override
    public void run() {
        Messaging m = context().messaging();
        String here = context().hostName();
        BlockingQueue<Message> heard = new LinkedBlockingQueue<>();
        m.addMessageListener(TOPIC, PASSWORD, msg -> {
            if ("ask".equals(msg.function())) {
                m.replyMessage(msg, "pong from " + here, "ok");
            } else {
                heard.add(msg);
            }
        });
        m.subscribeMessage(TOPIC, PASSWORD);
        context().report("ready");
        try {
            Message publication = heard.poll(20, TimeUnit.SECONDS);
            context().setResult(publication == null ? "heard nothing" : "heard " + publication.payload() + " from " + publication.sender());
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
        }
    }
}
