package io.robomw.console.rosbridge.rosapi;

import com.fasterxml.jackson.databind.JsonNode;
import com.fasterxml.jackson.databind.node.ArrayNode;
import com.fasterxml.jackson.databind.node.JsonNodeFactory;
import com.fasterxml.jackson.databind.node.ObjectNode;
import io.robomw.console.rosbridge.graph.Graph;
import io.robomw.console.rosbridge.graph.Service;
import io.robomw.console.rosbridge.graph.Topic;
import io.robomw.console.rosbridge.msg.Constant;
import io.robomw.console.rosbridge.msg.Field;
import io.robomw.console.rosbridge.msg.Interfaces;
import io.robomw.console.rosbridge.msg.MessageReader;
import io.robomw.console.rosbridge.msg.MessageType;
import io.robomw.console.rosbridge.msg.ServiceType;
import io.robomw.console.rosbridge.msg.TypeName;

import java.time.Clock;
import java.util.Collection;
import java.util.List;
import java.util.Optional;
import java.util.concurrent.CompletableFuture;
import java.util.function.Function;

/**
 * The {@code /rosapi/*} services clients call first to see what is there (roslibpy's
 * {@code get_topics}, {@code get_topic_type}, {@code get_services}, {@code get_nodes}...), with
 * rosapi's ROS 2 types ({@code rosapi_msgs/srv/Topics} etc.) and answers:
 *
 * <ul>
 *   <li>topics and services with their types in ROS 2's spelling ({@code nav_msgs/msg/Odometry});</li>
 *   <li>an unknown topic's or service's type as {@code ""}, as rosapi answers;</li>
 *   <li>type definitions ({@code message_details}) as rosapi's {@code TypeDef}s: the type and every
 *   message type it uses, field types in ROS 2's names ({@code double}, {@code std_msgs/Header}),
 *   {@code fieldarraylen} -1 for a single value, the length of a fixed array, 0 for a sequence;</li>
 *   <li>{@code get_ros_version}: version 2, distro {@code jazzy} (the distro whose message
 *   definitions the bridge's match: no {@code variance} in {@code sensor_msgs/msg/Range});</li>
 *   <li>parameters: the bridge has none ({@code get_param} answers the default given).</li>
 * </ul>
 * All of them answer at once, from the graph as it is.
 */
public final class RosApi {

    /** The node rosapi's services belong to. */
    public static final String NODE = "/rosapi";
    /** The ROS version the bridge speaks. */
    public static final int ROS_VERSION = 2;
    /** The distro whose message definitions the bridge's match. */
    public static final String DISTRO = "jazzy";

    private static final JsonNodeFactory NODES = JsonNodeFactory.instance;

    private final Graph graph;
    private final Interfaces interfaces;
    private final Clock clock;

    private RosApi(Graph graph, Clock clock) {
        this.graph = graph;
        this.interfaces = graph.interfaces();
        this.clock = clock;
    }

