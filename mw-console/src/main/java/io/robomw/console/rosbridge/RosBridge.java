package io.robomw.console.rosbridge;

import io.robomw.api.Messaging;
import io.robomw.api.spi.FailurePolicy;
import io.robomw.console.rosbridge.graph.Graph;
import io.robomw.console.rosbridge.graph.TopicResolver;
import io.robomw.console.rosbridge.messaging.MessagingBridge;
import io.robomw.console.rosbridge.msg.Interfaces;
import io.robomw.console.rosbridge.msg.MessageReader;
import io.robomw.console.rosbridge.protocol.Limits;
import io.robomw.console.rosbridge.robot.RobotNode;
import io.robomw.console.rosbridge.robot.RobotServices;
import io.robomw.console.rosbridge.robot.Threads;
import io.robomw.console.rosbridge.robot.TransformFeed;
import io.robomw.console.rosbridge.rosapi.RosApi;
import io.robomw.console.rosbridge.server.RosBridgeServer;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.io.IOException;
import java.net.URI;
import java.time.Clock;
import java.util.ArrayList;
import java.util.HashMap;
import java.util.List;
import java.util.Map;
import java.util.Objects;
import java.util.concurrent.ExecutorService;
import java.util.concurrent.LinkedBlockingQueue;
import java.util.concurrent.ScheduledThreadPoolExecutor;
import java.util.concurrent.ThreadFactory;
import java.util.concurrent.ThreadPoolExecutor;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicInteger;

/**
 * A rosbridge v2 endpoint: RoboMW robots as ROS 2 topics and services for the clients of
 * rosbridge_suite's protocol (roslibpy, roslibjs, ROSLibSharp, a ROS 2 machine's own rosbridge
 * client), with no ROS installation anywhere: RoboMW is the ROS side of the socket.
 *
 * <ul>
 *   <li>each robot as a node with {@code /<ns>/odom}, {@code /<ns>/cmd_vel}, a {@code Range} topic
 *   per range finder, {@code /<ns>/joint_states}, and its verbs as services ({@link RobotNode},
 *   {@link RobotServices}); {@code /tf} and {@code /tf_static} for all ({@link TransformFeed});</li>
 *   <li>rosapi's services ({@link RosApi});</li>
 *   <li>RoboMW messaging topics as {@code /robomw/T}, both ways, when given a messaging node
 *   ({@link MessagingBridge});</li>
 *   <li>topics clients advertise, between clients.</li>
 * </ul>
 *
 * The protocol and its choices where rosbridge_suite's ROS 2 server and this one differ are in
 * {@link io.robomw.console.rosbridge.protocol.ClientSession} and docs/ros2.md. Safety it adds: a
 * loopback bind unless a token is given ({@link RosBridgeServer}), and {@link Limits} on every
 * client.
 *
 * <h2>Threads</h2>
 * {@code rosbridge-http-N} (Jetty: the connections), {@code rosbridge-feed-N} (two: samples,
 * throttles, pings), {@code rosbridge-call-N} (up to eight: calls that wait for a network, one at
 * a time per remote robot and kind). {@link #close()} stops them all; the robots stay open.
 */
public final class RosBridge implements AutoCloseable {

    private static final Logger LOG = LoggerFactory.getLogger(RosBridge.class);
    /** rosbridge_suite's port. */
    public static final int DEFAULT_PORT = 9090;
    /** The environment variable a command reads the access token from. */
    public static final String TOKEN_ENV = "MW_ROSBRIDGE_TOKEN";

    private final Graph graph;
    private final List<RobotNode> nodes;
    private final TransformFeed tf;
    private final MessagingBridge messaging;
    private final RosBridgeServer server;
    private final ScheduledThreadPoolExecutor feeds;
    private final ExecutorService blocking;

    private RosBridge(Graph graph, List<RobotNode> nodes, TransformFeed tf, MessagingBridge messaging, RosBridgeServer server,
                      ScheduledThreadPoolExecutor feeds, ExecutorService blocking) {
        this.graph = graph;
        this.nodes = nodes;
        this.tf = tf;
        this.messaging = messaging;
        this.server = server;
        this.feeds = feeds;
        this.blocking = blocking;
    }

    /** @return a builder: no robots, loopback, port {@value #DEFAULT_PORT} */
    public static Builder builder() {
        return new Builder();
    }

    /** @return where clients connect, {@code ws://HOST:PORT/} (without the token) */
    public URI address() {
        return server.address();
    }

    /** @return the port */
    public int port() {
        return server.port();
    }

    /** @return clients connected now */
    public int clients() {
        return server.clients();
    }

    /** @return the topics and services offered (for tests and tools) */
    public Graph graph() {
        return graph;
    }

    /** @return each robot's ROS namespace, by robot name */
    public Map<String, String> namespaces() {
        Map<String, String> m = new java.util.LinkedHashMap<>();
        for (RobotNode n : nodes) {
            m.put(n.robot().robot().name(), n.namespace());
        }
        return m;
    }

    /** Stops serving: clients are disconnected, sampling stops; the robots and the messaging node stay open. */
    @Override
    public void close() {
        server.close();
        tf.close();
        nodes.forEach(RobotNode::close);
        if (messaging != null) {
            messaging.close();
        }
        feeds.shutdownNow();
        blocking.shutdownNow();
        try {
            feeds.awaitTermination(5, TimeUnit.SECONDS);
            blocking.awaitTermination(5, TimeUnit.SECONDS);
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
        }
    }

    /** Builds and starts a bridge. */
    public static final class Builder {
        private final List<BridgedRobot> robots = new ArrayList<>();
        private Messaging messagingNode;
        private String bind = "127.0.0.1";
        private int port = DEFAULT_PORT;
        private String token;
        private final List<String> origins = new ArrayList<>();
        private Limits limits = Limits.DEFAULTS;
        private Rates rates = Rates.DEFAULTS;
        private FailurePolicy failures = FailurePolicy.logging();
        private Clock clock = Clock.systemUTC();
        private String echoPath;

