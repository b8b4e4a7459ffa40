package io.robomw.console.rosbridge.protocol;

import com.fasterxml.jackson.databind.node.JsonNodeFactory;
import com.fasterxml.jackson.databind.node.ObjectNode;
import io.robomw.console.rosbridge.graph.Graph;
import io.robomw.console.rosbridge.graph.Service;
import io.robomw.console.rosbridge.graph.TopicResolver;
import io.robomw.console.rosbridge.msg.Interfaces;
import io.robomw.console.rosbridge.msg.MessageReader;

import java.time.Clock;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.Executors;
import java.util.concurrent.ScheduledExecutorService;

/**
 * One client session on a small graph, for the protocol tests: {@code /chatter}
 * ({@code std_msgs/msg/String}), a service {@code /echo} ({@code std_srvs/srv/SetBool}: answers
 * its {@code data} as {@code success}) and {@code /slow} (answered when the test completes
 * {@link #slowAnswer}).
 */
final class Wiring implements AutoCloseable {

    final Interfaces interfaces = Interfaces.load();
    final Graph graph = new Graph(interfaces);
    final MessageReader reader = new MessageReader(interfaces, Clock.systemUTC());
    final ScheduledExecutorService timer = Executors.newSingleThreadScheduledExecutor(r -> new Thread(r, "rosbridge-test-timer"));
    final RecordingTransport transport = new RecordingTransport();
    final Outbox outbox;
    final ClientSession session;
    volatile CompletableFuture<ObjectNode> slowAnswer = new CompletableFuture<>();

    Wiring() {
        this(Limits.DEFAULTS);
    }

    Wiring(Limits limits) {
        graph.declare("/chatter", interfaces.message("std_msgs/msg/String"), false).addPublisher("/test");
        graph.addService(new Service("/echo", interfaces.service("std_srvs/srv/SetBool"), "/test", req -> {
            ObjectNode r = JsonNodeFactory.instance.objectNode();
            r.put("success", req.get("data").booleanValue());
            r.put("message", "echo");
            return CompletableFuture.completedFuture(r);
        }));
        graph.addService(new Service("/slow", interfaces.service("std_srvs/srv/Trigger"), "/test", req -> slowAnswer));
        outbox = new Outbox(transport, limits, timer, "test client");
        session = new ClientSession(graph, TopicResolver.NONE, reader, limits, outbox, "test client");
    }

    /** Sends one message as the client. */
    void send(String json) {
        session.onText(json);
    }

    @Override
    public void close() {
        session.close();
        timer.shutdownNow();
    }
}