    /**
     * Offers rosapi's services in a graph.
     *
     * @param graph the graph they describe and are offered in
     * @param clock what {@code get_time} answers
     */
    public static void offer(Graph graph, Clock clock) {
        RosApi api = new RosApi(graph, clock);
        api.add("topics", "Topics", req -> {
            ObjectNode r = NODES.objectNode();
            List<Topic> topics = graph.topics();
            r.set("topics", strings(topics.stream().map(Topic::name).toList()));
            r.set("types", strings(topics.stream().map(t -> t.type().name().full()).toList()));
            return r;
        });
        api.add("topics_for_type", "TopicsForType", req -> {
            Optional<TypeName> type = api.messageName(req.get("type").asText());
            ObjectNode r = NODES.objectNode();
            r.set("topics", strings(graph.topics().stream().filter(t -> type.isPresent() && t.type().name().equals(type.get())).map(Topic::name).toList()));
            return r;
        });
        api.add("topics_and_raw_types", "TopicsAndRawTypes", req -> {
            ObjectNode r = NODES.objectNode();
            List<Topic> topics = graph.topics();
            r.set("topics", strings(topics.stream().map(Topic::name).toList()));
            r.set("types", strings(topics.stream().map(t -> t.type().name().full()).toList()));
            r.set("typedefs_full_text", strings(topics.stream().map(t -> api.interfaces.fullText(t.type())).toList()));
            return r;
        });
        api.add("topic_type", "TopicType", req -> {
            ObjectNode r = NODES.objectNode();
            r.put("type", topic(graph, req.get("topic").asText()).map(t -> t.type().name().full()).orElse(""));
            return r;
        });
        api.add("services", "Services", req -> {
            ObjectNode r = NODES.objectNode();
            r.set("services", strings(graph.services().stream().map(Service::name).toList()));
            return r;
        });
        api.add("services_for_type", "ServicesForType", req -> {
            Optional<TypeName> type = api.serviceName(req.get("type").asText());
            ObjectNode r = NODES.objectNode();
            r.set("services", strings(graph.services().stream().filter(s -> type.isPresent() && s.type().name().equals(type.get()))
                    .map(Service::name).toList()));
            return r;
        });
        api.add("service_type", "ServiceType", req -> {
            ObjectNode r = NODES.objectNode();
            r.put("type", service(graph, req.get("service").asText()).map(s -> s.type().name().full()).orElse(""));
            return r;
        });
        api.add("nodes", "Nodes", req -> {
            ObjectNode r = NODES.objectNode();
            r.set("nodes", strings(graph.nodes()));
            return r;
        });
        api.add("node_details", "NodeDetails", req -> {
            String node = req.get("node").asText();
            ObjectNode r = NODES.objectNode();
            r.set("subscribing", strings(graph.topics().stream().filter(t -> t.subscribers().contains(node)).map(Topic::name).toList()));
            r.set("publishing", strings(graph.topics().stream().filter(t -> t.publishers().contains(node)).map(Topic::name).toList()));
            r.set("services", strings(graph.services().stream().filter(s -> s.node().equals(node)).map(Service::name).toList()));
            return r;
        });
        api.add("publishers", "Publishers", req -> {
            ObjectNode r = NODES.objectNode();
            r.set("publishers", strings(topic(graph, req.get("topic").asText()).map(t -> sorted(t.publishers())).orElse(List.of())));
            return r;
        });
        api.add("subscribers", "Subscribers", req -> {
            ObjectNode r = NODES.objectNode();
            r.set("subscribers", strings(topic(graph, req.get("topic").asText()).map(t -> sorted(t.subscribers())).orElse(List.of())));
            return r;
        });
        api.add("service_providers", "ServiceProviders", req -> {
            ObjectNode r = NODES.objectNode();
            r.set("providers", strings(service(graph, req.get("service").asText()).map(s -> List.of(s.node())).orElse(List.of())));
            return r;
        });
        api.add("service_node", "ServiceNode", req -> {
            ObjectNode r = NODES.objectNode();
            r.put("node", service(graph, req.get("service").asText()).map(Service::node).orElse(""));
            return r;
        });
        api.add("message_details", "MessageDetails", req -> {
            MessageType type = api.interfaces.message(req.get("type").asText());
            return typedefs(api.interfaces.withDependencies(type));
        });
        api.add("service_request_details", "ServiceRequestDetails", req -> {
            ServiceType type = api.interfaces.service(req.get("type").asText());
            return typedefs(api.interfaces.withDependencies(type.request()));
        });
        api.add("service_response_details", "ServiceResponseDetails", req -> {
            ServiceType type = api.interfaces.service(req.get("type").asText());
            return typedefs(api.interfaces.withDependencies(type.response()));
        });
        api.add("get_time", "GetTime", req -> {
            ObjectNode r = NODES.objectNode();
            r.set("time", MessageReader.time(clock.instant()));
            return r;
        });
        api.add("get_ros_version", "GetROSVersion", req -> {
            ObjectNode r = NODES.objectNode();
            r.put("version", ROS_VERSION);
            r.put("distro", DISTRO);
            return r;
        });
        api.add("action_servers", "GetActionServers", req -> {
            ObjectNode r = NODES.objectNode();
            r.set("action_servers", NODES.arrayNode());
            return r;
        });
        api.add("get_param_names", "GetParamNames", req -> {
            ObjectNode r = NODES.objectNode();
            r.set("names", NODES.arrayNode());
            return r;
        });
        api.add("get_param", "GetParam", req -> {
            ObjectNode r = NODES.objectNode();
            r.put("value", req.get("default_value").asText());
            return r;
        });
        api.add("has_param", "HasParam", req -> {
            ObjectNode r = NODES.objectNode();
            r.put("exists", false);
            return r;
        });
    }

