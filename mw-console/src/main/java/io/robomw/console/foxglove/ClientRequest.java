package io.robomw.console.foxglove;

import com.fasterxml.jackson.core.JsonProcessingException;
import com.fasterxml.jackson.databind.JsonNode;
import com.fasterxml.jackson.databind.ObjectMapper;

import java.util.ArrayList;
import java.util.List;
import java.util.Map;

/**
 * A client's JSON text message (its {@code op}), parsed strictly: each field is checked, and a
 * message that is not what the protocol says is refused with a {@link BadRequest} naming the op,
 * the field, the value and the rule. The connection goes on after a bad message (the server answers
 * with a status error). Ops of capabilities RoboMW does not offer (parameters, services, connection
 * graph, assets) parse to {@link Unsupported}, answered as the Foxglove SDK answers them.
 */
public sealed interface ClientRequest {

    /** The most entries one subscribe, unsubscribe, advertise or unadvertise may carry. */
    int MAX_ENTRIES = 1_000;

    /**
     * Subscriptions to server channels.
     *
     * @param subscriptions each with the client's own id for it
     */
    record Subscribe(List<Subscription> subscriptions) implements ClientRequest {
        /** Copies. */
        public Subscribe {
            subscriptions = List.copyOf(subscriptions);
        }
    }

    /**
     * One subscription.
     *
     * @param id        the client's id for it (u32), which each message on it carries
     * @param channelId the server channel (u32)
     */
    record Subscription(long id, long channelId) {
    }

    /** @param subscriptionIds the subscriptions to end, by the client's ids */
    record Unsubscribe(List<Long> subscriptionIds) implements ClientRequest {
        /** Copies. */
        public Unsubscribe {
            subscriptionIds = List.copyOf(subscriptionIds);
        }
    }

    /** @param channels channels the client will publish on (the clientPublish capability) */
    record Advertise(List<ClientChannel> channels) implements ClientRequest {
        /** Copies. */
        public Advertise {
            channels = List.copyOf(channels);
        }
    }

    /**
     * A channel a client publishes on.
     *
     * @param id         the client's id for it (u32), which its MESSAGE_DATA frames carry
     * @param topic      its topic
     * @param encoding   how its messages are encoded ({@code json})
     * @param schemaName its messages' type ({@code geometry_msgs/Twist})
     */
    record ClientChannel(long id, String topic, String encoding, String schemaName) {
    }

    /** @param channelIds the client channels that end */
    record Unadvertise(List<Long> channelIds) implements ClientRequest {
        /** Copies. */
        public Unadvertise {
            channelIds = List.copyOf(channelIds);
        }
    }

    /**
     * An op of a capability RoboMW does not offer.
     *
     * @param op         the op
     * @param capability the capability it needs, in the SDK's words
     */
    record Unsupported(String op, String capability) implements ClientRequest {
        /** @return the status the SDK answers with */
        public String answer() {
            return capability.equals("services") ? "Server does not support services" : "Server does not support " + capability + " capability";
        }
    }

    /** A client message that is not what the protocol says; its message is the status the client is sent. */
    final class BadRequest extends Exception {
        private static final long serialVersionUID = 1L;

        /** @param message what is wrong, for the client */
        public BadRequest(String message) {
            super(message);
        }
    }

    /** The ops of capabilities not offered, and the capability each needs. */
    Map<String, String> UNSUPPORTED = Map.of(
            "getParameters", "parameters",
            "setParameters", "parameters",
            "subscribeParameterUpdates", "parametersSubscribe",
            "unsubscribeParameterUpdates", "parametersSubscribe",
            "subscribeConnectionGraph", "connection graph",
            "unsubscribeConnectionGraph", "connection graph",
            "fetchAsset", "assets");

