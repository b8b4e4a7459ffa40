package io.robomw.console.rosbridge.messaging;

import com.fasterxml.jackson.core.JsonProcessingException;
import com.fasterxml.jackson.databind.ObjectMapper;
import com.fasterxml.jackson.databind.node.JsonNodeFactory;
import com.fasterxml.jackson.databind.node.ObjectNode;
import io.robomw.api.Message;
import io.robomw.api.MessageListener;
import io.robomw.api.Messaging;
import io.robomw.console.rosbridge.graph.Graph;
import io.robomw.console.rosbridge.graph.Publication;
import io.robomw.console.rosbridge.graph.Topic;
import io.robomw.console.rosbridge.graph.TopicListener;
import io.robomw.console.rosbridge.graph.TopicResolver;
import io.robomw.console.rosbridge.msg.MessageReader;
import io.robomw.console.rosbridge.msg.MessageType;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.io.Serializable;
import java.util.HashMap;
import java.util.Map;
import java.util.Optional;
import java.util.concurrent.atomic.AtomicLong;

/**
 * RoboMW messaging topics as ROS topics, both ways: a RoboMW publication on topic {@code T}
 * appears on {@code /robomw/T}, and a ROS client's message on {@code /robomw/T} is published on
 * {@code T} (docs/messaging.md), each as a {@code robomw_msgs/msg/Message}:
 *
 * <table>
 *   <caption>fields</caption>
 *   <tr><th>field</th><th>from RoboMW</th><th>to RoboMW</th></tr>
 *   <tr><td>{@code stamp}</td><td>the message's timestamp</td><td>ignored (RoboMW stamps it)</td></tr>
 *   <tr><td>{@code sender}</td><td>the sending node or robot</td><td>ignored (the bridge's node sends it)</td></tr>
 *   <tr><td>{@code function}</td><td>the message's function</td><td>its function ({@code publish} if empty)</td></tr>
 *   <tr><td>{@code data}</td><td>a String payload as it is; any other as JSON (records, numbers,
 *   lists, maps), or its {@code toString()} if it has no JSON form; empty for none</td><td>the payload, a String</td></tr>
 *   <tr><td>{@code payload_type}</td><td>the payload's Java class, empty for none</td><td>ignored</td></tr>
 * </table>
 *
 * A {@code /robomw/T} topic exists once a client names it (subscribe, advertise or publish), and
 * RoboMW's topic {@code T} is subscribed to while the ROS topic has subscribers. Only topics
 * without a password are bridged. Publications that came from RoboMW are not sent back to it.
 */
public final class MessagingBridge implements TopicResolver, AutoCloseable {

    /** Where RoboMW topics appear. */
    public static final String PREFIX = "/robomw/";
    /** The node that publishes and receives them, as rosapi lists it. */
    public static final String NODE = "/robomw_messaging";
    /** The function of a ROS client's message that does not give one. */
    public static final String DEFAULT_FUNCTION = "publish";

    private static final Logger LOG = LoggerFactory.getLogger(MessagingBridge.class);
    private static final ObjectMapper JSON = new ObjectMapper().findAndRegisterModules();
    private static final JsonNodeFactory NODES = JsonNodeFactory.instance;

    private final Messaging messaging;
    private final Graph graph;
    private final MessageType type;
    private final Map<String, Bridged> bridged = new HashMap<>();
    private final ThreadLocal<Boolean> relaying = ThreadLocal.withInitial(() -> false);
    private final AtomicLong failures = new AtomicLong();

    /** One RoboMW topic while it is bridged. */
    private final class Bridged {
        final String roboTopic;
        final Topic topic;
        final MessageListener fromRoboMw;
        final TopicListener toRoboMw;
        boolean listening;

        Bridged(String roboTopic, Topic topic) {
            this.roboTopic = roboTopic;
            this.topic = topic;
            this.fromRoboMw = m -> relay(topic, m);
            this.toRoboMw = p -> publish(roboTopic, p);
        }
    }

