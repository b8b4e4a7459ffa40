package io.robomw.console.rosbridge.protocol;

import io.robomw.console.rosbridge.graph.Graph;
import io.robomw.console.rosbridge.graph.Topic;
import io.robomw.console.rosbridge.msg.MessageType;

import java.util.HashMap;
import java.util.Map;
import java.util.concurrent.TimeUnit;

/**
 * One client's subscriptions. A client may subscribe to a topic several times with different
 * ids (one per component, as the protocol recommends); it gets each message once, with the
 * lowest {@code throttle_rate} and the highest {@code queue_length} of them (as rosbridge_suite's
 * protocol document says; its code takes the lowest queue length), and in CBOR if any of them
 * asked for it. A {@code fragment_size} holds for the whole client, as in rosbridge_suite
 * ({@link ClientSession}). {@code unsubscribe} without an
 * id ends all of them. Used on the client's thread (and {@link #close} from any).
 */
final class ClientSubscriptions {

    /** The key of a subscription sent without an id. */
    private static final String NO_ID = "\u0000no id";

    private final Session session;
    private final Map<String, Subscribed> topics = new HashMap<>();
    private int count;

    /** One topic this client receives: its queue and the subscriptions that want it. */
    private static final class Subscribed {
        final Topic topic;
        final TopicQueue queue;
        final Map<String, Params> byId = new HashMap<>();

        Subscribed(Topic topic, TopicQueue queue) {
            this.topic = topic;
            this.queue = queue;
        }
    }

    /** What one subscribe asked for. */
    private record Params(int throttleMillis, int queueLength, Compression compression) {
    }

    ClientSubscriptions(Session session) {
        this.session = session;
    }

    synchronized void subscribe(Request r) {
        String name = r.requiredText("topic");
        String absolute = absolute(name);
        String type = r.text("type");
        int throttle = r.integer("throttle_rate", 0, 0);
        int queueLength = r.integer("queue_length", 0, 0);
        String compressionText = r.text("compression");
        Compression compression;
        try {
            compression = Compression.of(compressionText);
        } catch (IllegalArgumentException e) {
            throw new ProtocolException("subscribe to " + name + ": " + e.getMessage());
        }
        Topic topic = find(absolute, type, name);
        String key = r.idText() == null ? NO_ID : r.idText();
        Subscribed s = topics.get(absolute);
        boolean newId = s == null || !s.byId.containsKey(key);
        if (newId && count >= session.limits.maxSubscriptions()) {
            throw new ProtocolException("subscribe to " + name + ": this client already has " + count + " subscriptions, the most one client may hold");
        }
        if (s == null) {
            s = new Subscribed(topic, session.outbox.queue(name));
            topics.put(absolute, s);
        }
        s.byId.put(key, new Params(throttle, queueLength, compression));
        if (newId) {
            count++;
        }
        apply(s);
        if (s.byId.size() == 1 && newId) {
            topic.subscribe(s.queue, Graph.BRIDGE_NODE);
        }
        if ("png".equalsIgnoreCase(compressionText)) {
            session.status(StatusLevel.WARNING, "subscribe to " + name + ": png compression is not offered by this bridge; messages come as JSON", r.id());
        }
        session.status(StatusLevel.INFO, "Subscribed to " + name, r.id());
    }

    synchronized void unsubscribe(Request r) {
        String name = r.requiredText("topic");
        String absolute = absolute(name);
        Subscribed s = topics.get(absolute);
        if (s == null) {
            return;
        }
        String id = r.idText();
        if (id == null) {
            count -= s.byId.size();
            s.byId.clear();
        } else if (s.byId.remove(id) != null) {
            count--;
        }
        if (s.byId.isEmpty()) {
            end(absolute, s);
        } else {
            apply(s);
        }
        session.status(StatusLevel.INFO, "Unsubscribed from " + name, r.id());
    }

    synchronized void close() {
        for (Map.Entry<String, Subscribed> e : Map.copyOf(topics).entrySet()) {
            end(e.getKey(), e.getValue());
        }
        count = 0;
    }

    private void end(String absolute, Subscribed s) {
        topics.remove(absolute);
        s.topic.unsubscribe(s.queue);
        session.outbox.remove(s.queue);
        session.graph.release(s.topic);
    }

    private void apply(Subscribed s) {
        int throttle = Integer.MAX_VALUE;
        int queue = 0;
        Compression compression = Compression.NONE;
        for (Params p : s.byId.values()) {
            throttle = Math.min(throttle, p.throttleMillis());
            queue = Math.max(queue, p.queueLength());
            if (p.compression() == Compression.CBOR) {
                compression = Compression.CBOR;
            }
        }
        session.outbox.configure(s.queue, queue, TimeUnit.MILLISECONDS.toNanos(throttle), compression);
    }

    private Topic find(String absolute, String type, String name) {
        MessageType wanted = null;
        if (type != null) {
            try {
                wanted = session.graph.interfaces().message(type);
            } catch (IllegalArgumentException e) {
                throw new ProtocolException("subscribe to " + name + ": " + e.getMessage());
            }
        }
        Topic t = session.graph.topic(absolute).or(() -> session.resolver.resolve(absolute)).orElse(null);
        if (t == null) {
            if (wanted == null) {
                throw new ProtocolException("Cannot infer topic type for topic " + name + " as it is not yet advertised");
            }
            return session.graph.declare(absolute, wanted, false);
        }
        if (wanted != null && !wanted.name().equals(t.type().name())) {
            throw new ProtocolException("Tried to subscribe to a topic " + name + " with type " + type + " but the topic is already established with type "
                    + t.type().name().full());
        }
        return t;
    }

    private static String absolute(String name) {
        try {
            return Graph.absolute(name);
        } catch (IllegalArgumentException e) {
            throw new ProtocolException(e.getMessage());
        }
    }
}