    /**
     * Parses a text message.
     *
     * @param text the message
     * @return what the client asks
     * @throws BadRequest saying what is wrong with it
     */
    static ClientRequest parse(String text) throws BadRequest {
        JsonNode n;
        try {
            n = Json.MAPPER.readTree(text);
        } catch (JsonProcessingException e) {
            throw new BadRequest("Invalid message: not JSON (" + e.getOriginalMessage() + ")");
        }
        if (n == null || !n.isObject()) {
            throw new BadRequest("Invalid message: a text message is a JSON object with an \"op\", got " + Json.shortly(text));
        }
        JsonNode op = n.get("op");
        if (op == null || !op.isTextual()) {
            throw new BadRequest("Invalid message: no \"op\" string in " + Json.shortly(text));
        }
        return switch (op.asText()) {
            case "subscribe" -> {
                List<Subscription> s = new ArrayList<>();
                for (JsonNode e : array(n, "subscriptions", "subscribe")) {
                    s.add(new Subscription(u32(e, "id", "subscribe"), u32(e, "channelId", "subscribe")));
                }
                yield new Subscribe(s);
            }
            case "unsubscribe" -> new Unsubscribe(u32s(n, "subscriptionIds", "unsubscribe"));
            case "advertise" -> {
                List<ClientChannel> c = new ArrayList<>();
                for (JsonNode e : array(n, "channels", "advertise")) {
                    c.add(new ClientChannel(u32(e, "id", "advertise"), text(e, "topic", "advertise"), text(e, "encoding", "advertise"),
                            text(e, "schemaName", "advertise")));
                }
                yield new Advertise(c);
            }
            case "unadvertise" -> new Unadvertise(u32s(n, "channelIds", "unadvertise"));
            default -> {
                String capability = UNSUPPORTED.get(op.asText());
                if (capability == null) {
                    throw new BadRequest("Invalid message: unknown op \"" + Json.shortly(op.asText())
                            + "\" (RoboMW takes subscribe, unsubscribe, advertise and unadvertise)");
                }
                yield new Unsupported(op.asText(), capability);
            }
        };
    }

    private static JsonNode array(JsonNode n, String field, String op) throws BadRequest {
        JsonNode a = n.get(field);
        if (a == null || !a.isArray()) {
            throw new BadRequest("Invalid message: " + op + " needs an array \"" + field + "\", got " + (a == null ? "none" : Json.shortly(a.toString())));
        }
        if (a.size() > MAX_ENTRIES) {
            throw new BadRequest("Invalid message: " + op + " carries " + a.size() + " entries in \"" + field + "\"; at most " + MAX_ENTRIES + " at once");
        }
        return a;
    }

    private static List<Long> u32s(JsonNode n, String field, String op) throws BadRequest {
        List<Long> ids = new ArrayList<>();
        for (JsonNode e : array(n, field, op)) {
            ids.add(u32(e, op + " " + field));
        }
        return ids;
    }

    private static long u32(JsonNode n, String field, String op) throws BadRequest {
        if (!n.isObject()) {
            throw new BadRequest("Invalid message: each entry of " + op + " is an object, got " + Json.shortly(n.toString()));
        }
        JsonNode v = n.get(field);
        if (v == null) {
            throw new BadRequest("Invalid message: an entry of " + op + " has no \"" + field + "\"");
        }
        return u32(v, op + " \"" + field + "\"");
    }

    private static long u32(JsonNode v, String what) throws BadRequest {
        if (!v.isIntegralNumber() || !v.canConvertToLong() || v.asLong() < 0 || v.asLong() > BinaryFrames.U32_MAX) {
            throw new BadRequest("Invalid message: " + what + " must be an integer from 0 to " + BinaryFrames.U32_MAX + ", got " + Json.shortly(v.toString()));
        }
        return v.asLong();
    }

    private static String text(JsonNode n, String field, String op) throws BadRequest {
        JsonNode v = n.get(field);
        if (v == null || !v.isTextual()) {
            throw new BadRequest("Invalid message: a channel of " + op + " needs a string \"" + field + "\", got "
                    + (v == null ? "none" : Json.shortly(v.toString())));
        }
        return v.asText();
    }
}
