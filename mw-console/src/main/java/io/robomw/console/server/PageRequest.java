package io.robomw.console.server;

import com.fasterxml.jackson.core.JsonProcessingException;
import com.fasterxml.jackson.databind.JsonNode;
import com.fasterxml.jackson.databind.ObjectMapper;

import java.util.UUID;

/**
 * One request a page sends over its WebSocket, as JSON text:
 *
 * <pre>
 * {"op": "retract" | "dispose", "agent": "UUID",         "token": "...", "id": 7}
 * {"op": "stop",                "robot": "robot name",   "token": "...", "id": 8}
 * </pre>
 *
 * {@code id} (optional, a number) comes back in the reply. Anything else is refused with a
 * {@link BadRequest} saying what was wrong: not JSON, not an object, an unknown op, a missing or
 * mistyped field, an agent id that is not a UUID, a robot name that is too long.
 *
 * @param op    the operation
 * @param agent the agent, for retract and dispose
 * @param robot the robot, for stop
 * @param token the access token the console printed
 * @param id    the page's number for the request, echoed back (0 if none)
 */
public record PageRequest(Op op, UUID agent, String robot, String token, long id) {

    /** Operations a page may ask for. */
    public enum Op {
        /** Bring an agent home. */
        RETRACT("retract"),
        /** End an agent's trip where it is. */
        DISPOSE("dispose"),
        /** Stop every motor of a robot. */
        STOP("stop");

        private final String wire;

        Op(String wire) {
            this.wire = wire;
        }

        /** @return the op's name in requests */
        public String wire() {
            return wire;
        }

        static Op of(String name) throws BadRequest {
            for (Op o : values()) {
                if (o.wire.equals(name)) {
                    return o;
                }
            }
            throw new BadRequest("unknown op '" + clip(name) + "': use retract, dispose or stop");
        }
    }

    /** The longest request accepted, characters (the WebSocket refuses longer frames too). */
    public static final int MAX_LENGTH = 4096;
    private static final int MAX_NAME = 200;
    private static final ObjectMapper JSON = new ObjectMapper();

    /** A request that cannot be served as sent. */
    public static final class BadRequest extends Exception {
        private static final long serialVersionUID = 1L;

        BadRequest(String message) {
            super(message);
        }
    }

    /**
     * @param text what the page sent
     * @return the request
     * @throws BadRequest if it is not a well-formed request
     */
    public static PageRequest parse(String text) throws BadRequest {
        if (text.length() > MAX_LENGTH) {
            throw new BadRequest("request of " + text.length() + " characters; the limit is " + MAX_LENGTH);
        }
        JsonNode n;
        try {
            n = JSON.readTree(text);
        } catch (JsonProcessingException e) {
            throw new BadRequest("not JSON: " + e.getOriginalMessage());
        }
        if (n == null || !n.isObject()) {
            throw new BadRequest("a request is a JSON object, got " + (n == null ? "nothing" : n.getNodeType().name().toLowerCase(java.util.Locale.ROOT)));
        }
        Op op = Op.of(text(n, "op"));
        long id = 0;
        if (n.has("id")) {
            if (!n.get("id").canConvertToLong()) {
                throw new BadRequest("field 'id' must be a whole number");
            }
            id = n.get("id").asLong();
        }
        String token = n.has("token") ? text(n, "token") : "";
        return switch (op) {
            case RETRACT, DISPOSE -> {
                String agent = text(n, "agent");
                try {
                    yield new PageRequest(op, UUID.fromString(agent), null, token, id);
                } catch (IllegalArgumentException e) {
                    throw new BadRequest("field 'agent' must be an agent's id (a UUID), got '" + clip(agent) + "'");
                }
            }
            case STOP -> {
                String robot = text(n, "robot");
                if (robot.isEmpty() || robot.length() > MAX_NAME) {
                    throw new BadRequest("field 'robot' must name a robot (1 to " + MAX_NAME + " characters)");
                }
                yield new PageRequest(op, null, robot, token, id);
            }
        };
    }

    private static String text(JsonNode n, String field) throws BadRequest {
        JsonNode v = n.get(field);
        if (v == null || v.isNull()) {
            throw new BadRequest("field '" + field + "' is missing");
        }
        if (!v.isTextual()) {
            throw new BadRequest("field '" + field + "' must be a string, got " + v.getNodeType().name().toLowerCase(java.util.Locale.ROOT));
        }
        return v.asText();
    }

    private static String clip(String s) {
        return s.length() > 60 ? s.substring(0, 60) + "..." : s;
    }
}
