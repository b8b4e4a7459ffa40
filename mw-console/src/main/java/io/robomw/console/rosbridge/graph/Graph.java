package io.robomw.console.rosbridge.graph;

import io.robomw.console.rosbridge.msg.Interfaces;
import io.robomw.console.rosbridge.msg.MessageType;

import java.util.Comparator;
import java.util.List;
import java.util.Optional;
import java.util.TreeSet;
import java.util.concurrent.ConcurrentHashMap;
import java.util.regex.Pattern;

/**
 * The topics and services the bridge offers, as a ROS 2 graph would list them: the robots' own
 * (declared when the bridge starts), rosapi's, RoboMW messaging topics while they are bridged, and
 * topics clients advertise. A topic has one type; using it with another is refused, as ROS 2
 * refuses a publisher of a second type. Thread-safe.
 */
public final class Graph {

    /** The node clients' publishers and subscriptions belong to, as rosbridge_suite's own node is named. */
    public static final String BRIDGE_NODE = "/rosbridge_websocket";
    /** Longest topic or service name taken. */
    public static final int MAX_NAME_LENGTH = 256;

    private static final Pattern NAME = Pattern.compile("(/[A-Za-z0-9_~.\\-{}]+)+");
    private static final Pattern NOT_ROS = Pattern.compile("[^A-Za-z0-9_]");

    private final Interfaces interfaces;
    private final ConcurrentHashMap<String, Topic> topics = new ConcurrentHashMap<>();
    private final ConcurrentHashMap<String, Service> services = new ConcurrentHashMap<>();

    /** @param interfaces the types topics and services may have */
    public Graph(Interfaces interfaces) {
        this.interfaces = interfaces;
    }

    /** @return the types topics and services may have */
    public Interfaces interfaces() {
        return interfaces;
    }

    /**
     * Makes a topic known, or returns it if it is known with the same type.
     *
     * @param name    its name, absolute or relative (relative names are taken from {@code /})
     * @param type    its type
     * @param latched whether new subscribers get its last message (only when it is created)
     * @return the topic
     * @throws IllegalArgumentException if the name is not a topic name, or the topic exists with another type
     */
    public Topic declare(String name, MessageType type, boolean latched) {
        String n = absolute(name);
        Topic t = topics.computeIfAbsent(n, k -> new Topic(k, type, latched));
        if (!t.type().name().equals(type.name())) {
            throw new IllegalArgumentException("topic " + n + " already has type " + t.type().name().full() + " and cannot be used as "
                    + type.name().full());
        }
        return t;
    }

    /**
     * @param name a topic's name
     * @return the topic, if known
     */
    public Optional<Topic> topic(String name) {
        return Optional.ofNullable(topics.get(absolute(name)));
    }

    /**
     * Forgets a topic no one publishes on and nothing receives (a client's topic after it unadvertised).
     *
     * @param topic the topic
     */
    public void release(Topic topic) {
        topics.computeIfPresent(topic.name(), (k, t) -> t == topic && t.abandoned() ? null : t);
    }

    /**
     * @param service a service to offer
     * @throws IllegalArgumentException if a service of that name exists
     */
    public void addService(Service service) {
        String n = absolute(service.name());
        if (services.putIfAbsent(n, service) != null) {
            throw new IllegalArgumentException("service " + n + " is offered twice");
        }
    }

    /**
     * @param name a service's name
     * @return the service, if offered
     */
    public Optional<Service> service(String name) {
        return Optional.ofNullable(services.get(absolute(name)));
    }

    /** @return every topic, by name */
    public List<Topic> topics() {
        return topics.values().stream().sorted(Comparator.comparing(Topic::name)).toList();
    }

    /** @return every service, by name */
    public List<Service> services() {
        return services.values().stream().sorted(Comparator.comparing(Service::name)).toList();
    }

    /** @return every node that publishes, receives or offers something, by name */
    public List<String> nodes() {
        TreeSet<String> nodes = new TreeSet<>();
        nodes.add(BRIDGE_NODE);
        for (Topic t : topics.values()) {
            nodes.addAll(t.publishers());
            nodes.addAll(t.subscribers());
        }
        for (Service s : services.values()) {
            nodes.add(s.node());
        }
        return List.copyOf(nodes);
    }

    /**
     * @param name a topic or service name as a client writes it
     * @return it made absolute ({@code odom} is {@code /odom})
     * @throws IllegalArgumentException if it is empty, too long, or has characters, empty parts or
     *                                  a trailing slash no ROS name has
     */
    public static String absolute(String name) {
        if (name == null || name.isEmpty()) {
            throw new IllegalArgumentException("no name given: a topic or service is named /like/this");
        }
        String n = name.startsWith("/") ? name : "/" + name;
        if (n.length() > MAX_NAME_LENGTH || !NAME.matcher(n).matches()) {
            throw new IllegalArgumentException("'" + (name.length() > 80 ? name.substring(0, 80) + "..." : name) + "' is not a topic or service name: "
                    + "parts of letters, digits and _ separated by single slashes, at most " + MAX_NAME_LENGTH + " characters");
        }
        return n;
    }

    /**
     * @param robotName a RoboMW robot's name ({@code nxt-1})
     * @return the ROS namespace its topics and frames are under: each character a ROS name may not
     *         hold becomes {@code _}, and a leading digit gets a {@code _} before it ({@code nxt_1})
     */
    public static String namespace(String robotName) {
        String n = NOT_ROS.matcher(robotName).replaceAll("_");
        return n.isEmpty() || Character.isDigit(n.charAt(0)) ? "_" + n : n;
    }
}
