package io.robomw.console.rosbridge.protocol;

import com.fasterxml.jackson.databind.JsonNode;
import com.fasterxml.jackson.databind.node.JsonNodeFactory;
import com.fasterxml.jackson.databind.node.ObjectNode;
import io.robomw.console.rosbridge.graph.Graph;
import io.robomw.console.rosbridge.graph.Service;
import io.robomw.console.rosbridge.msg.MessageException;
import io.robomw.console.rosbridge.msg.ServiceType;
import io.robomw.console.rosbridge.msg.TypeName;
import io.robomw.console.rosbridge.msg.Wire;

import java.util.LinkedHashMap;
import java.util.Map;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.CompletionException;
import java.util.concurrent.TimeoutException;
import java.util.concurrent.atomic.AtomicInteger;

/**
 * One client's service calls: {@code call_service} in, {@code service_response} out, as
 * rosbridge_suite's ROS 2 {@code CallService} answers: {@code {op, service, values, result, id}},
 * with {@code result: false} and the error's text as {@code values} when the call failed (no such
 * service, arguments that do not fit the request type, the handler's failure, the deadline). A
 * {@code call_service} without a {@code service} cannot be answered and gets a status error
 * instead. Calls run concurrently; each is answered when its handler completes (a robot's move
 * when the robot has moved), within {@link Limits#maxCallDuration}.
 */
final class ClientCalls {

    private final Session session;
    private final AtomicInteger inFlight = new AtomicInteger();

    ClientCalls(Session session) {
        this.session = session;
    }

    void call(Request r) {
        String name = r.requiredText("service");
        Service service;
        ObjectNode request;
        try {
            service = session.graph.service(Graph.absolute(name))
                    .orElseThrow(() -> new ProtocolException("Service " + name + " does not exist"));
            String type = r.text("type");
            if (type != null && !sameType(type, service.type())) {
                throw new ProtocolException("service " + name + " has type " + service.type().name().full() + ", not " + type);
            }
            JsonNode args = r.body().get("args");
            if (args != null && args.isArray() && args.isEmpty()) {
                args = null; // roslibpy and ROS 1 clients send [] for no arguments
            }
            request = session.reader.read(args, service.type().request());
        } catch (ProtocolException | MessageException e) {
            fail(name, r.id(), e.getMessage());
            return;
        } catch (IllegalArgumentException e) {
            fail(name, r.id(), e.getMessage());
            return;
        }
        if (inFlight.incrementAndGet() > session.limits.maxCallsInFlight()) {
            inFlight.decrementAndGet();
            fail(name, r.id(), "call_service " + name + ": this client already has " + session.limits.maxCallsInFlight()
                    + " calls waiting for an answer, the most one client may");
            return;
        }
        CompletableFuture<ObjectNode> answer;
        try {
            answer = service.handler().call(request);
        } catch (RuntimeException e) {
            answer = CompletableFuture.failedFuture(e);
        }
        answer.orTimeout(session.limits.maxCallDuration().toMillis(), java.util.concurrent.TimeUnit.MILLISECONDS).whenComplete((values, failure) -> {
            inFlight.decrementAndGet();
            if (failure != null) {
                fail(name, r.id(), message(failure));
                return;
            }
            ObjectNode response;
            try {
                response = session.reader.read(values, service.type().response());
            } catch (MessageException e) {
                fail(name, r.id(), "service " + name + " gave a response that does not fit " + service.type().name().full() + ": " + e.getMessage());
                return;
            }
            respond(name, r.id(), response, true);
        });
    }

    /** @return calls of this client waiting for an answer */
    int inFlight() {
        return inFlight.get();
    }

    private void fail(String service, JsonNode id, String message) {
        session.status(StatusLevel.ERROR, "call_service " + service + ": " + message, id);
        respond(service, id, JsonNodeFactory.instance.textNode(message), false);
    }

    private void respond(String service, JsonNode id, JsonNode values, boolean result) {
        Map<String, Object> f = new LinkedHashMap<>();
        f.put("op", "service_response");
        f.put("service", service);
        f.put("values", values);
        f.put("result", result);
        if (id != null) {
            f.put("id", id);
        }
        session.outbox.reply(Wire.jsonFrame(f), id == null ? null : id.isTextual() ? id.asText() : id.toString());
    }

    private static boolean sameType(String type, ServiceType actual) {
        try {
            return TypeName.parse(type, TypeName.Kind.SRV).equals(actual.name());
        } catch (IllegalArgumentException e) {
            return false;
        }
    }

    private static String message(Throwable failure) {
        Throwable t = failure instanceof CompletionException && failure.getCause() != null ? failure.getCause() : failure;
        if (t instanceof TimeoutException) {
            return "no answer within the bridge's longest call";
        }
        return t.getMessage() != null ? t.getMessage() : t.toString();
    }
}
