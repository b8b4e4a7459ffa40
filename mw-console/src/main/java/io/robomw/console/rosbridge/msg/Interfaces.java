package io.robomw.console.rosbridge.msg;

import java.io.IOException;
import java.io.InputStream;
import java.io.UncheckedIOException;
import java.nio.charset.StandardCharsets;
import java.util.ArrayList;
import java.util.LinkedHashMap;
import java.util.LinkedHashSet;
import java.util.List;
import java.util.Map;
import java.util.Optional;
import java.util.Set;

/**
 * The ROS 2 interfaces the bridge speaks: the standard messages its topics carry
 * ({@code nav_msgs/msg/Odometry}, {@code sensor_msgs/msg/Range}, {@code tf2_msgs/msg/TFMessage}...),
 * rosapi's services, {@code std_srvs}, and RoboMW's own {@code robomw_msgs} (a robot's verbs as
 * services, messaging publications as messages). Their definitions are interface files in this
 * jar ({@code io/robomw/console/rosbridge/interfaces/PKG/msg|srv/NAME}, listed in its
 * {@code index}), written as ROS 2's own packages define them (for {@code robomw_msgs}, so that a
 * ROS 2 workspace can build the same package from them: docs/ros2.md).
 *
 * <p>A type outside this set cannot be advertised, published or subscribed to: the bridge has no
 * ROS installation to load it from (rosbridge_suite refuses a type it cannot import the same way).
 * Immutable and thread-safe.
 */
public final class Interfaces {

    private static final String ROOT = "/io/robomw/console/rosbridge/interfaces/";

    private final Map<TypeName, MessageType> messages;
    private final Map<TypeName, ServiceType> services;

    private Interfaces(Map<TypeName, MessageType> messages, Map<TypeName, ServiceType> services) {
        this.messages = Map.copyOf(messages);
        this.services = Map.copyOf(services);
    }

    /**
     * Loads the definitions in this jar and checks that every field's type is defined.
     *
     * @return the interfaces
     * @throws IllegalStateException if a definition is missing or does not parse (a broken jar)
     */
    public static Interfaces load() {
        Map<TypeName, MessageType> messages = new LinkedHashMap<>();
        Map<TypeName, ServiceType> services = new LinkedHashMap<>();
        for (String path : resource("index").lines().map(String::strip).filter(l -> !l.isEmpty()).toList()) {
            String[] parts = path.split("/");
            if (parts.length != 3 || !parts[2].contains(".")) {
                throw new IllegalStateException("the bridge's interface index lists '" + path + "', which is not PKG/msg|srv/NAME.msg|srv");
            }
            String base = parts[2].substring(0, parts[2].lastIndexOf('.'));
            String text = resource(path);
            try {
                if (parts[1].equals("msg")) {
                    TypeName n = new TypeName(parts[0], TypeName.Kind.MSG, base);
                    messages.put(n, InterfaceParser.message(n, text));
                } else {
                    TypeName n = new TypeName(parts[0], TypeName.Kind.SRV, base);
                    services.put(n, InterfaceParser.service(n, text));
                }
            } catch (IllegalArgumentException e) {
                throw new IllegalStateException("the bridge's interface " + path + " does not parse: " + e.getMessage(), e);
            }
        }
        Interfaces i = new Interfaces(messages, services);
        i.checkReferences();
        return i;
    }

    /**
     * @param type a message type's name, either spelling
     * @return its definition, if the bridge knows it
     */
    public Optional<MessageType> message(TypeName type) {
        return Optional.ofNullable(messages.get(type));
    }

    /**
     * @param type a message type as a client writes it
     * @return its definition
     * @throws IllegalArgumentException if it is not a type name, or not one the bridge knows (naming the packages it knows)
     */
    public MessageType message(String type) {
        TypeName n = TypeName.parse(type, TypeName.Kind.MSG);
        return message(n).orElseThrow(() -> new IllegalArgumentException("unknown message type " + type + ": this bridge has no ROS installation and "
                + "knows the messages of " + packages(messages.keySet()) + " (docs/ros2.md lists them)"));
    }

    /**
     * @param type a service type's name
     * @return its definition, if the bridge knows it
     */
    public Optional<ServiceType> service(TypeName type) {
        return Optional.ofNullable(services.get(type));
    }

    /**
     * @param type a service type as a client writes it
     * @return its definition
     * @throws IllegalArgumentException if the bridge does not know it
     */
    public ServiceType service(String type) {
        TypeName n = TypeName.parse(type, TypeName.Kind.SRV);
        return service(n).orElseThrow(() -> new IllegalArgumentException("unknown service type " + type + ": this bridge knows the services of "
                + packages(services.keySet())));
    }

    /**
     * The type definitions rosapi's {@code message_details} gives: the type, then every message
     * type its fields use, each once, depth first.
     *
     * @param type a message type
     * @return its definitions
     */
    public List<MessageType> withDependencies(MessageType type) {
        List<MessageType> out = new ArrayList<>();
        collect(type, new LinkedHashSet<>(), out);
        return out;
    }

    /**
     * The full text of a type as rosapi's {@code topics_and_raw_types} gives it ({@code gendeps --cat}):
     * its definition, then each type it uses after a line of {@code =} and {@code MSG: pkg/Type}.
     *
     * @param type a message type
     * @return the text
     */
    public String fullText(MessageType type) {
        StringBuilder b = new StringBuilder(type.definition());
        List<MessageType> all = withDependencies(type);
        for (MessageType dep : all.subList(1, all.size())) {
            b.append("\n================================================================================\nMSG: ").append(dep.name().shortName())
                    .append('\n').append(dep.definition());
        }
        return b.toString();
    }

    private void collect(MessageType type, Set<TypeName> seen, List<MessageType> out) {
        if (!seen.add(type.name())) {
            return;
        }
        out.add(type);
        for (Field f : type.fields()) {
            if (f.message() != null) {
                collect(messages.get(f.message()), seen, out);
            }
        }
    }

    private void checkReferences() {
        List<MessageType> all = new ArrayList<>(messages.values());
        for (ServiceType s : services.values()) {
            all.add(s.request());
            all.add(s.response());
        }
        for (MessageType m : all) {
            for (Field f : m.fields()) {
                if (f.message() != null && !messages.containsKey(f.message())) {
                    throw new IllegalStateException("the bridge's interface " + m.name() + " uses " + f.message() + " in field " + f.name()
                            + ", which is not defined in its index");
                }
            }
        }
    }

    private static String packages(Set<TypeName> names) {
        return String.join(", ", names.stream().map(TypeName::pkg).distinct().sorted().toList());
    }

    private static String resource(String path) {
        try (InputStream in = Interfaces.class.getResourceAsStream(ROOT + path)) {
            if (in == null) {
                throw new IllegalStateException("the bridge's interface definition " + path + " is missing from its jar");
            }
            return new String(in.readAllBytes(), StandardCharsets.UTF_8);
        } catch (IOException e) {
            throw new UncheckedIOException(e);
        }
    }
}
