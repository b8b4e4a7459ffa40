package io.robomw.console.rosbridge.protocol;

import io.robomw.console.rosbridge.graph.Graph;
import io.robomw.console.rosbridge.graph.Topic;
import io.robomw.console.rosbridge.msg.MessageException;
import io.robomw.console.rosbridge.msg.MessageType;

import java.util.HashMap;
import java.util.HashSet;
import java.util.Map;
import java.util.Set;

/**
 * The topics one client publishes on. {@code advertise} names the type; {@code publish} on a
 * topic the client did not advertise advertises it first with the topic's type (a topic no one
 * has declared has none to infer: refused, in rosbridge_suite's words). Advertisements are
 * counted by id, and {@code unadvertise} without an id ends all of them; a topic published on
 * without an advertisement stays published on until the client leaves. Used on the client's
 * thread (and {@link #close} from any).
 */
final class ClientPublishers {

    private static final String IMPLICIT = "\u0000publish";
    private static final String NO_ID = "\u0000no id";

    private final Session session;
    private final Map<String, Advertised> topics = new HashMap<>();

    private record Advertised(Topic topic, Set<String> ids) {
    }

    ClientPublishers(Session session) {
        this.session = session;
    }

    synchronized void advertise(Request r) {
        String name = r.requiredText("topic");
        String type = r.requiredText("type");
        boolean latch = r.flag("latch");
        String absolute = absolute(name);
        MessageType t;
        try {
            t = session.graph.interfaces().message(type);
        } catch (IllegalArgumentException e) {
            throw new ProtocolException("advertise " + name + ": " + e.getMessage());
        }
        Advertised a = topics.get(absolute);
        if (a == null && topics.size() >= session.limits.maxAdvertisements()) {
            throw new ProtocolException("advertise " + name + ": this client already advertises " + topics.size() + " topics, the most one client may");
        }
        Topic topic = a != null ? a.topic() : declare(absolute, t, latch, name);
        if (!topic.type().name().equals(t.name())) {
            throw new ProtocolException("advertise " + name + ": the topic already has type " + topic.type().name().full() + ", not " + type);
        }
        if (a == null) {
            a = new Advertised(topic, new HashSet<>());
            topics.put(absolute, a);
            topic.addPublisher(Graph.BRIDGE_NODE);
        }
        a.ids().add(r.idText() == null ? NO_ID : r.idText());
        session.status(StatusLevel.INFO, "Advertised " + name + " (" + topic.type().name().full() + ")", r.id());
    }

    synchronized void unadvertise(Request r) {
        String name = r.requiredText("topic");
        String absolute = absolute(name);
        Advertised a = topics.get(absolute);
        if (a == null) {
            return;
        }
        if (r.idText() == null) {
            a.ids().clear();
        } else {
            a.ids().remove(r.idText());
        }
        if (a.ids().isEmpty()) {
            end(absolute, a);
        }
    }

    void publish(Request r) {
        String name = r.requiredText("topic");
        String absolute = absolute(name);
        Topic topic;
        synchronized (this) {
            Advertised a = topics.get(absolute);
            if (a == null) {
                Topic t = session.graph.topic(absolute).or(() -> session.resolver.resolve(absolute))
                        .orElseThrow(() -> new ProtocolException("Cannot infer topic type for topic " + name + " as it is not yet advertised"));
                if (topics.size() >= session.limits.maxAdvertisements()) {
                    throw new ProtocolException("publish on " + name + ": this client already publishes on " + topics.size() + " topics, the most one client may");
                }
                a = new Advertised(t, new HashSet<>(Set.of(IMPLICIT)));
                topics.put(absolute, a);
                t.addPublisher(Graph.BRIDGE_NODE);
            }
            topic = a.topic();
        }
        try {
            topic.publish(session.reader.read(r.body().get("msg"), topic.type()));
        } catch (MessageException e) {
            throw new ProtocolException("publish on " + name + ": " + e.getMessage());
        }
    }

    synchronized void close() {
        for (Map.Entry<String, Advertised> e : Map.copyOf(topics).entrySet()) {
            end(e.getKey(), e.getValue());
        }
    }

    private void end(String absolute, Advertised a) {
        topics.remove(absolute);
        a.topic().removePublisher(Graph.BRIDGE_NODE);
        session.graph.release(a.topic());
    }

    private Topic declare(String absolute, MessageType type, boolean latch, String name) {
        Topic existing = session.graph.topic(absolute).or(() -> session.resolver.resolve(absolute)).orElse(null);
        if (existing != null) {
            return existing;
        }
        try {
            return session.graph.declare(absolute, type, latch);
        } catch (IllegalArgumentException e) {
            throw new ProtocolException("advertise " + name + ": " + e.getMessage());
        }
    }

    private static String absolute(String name) {
        try {
            return Graph.absolute(name);
        } catch (IllegalArgumentException e) {
            throw new ProtocolException(e.getMessage());
        }
    }
}