    private void add(String name, String type, Function<ObjectNode, ObjectNode> answer) {
        ServiceType t = interfaces.service(new TypeName("rosapi_msgs", TypeName.Kind.SRV, type))
                .orElseThrow(() -> new IllegalStateException("the bridge's interfaces lack rosapi_msgs/srv/" + type));
        graph.addService(new Service("/rosapi/" + name, t, NODE, req -> {
            try {
                return CompletableFuture.completedFuture(answer.apply(req));
            } catch (RuntimeException e) {
                return CompletableFuture.failedFuture(e);
            }
        }));
    }

    private Optional<TypeName> messageName(String text) {
        try {
            return Optional.of(TypeName.parse(text, TypeName.Kind.MSG));
        } catch (IllegalArgumentException e) {
            return Optional.empty();
        }
    }

    private Optional<TypeName> serviceName(String text) {
        try {
            return Optional.of(TypeName.parse(text, TypeName.Kind.SRV));
        } catch (IllegalArgumentException e) {
            return Optional.empty();
        }
    }

    private static Optional<Topic> topic(Graph graph, String name) {
        try {
            return graph.topic(name);
        } catch (IllegalArgumentException e) {
            return Optional.empty();
        }
    }

    private static Optional<Service> service(Graph graph, String name) {
        try {
            return graph.service(name);
        } catch (IllegalArgumentException e) {
            return Optional.empty();
        }
    }

    /**
     * @param types a type and the types it uses
     * @return {@code {typedefs: [...]}} in rosapi's {@code TypeDef} shape
     */
    static ObjectNode typedefs(List<MessageType> types) {
        ArrayNode defs = NODES.arrayNode();
        for (MessageType t : types) {
            defs.add(typedef(t));
        }
        ObjectNode r = NODES.objectNode();
        r.set("typedefs", defs);
        return r;
    }

    /**
     * @param t a message type
     * @return its rosapi {@code TypeDef}
     */
    static ObjectNode typedef(MessageType t) {
        ObjectNode d = NODES.objectNode();
        d.put("type", t.name().shortName());
        ArrayNode names = d.putArray("fieldnames");
        ArrayNode types = d.putArray("fieldtypes");
        ArrayNode lengths = d.putArray("fieldarraylen");
        ArrayNode examples = d.putArray("examples");
        for (Field f : t.fields()) {
            names.add(f.name());
            types.add(f.elementTypeName());
            lengths.add(f.arrayLength());
            examples.add(example(f));
        }
        ArrayNode constNames = d.putArray("constnames");
        ArrayNode constValues = d.putArray("constvalues");
        for (Constant c : t.constants()) {
            constNames.add(c.name());
            constValues.add(c.value());
        }
        return d;
    }

    /** rosapi's example: {@code []} for an array, {@code {}} for a message, the default as Python prints it for a value. */
    private static String example(Field f) {
        if (f.array()) {
            return "[]";
        }
        if (f.message() != null) {
            return "{}";
        }
        JsonNode d = f.defaultValue();
        return switch (f.primitive()) {
            case BOOL -> "False";
            case STRING -> "";
            case FLOAT32, FLOAT64 -> d == null ? "0.0" : String.valueOf(d.doubleValue());
            default -> d == null ? "0" : String.valueOf(d.longValue());
        };
    }

    private static ArrayNode strings(Collection<String> values) {
        ArrayNode a = NODES.arrayNode();
        values.forEach(a::add);
        return a;
    }

    private static List<String> sorted(Collection<String> values) {
        return values.stream().sorted().toList();
    }
}
