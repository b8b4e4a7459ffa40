package io.robomw.console.rosbridge.protocol;

import com.fasterxml.jackson.core.JsonProcessingException;
import com.fasterxml.jackson.databind.JsonNode;
import com.fasterxml.jackson.databind.ObjectMapper;
import com.fasterxml.jackson.databind.node.ObjectNode;
import com.fasterxml.jackson.dataformat.cbor.databind.CBORMapper;
import io.robomw.console.rosbridge.graph.Graph;
import io.robomw.console.rosbridge.graph.TopicResolver;
import io.robomw.console.rosbridge.msg.MessageReader;

import java.io.IOException;
import java.util.Optional;

/**
 * One client of the rosbridge v2 protocol, as rosbridge_suite's ROS 2 server serves it: reads
 * each message the client sends (a text frame of JSON, or a binary frame of CBOR), carries out
 * its {@code op}, and answers through the client's {@link Outbox}.
 *
 * <h2>Errors</h2>
 * Bad JSON, a message that is not an object, a missing or unknown {@code op}, a field of the
 * wrong kind, a request that cannot be carried out: the message is not acted on and the
 * connection goes on. rosbridge_suite's ROS 2 server only logs these; so does this bridge, and
 * it also sends a {@code status} error to a client that asked for status messages with
 * {@code set_level} ({@link StatusLevel}). A failed {@code call_service} is answered with
 * {@code result: false} in any case ({@link ClientCalls}).
 *
 * <h2>Fragments</h2>
 * A message may come in {@code fragment}s ({@link Defragmenter}); once whole it is handled as if
 * it had come in one frame. A {@code fragment_size} in any message sets the size the client's
 * replies and messages are cut to from then on, as in rosbridge_suite.
 *
 * <p>The connection calls {@link #onText}/{@link #onBinary} one at a time; {@link #close} may
 * come from any thread.
 */
public final class ClientSession {

    private static final ObjectMapper JSON = new ObjectMapper();
    private static final CBORMapper CBOR = new CBORMapper();

    private final Session session;
    private final ClientSubscriptions subscriptions;
    private final ClientPublishers publishers;
    private final ClientCalls calls;
    private final Defragmenter defragmenter;

    /**
     * @param graph    the topics and services
     * @param resolver makes topics on first use (RoboMW messaging topics)
     * @param reader   reads client messages against their types
     * @param limits   the bounds
     * @param outbox   where everything for this client goes
     * @param client   the client, as log lines name it (its address)
     */
    public ClientSession(Graph graph, TopicResolver resolver, MessageReader reader, Limits limits, Outbox outbox, String client) {
        this.session = new Session(graph, resolver, reader, limits, outbox, client);
        this.subscriptions = new ClientSubscriptions(session);
        this.publishers = new ClientPublishers(session);
        this.calls = new ClientCalls(session);
        this.defragmenter = new Defragmenter(limits);
    }

    /** @param text a text frame from the client: one JSON message */
    public void onText(String text) {
        JsonNode message;
        try {
            message = JSON.readTree(text);
        } catch (JsonProcessingException e) {
            session.status(StatusLevel.ERROR, "Unable to parse message as JSON: " + e.getOriginalMessage() + " (message began: " + head(text) + ")", null);
            return;
        }
        handle(message, text);
    }

    /** @param data a binary frame from the client: one CBOR-encoded message */
    public void onBinary(byte[] data) {
        JsonNode message;
        try {
            message = CBOR.readTree(data);
        } catch (IOException e) {
            session.status(StatusLevel.ERROR, "Unable to parse a binary message as CBOR (" + data.length + " bytes): " + e.getMessage(), null);
            return;
        }
        handle(message, "(" + data.length + " bytes of CBOR)");
    }

    /** Ends every subscription and advertisement of this client and drops what waits for it. */
    public void close() {
        subscriptions.close();
        publishers.close();
        session.outbox.close();
    }

    /** @return this client's service calls not yet answered */
    public int callsInFlight() {
        return calls.inFlight();
    }

    private void handle(JsonNode message, String original) {
        if (message == null || !message.isObject()) {
            session.status(StatusLevel.ERROR, "Received a message without an op. All messages require 'op' field with value one of: " + Op.allowed()
                    + ". Original message was: " + head(original), null);
            return;
        }
        ObjectNode body = (ObjectNode) message;
        JsonNode id = body.get("id");
        JsonNode opNode = body.get("op");
        if (opNode == null || !opNode.isTextual()) {
            session.status(StatusLevel.ERROR, "Received a message without an op. All messages require 'op' field with value one of: " + Op.allowed()
                    + ". Original message was: " + head(original), id);
            return;
        }
        Op op = Op.of(opNode.asText());
        if (op == null) {
            session.status(StatusLevel.ERROR, "Unknown operation: " + head(opNode.asText()) + ". Allowed operations: " + Op.allowed()
                    + ("auth".equals(opNode.asText()) ? " (ROS 2's rosbridge has no auth; this bridge takes its token in the URL: docs/ros2.md)" : ""), id);
            return;
        }
        if (!op.offered()) {
            session.status(StatusLevel.ERROR, op.wire() + " is not offered by this bridge (it offers " + Op.allowed() + ")", id);
            return;
        }
        Request r = new Request(op, id, body);
        try {
            JsonNode fragmentSize = body.get("fragment_size");
            if (fragmentSize != null && !fragmentSize.isNull()) {
                session.outbox.fragmentSize(r.integer("fragment_size", 0, 1));
            }
            switch (op) {
                case ADVERTISE -> publishers.advertise(r);
                case UNADVERTISE -> publishers.unadvertise(r);
                case PUBLISH -> publishers.publish(r);
                case SUBSCRIBE -> subscriptions.subscribe(r);
                case UNSUBSCRIBE -> subscriptions.unsubscribe(r);
                case CALL_SERVICE -> calls.call(r);
                case FRAGMENT -> fragment(r);
                case SET_LEVEL -> session.statusLevel(StatusLevel.of(r.requiredText("level")));
                default -> throw new IllegalStateException("op " + op.wire() + " is offered but has no handler");
            }
        } catch (ProtocolException e) {
            session.status(StatusLevel.ERROR, op.wire() + ": " + e.getMessage(), id);
        } catch (IllegalArgumentException e) {
            session.status(StatusLevel.ERROR, op.wire() + ": " + e.getMessage(), id);
        }
    }

    private void fragment(Request r) {
        String id = r.idText();
        if (id == null) {
            throw new ProtocolException("a fragment needs the 'id' of the message it is part of");
        }
        Optional<String> whole = defragmenter.add(id, r.requiredText("data"), r.integer("num", -1, 0), r.integer("total", -1, 1), System.nanoTime());
        whole.ifPresent(this::onText);
    }

    private static String head(String text) {
        return text.length() <= 120 ? text : text.substring(0, 120) + "...";
    }
}