        private Builder() {
        }

        /**
         * @param robot a robot to offer; robots' namespaces must differ
         * @return this
         */
        public Builder robot(BridgedRobot robot) {
            robots.add(Objects.requireNonNull(robot, "robot"));
            return this;
        }

        /**
         * @param messaging the node RoboMW topics are bridged through ({@code /robomw/T}); none by default
         * @return this
         */
        public Builder messaging(Messaging messaging) {
            this.messagingNode = messaging;
            return this;
        }

        /**
         * @param address where to listen: {@code 127.0.0.1} (the default) keeps it to this machine;
         *                another address needs a {@link #token}
         * @param port    the port, 0 for a free one
         * @return this
         */
        public Builder listen(String address, int port) {
            if (port < 0 || port > 65535) {
                throw new IllegalArgumentException("a rosbridge port is 0 (a free one) to 65535, got " + port);
            }
            this.bind = Objects.requireNonNull(address, "address");
            this.port = port;
            return this;
        }

        /**
         * @param token the access token clients must give (at least 16 characters), or {@code null} for none
         * @return this
         */
        public Builder token(String token) {
            this.token = token;
            return this;
        }

        /**
         * @param origin a web origin whose pages may connect ({@code https://dashboard.example.org}, {@code *} for any)
         * @return this
         */
        public Builder allowOrigin(String origin) {
            origins.add(Objects.requireNonNull(origin, "origin"));
            return this;
        }

        /**
         * @param limits the bounds on clients
         * @return this
         */
        public Builder limits(Limits limits) {
            this.limits = Objects.requireNonNull(limits, "limits");
            return this;
        }

        /**
         * @param rates how often robots are sampled
         * @return this
         */
        public Builder rates(Rates rates) {
            this.rates = Objects.requireNonNull(rates, "rates");
            return this;
        }

        /**
         * @param failures where the feeds' unexpected failures go
         * @return this
         */
        public Builder failures(FailurePolicy failures) {
            this.failures = Objects.requireNonNull(failures, "failures");
            return this;
        }

        /**
         * @param clock the clock messages are stamped with (the wall clock by default)
         * @return this
         */
        public Builder clock(Clock clock) {
            this.clock = Objects.requireNonNull(clock, "clock");
            return this;
        }

        /**
         * @param path a path on the bridge's server that echoes text frames, for measuring the
         *             bridge against the bare server (bench/rosbridge); none by default
         * @return this
         */
        public Builder echo(String path) {
            this.echoPath = path;
            return this;
        }

        /**
         * Declares every robot's topics and services and starts serving.
         *
         * @return the running bridge
         * @throws IOException              if the port cannot be used
         * @throws IllegalArgumentException if two robots share a namespace, or the bind needs a token
         */
        public RosBridge start() throws IOException {
            Map<String, String> seen = new HashMap<>();
            for (BridgedRobot r : robots) {
                String ns = Graph.namespace(r.robot().name());
                String other = seen.putIfAbsent(ns, r.robot().name());
                if (other != null) {
                    throw new IllegalArgumentException("robots '" + other + "' and '" + r.robot().name() + "' would both be /" + ns
                            + " in ROS (a ROS name holds only letters, digits and _); rename one");
                }
            }
            Interfaces interfaces = Interfaces.load();
            Graph graph = new Graph(interfaces);
            MessageReader reader = new MessageReader(interfaces, clock);
            ScheduledThreadPoolExecutor feeds = new ScheduledThreadPoolExecutor(2, named("rosbridge-feed"));
            feeds.setRemoveOnCancelPolicy(true);
            ThreadPoolExecutor blocking = new ThreadPoolExecutor(8, 8, 30, TimeUnit.SECONDS, new LinkedBlockingQueue<>(), named("rosbridge-call"));
            blocking.allowCoreThreadTimeOut(true);
            Threads threads = new Threads(feeds, blocking, failures);
            List<RobotNode> nodes = new ArrayList<>();
            TransformFeed tf = null;
            MessagingBridge bridge = null;
            try {
                RosApi.offer(graph, clock);
                for (BridgedRobot r : robots) {
                    RobotNode n = RobotNode.start(r, graph, rates.odometryHz(), rates::sensorRate, threads, clock);
                    nodes.add(n);
                    RobotServices.offer(n, graph, threads);
                }
                tf = TransformFeed.start(nodes, graph, rates.odometryHz(), threads, clock);
                bridge = messagingNode == null ? null : new MessagingBridge(messagingNode, graph);
                TopicResolver resolver = bridge == null ? TopicResolver.NONE : bridge;
                RosBridgeServer server = RosBridgeServer.start(graph, resolver, reader, limits, feeds, token, origins, bind, port, echoPath);
                LOG.info("rosbridge serving at {} (robots: {})", server.address(), nodes.stream().map(RobotNode::namespace).toList());
                return new RosBridge(graph, List.copyOf(nodes), tf, bridge, server, feeds, blocking);
            } catch (IOException | RuntimeException e) {
                if (tf != null) {
                    tf.close();
                }
                nodes.forEach(RobotNode::close);
                if (bridge != null) {
                    bridge.close();
                }
                feeds.shutdownNow();
                blocking.shutdownNow();
                throw e;
            }
        }

        private static ThreadFactory named(String prefix) {
            AtomicInteger n = new AtomicInteger();
            return r -> {
                Thread t = new Thread(r, prefix + "-" + n.incrementAndGet());
                t.setDaemon(true);
                return t;
            };
        }
    }
}