    /**
     * @param messaging the node RoboMW topics are published and received through
     * @param graph     the graph {@code /robomw/*} topics go into
     */
    public MessagingBridge(Messaging messaging, Graph graph) {
        this.messaging = messaging;
        this.graph = graph;
        this.type = graph.interfaces().message("robomw_msgs/msg/Message");
    }

    @Override
    public synchronized Optional<Topic> resolve(String name) {
        if (!name.startsWith(PREFIX) || name.length() == PREFIX.length()) {
            return Optional.empty();
        }
        Bridged b = bridged.get(name);
        if (b != null) {
            return Optional.of(b.topic);
        }
        Topic topic = graph.declare(name, type, false);
        Bridged fresh = new Bridged(name.substring(PREFIX.length()), topic);
        bridged.put(name, fresh);
        topic.addPublisher(NODE);
        topic.addSink(fresh.toRoboMw, NODE);
        topic.onDemand(wanted -> listen(fresh, wanted));
        LOG.info("rosbridge: RoboMW topic '{}' bridged as {}", fresh.roboTopic, name);
        return Optional.of(topic);
    }

    private void listen(Bridged b, boolean wanted) {
        synchronized (b) {
            listenLocked(b, wanted);
        }
    }

    private void listenLocked(Bridged b, boolean wanted) {
        if (wanted == b.listening) {
            return;
        }
        try {
            if (wanted) {
                messaging.subscribeMessage(b.roboTopic, null);
                messaging.addMessageListener(b.roboTopic, null, b.fromRoboMw);
            } else {
                messaging.removeMessageListener(b.roboTopic, b.fromRoboMw);
            }
            b.listening = wanted;
        } catch (RuntimeException e) {
            failed((wanted ? "subscribing to" : "leaving") + " RoboMW topic '" + b.roboTopic + "'", e);
        }
    }

    private void relay(Topic topic, Message m) {
        ObjectNode msg = NODES.objectNode();
        msg.set("stamp", MessageReader.time(m.timestamp()));
        msg.put("sender", m.sender());
        msg.put("function", m.function());
        msg.put("data", data(m.payload()));
        msg.put("payload_type", m.payload() == null ? "" : m.payload().getClass().getName());
        relaying.set(true);
        try {
            topic.publish(msg);
        } finally {
            relaying.set(false);
        }
    }

    private void publish(String roboTopic, Publication p) {
        if (relaying.get()) {
            return; // it came from RoboMW
        }
        String function = p.msg().path("function").asText();
        try {
            messaging.publishMessage(roboTopic, p.msg().path("data").asText(), function.isEmpty() ? DEFAULT_FUNCTION : function, null);
        } catch (RuntimeException e) {
            failed("publishing on RoboMW topic '" + roboTopic + "'", e);
        }
    }

    /**
     * @param payload a RoboMW message's payload
     * @return it as {@code data}: a String as it is, anything else as JSON, or its text if it has no JSON form
     */
    static String data(Serializable payload) {
        if (payload == null) {
            return "";
        }
        if (payload instanceof String s) {
            return s;
        }
        try {
            return JSON.writeValueAsString(payload);
        } catch (JsonProcessingException | RuntimeException e) {
            return payload.toString();
        }
    }

    private void failed(String what, RuntimeException e) {
        long n = failures.incrementAndGet();
        if (Long.bitCount(n) == 1) {
            LOG.warn("rosbridge: {} failed: {} ({} messaging failures so far)", what, e.getMessage(), n);
        }
    }

    /** Stops receiving RoboMW topics. */
    @Override
    public synchronized void close() {
        for (Bridged b : bridged.values()) {
            if (b.listening) {
                try {
                    messaging.removeMessageListener(b.roboTopic, b.fromRoboMw);
                } catch (RuntimeException e) {
                    LOG.debug("rosbridge: leaving RoboMW topic '{}' failed: {}", b.roboTopic, e.toString());
                }
                b.listening = false;
            }
            b.topic.removeSink(b.toRoboMw);
        }
    }
}
