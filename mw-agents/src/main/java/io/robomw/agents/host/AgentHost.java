package io.robomw.agents.host;

import io.robomw.agents.host.code.StateCodec;
import io.robomw.agents.host.store.JournalStore;
import io.robomw.agents.host.store.MemoryStore;
import io.robomw.agents.messaging.MessagingNode;
import io.robomw.agents.messaging.MessagingSettings;
import io.robomw.agents.messaging.security.TlsSettings;
import io.robomw.api.Agency;
import io.robomw.api.AgentRef;
import io.robomw.api.Itinerary;
import io.robomw.api.Messaging;
import io.robomw.api.MessagingException;
import io.robomw.api.Robot;
import io.robomw.api.spi.FailurePolicy;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import javax.net.ssl.SSLContext;
import java.io.IOException;
import java.io.ObjectInputFilter;
import java.io.Serializable;
import java.net.InetAddress;
import java.net.InetSocketAddress;
import java.net.ServerSocket;
import java.nio.file.Path;
import java.rmi.NoSuchObjectException;
import java.rmi.registry.LocateRegistry;
import java.rmi.registry.Registry;
import java.rmi.server.ExportException;
import java.rmi.server.UnicastRemoteObject;
import java.time.Duration;
import java.util.List;
import java.util.Objects;
import java.util.Optional;
import java.util.concurrent.TimeUnit;

/**
 * An agent host (paper section III.A.4, after the Aglets server): an RMI server, bound to a
 * robot or to none, that receives mobile agents, runs each stop of theirs on a named thread with
 * its robot, sends them on along their itineraries, and tells their homes how they are doing. Its
 * {@link #agency()} sends agents from here: they have this host as their home, where their results
 * arrive.
 *
 * <p><b>No agent lost, none duplicated.</b> A hop completes only when the receiving host has
 * stored the agent (durably, with a {@link JournalStore}) and acknowledged; until then the sender
 * keeps it. Every hop is numbered and a host never accepts a hop it has already seen, so a
 * retried transfer is not run twice. A stop is marked started before its work begins; a host
 * killed during the work resumes the agent after the stop (recorded as
 * {@link Itinerary.Outcome#INTERRUPTED}) rather than run it twice. A transfer that may have
 * reached the other host (the connection broke mid-call) is retried to that same host until it
 * answers, never sent elsewhere.
 *
 * <p><b>Trust.</b> Java 17+ has no sandbox for loaded code: an agent runs with the host's full
 * rights. So a host takes agents only from peers that prove the shared {@link ClusterKey}
 * (challenge/response, HMAC-SHA256, and the host proves it back) or, with TLS, present a
 * certificate its trust store vouches for; every call is MAC'd and numbered; state is read only
 * through {@link StateCodec}'s filter (the agent's own archive, an allow-list, size and depth
 * limits); archives are checked against their SHA-256.
 *
 * <p><b>Parts.</b> This class starts and stops the host and is its public face; the work is done
 * by package-private parts that share a {@link HostState}: {@link Calls} serves the verified calls
 * ({@link HostEndpoint} checks them), {@link Transfers} takes agents in, {@link Trips} runs their
 * stops and sends them on through {@link HopSender}, {@link Home} and {@link AgentRequests} are
 * the home side of the agents sent from here, {@link OwedEvents} tells homes what happened,
 * {@link Recovery} resumes what the store held, {@link CodeLoaders} keeps agents' code,
 * {@link Peers} calls other hosts, {@link RobotTurns} lends the robot to one stop at a time, and
 * {@link Bodies} lays out the call bodies.
 */
public final class AgentHost implements AutoCloseable {

    private static final Logger LOG = LoggerFactory.getLogger(AgentHost.class);

    private final String name;
    private final String bind;
    private final int requestedPort;
    private final HostMessaging messaging;
    private final ClusterKey key;
    private final TlsSettings tls;
    private final Path storeDir;
    private final Duration stopGrace;
    private final Duration endpointSpin;
    private final HostState state;
    private final RobotTurns robot;
    private final CodeLoaders code;
    private final OwedEvents owed;
    private final Trips trips;
    private final Home home;
    private final Calls calls;
    private final HostSockets.Counters counters = new HostSockets.Counters();
    private final Peers peers;
    private final boolean wire;
    private final int wirePort;
    private final Duration wireSpin;
    private final Duration wireReadSpin;
    private final boolean version2Only;
    private final boolean olderHosts;
    private final WireServer.Limits wireLimits;
    private final java.util.concurrent.ThreadFactory wireThreads;
    private HostEndpoint endpoint;
    private WireServer wireServer;
    private Registry registry;

    private AgentHost(Builder b) {
        this.name = b.name;
        this.bind = b.bind;
        this.requestedPort = b.port;
        this.key = b.key;
        this.tls = b.tls;
        this.storeDir = b.storeDir;
        this.stopGrace = b.stopGrace;
        this.endpointSpin = b.endpointSpin;
        this.state = new HostState(this, b.name, b.robot, new StateCodec(b.allowed, b.maxStateBytes), (int) b.callTimeout.toMillis(),
                b.runnerSpin, b.failures);
        this.robot = new RobotTurns(b.name, b.robot);
        this.code = new CodeLoaders(state);
        this.wire = b.wire && !b.version2Only;
        this.wirePort = b.wirePort;
        this.wireSpin = b.wireSpin;
        this.wireReadSpin = b.wireReadSpin;
        this.version2Only = b.version2Only;
        this.olderHosts = b.olderHosts || b.version2Only;
        this.wireLimits = b.wireLimits != null ? b.wireLimits : WireServer.Limits.of(b.maxStateBytes, b.callTimeout);
        this.wireThreads = b.wireThreads;
        Peers peers = new Peers(state, key, tls != null, this::serveSelf);
        this.peers = peers;
        this.messaging = new HostMessaging(state, peers, b.node, b.node != null && b.ownsNode);
        messaging.given(b.messagingAddress);
        state.messaging = messaging;
        this.owed = new OwedEvents(state, peers, b.delivery);
        this.trips = new Trips(state, new HopSender(state, peers), owed, robot, b.delivery.expiry());
        this.home = new Home(state, code, trips, new AgentRequests(state, peers));
        messaging.events(key, home::onEvent);
        this.calls = new Calls(state, new Transfers(state, code, trips, home, owed), code, home, owed);
    }

    /**
     * @param name the host's name, under which it is bound in its RMI registry
     * @return a builder
     */
    public static Builder builder(String name) {
        return new Builder(name);
    }

    /** Settings of an agent host. */
    public static final class Builder {
        private final String name;
        private String bind = "127.0.0.1";
        private int port;
        private Robot robot;
        private String messagingAddress;
        private MessagingSettings messagingSettings = MessagingSettings.defaults();
        private boolean withMessaging = true;
        private MessagingNode node;
        private boolean ownsNode;
        private ClusterKey key;
        private TlsSettings tls;
        private Path storeDir;
        private List<String> allowed = List.of();
        private long maxStateBytes = 64L << 20;
        private Duration callTimeout = Duration.ofSeconds(30);
        private Duration stopGrace = Duration.ofSeconds(5);
        private Duration runnerSpin = SpinHandoff.defaultSpin();
        private Duration endpointSpin = Duration.ZERO;
        private DeliveryPolicy delivery = DeliveryPolicy.defaults();
        private boolean wire = true;
        private int wirePort;
        private Duration wireSpin = SpinHandoff.defaultWireSpin();
        private Duration wireReadSpin = Duration.ZERO;
        private boolean version2Only;
        private boolean olderHosts;
        private WireServer.Limits wireLimits;
        private java.util.concurrent.ThreadFactory wireThreads;
        private FailurePolicy failures = FailurePolicy.logging();

        private Builder(String name) {
            if (name == null || !name.matches("[A-Za-z0-9._-]+")) {
                throw new IllegalArgumentException("'" + name + "' is not a host name: use letters, digits, '.', '_' and '-'");
            }
            this.name = name;
        }

        /** @param address the address to listen on and to be known by (default 127.0.0.1) @return this */
        public Builder bind(String address) {
            this.bind = Objects.requireNonNull(address);
            return this;
        }

        /** @param port the RMI registry port; 0 (the default) picks a free one @return this */
        public Builder port(int port) {
            this.port = port;
            return this;
        }

        /** @param robot the robot agents here drive, or {@code null} for none @return this */
        public Builder robot(Robot robot) {
            this.robot = robot;
            return this;
        }

        /**
         * Where the host's own messaging node receives; without this (and without
         * {@link #noMessaging()}) it receives at {@code tcp://BIND:0}, a free port on the host's
         * bind address. Agents here use it through {@code context().messaging()}.
         *
         * @param address a messaging address, for example {@code tcp://127.0.0.1:7000}
         * @return this
         */
        public Builder messaging(String address) {
            this.messagingAddress = Objects.requireNonNull(address, "address");
            this.withMessaging = true;
            return this;
        }

        /** @param settings the settings of the host's own messaging node (its allow-list, timeouts, TLS) @return this */
        public Builder messagingSettings(MessagingSettings settings) {
            this.messagingSettings = Objects.requireNonNull(settings, "settings");
            return this;
        }

        /**
         * Agents here use this node (which the caller keeps and closes) instead of one of the host's own.
         *
         * @param node the node
         * @return this
         */
        public Builder messagingNode(MessagingNode node) {
            this.node = Objects.requireNonNull(node, "node");
            this.withMessaging = true;
            return this;
        }

        /** The host gives its agents no messaging (a home that only receives results). @return this */
        public Builder noMessaging() {
            this.withMessaging = false;
            this.node = null;
            return this;
        }

        /**
         * @param policy where whatever the host's threads catch goes (default
         *               {@link FailurePolicy#logging()}): its agent runners (an agent's callback that
         *               throws fails its stop, and is reported as survived; an error no thread
         *               survives ends the agent's trip, naming it and this host, and the runner, while
         *               the host serves on), its agent wire's accept and connection loops, its
         *               deliveries to homes, and its own messaging node's threads
         * @return this
         */
        public Builder failures(FailurePolicy policy) {
            this.failures = Objects.requireNonNull(policy, "policy");
            return this;
        }

        /** @param key the cluster key every peer must prove @return this */
        public Builder clusterKey(ClusterKey key) {
            this.key = key;
            return this;
        }

        /** @param tls mutual TLS for the RMI endpoint, or {@code null} @return this */
        public Builder tls(TlsSettings tls) {
            this.tls = tls;
            return this;
        }

        /** @param dir keep accepted agents durably in this directory (a journal), surviving a kill @return this */
        public Builder store(Path dir) {
            this.storeDir = dir;
            return this;
        }

        /** Keeps agents in memory only (the default): fast, lost if the host is killed. @return this */
        public Builder memoryStore() {
            this.storeDir = null;
            return this;
        }

        /** @param classNames classes agent state may hold besides the agent's own code and JDK value types @return this */
        public Builder allow(List<String> classNames) {
            this.allowed = List.copyOf(classNames);
            return this;
        }

        /** @param bytes the largest agent state (and array in it) accepted @return this */
        public Builder maxStateBytes(long bytes) {
            this.maxStateBytes = bytes;
            return this;
        }

        /** @param timeout how long a call to another host may take @return this */
        public Builder callTimeout(Duration timeout) {
            this.callTimeout = timeout;
            return this;
        }

        /**
         * @param policy how reports and results owed to homes that do not answer are retried, and
         *               after how long they are given up (default {@link DeliveryPolicy#defaults()})
         * @return this
         */
        public Builder deliveryPolicy(DeliveryPolicy policy) {
            this.delivery = Objects.requireNonNull(policy, "policy");
            return this;
        }

        /**
         * @param grace how long {@link AgentHost#close()} lets the stops running then finish before it
         *              interrupts them (default 5 s); with a durable store an interrupted stop is
         *              resumed after it at the next start, not run again
         * @return this
         */
        public Builder stopGrace(Duration grace) {
            if (grace.isNegative()) {
                throw new IllegalArgumentException("stop grace " + grace + " is negative: it is how long running stops may finish when the host closes");
            }
            this.stopGrace = grace;
            return this;
        }

        /**
         * @param spin how long a runner thread with nothing to do spins for the next agent before it
         *             parks (default 150 µs; zero, the default on a machine with one processor, never
         *             spins): an agent handed to a spinning runner starts at once, where waking a parked
         *             thread takes tens of microseconds on a virtual machine. Bounded: a runner spins at
         *             most this long after each stop, then parks
         * @return this
         */
        public Builder runnerSpin(Duration spin) {
            if (spin.isNegative() || spin.compareTo(Duration.ofMillis(10)) > 0) {
                throw new IllegalArgumentException("runner spin " + spin + " must be between 0 and 10 ms: a spinning runner holds a processor");
            }
            this.runnerSpin = spin;
            return this;
        }

        /**
         * @param spin how long a connection thread of the host's endpoint spins for the next call
         *             before it blocks reading (default 0: never; plain sockets only)
         * @return this
         */
        public Builder endpointSpin(Duration spin) {
            if (spin.isNegative() || spin.compareTo(Duration.ofMillis(10)) > 0) {
                throw new IllegalArgumentException("endpoint spin " + spin + " must be between 0 and 10 ms: a spinning connection thread holds a processor");
            }
            this.endpointSpin = spin;
            return this;
        }

        /**
         * @param on whether the host takes transfers on its agent wire (agent protocol version 3,
         *           docs/agents.md "Wire and store formats"; the default) and sends them on other
         *           hosts' wires; off, every call goes over RMI (version 2) and no wire port is opened
         * @return this
         */
        public Builder wire(boolean on) {
            this.wire = on;
            return this;
        }

        /**
         * @param port the port of the host's agent wire, on its bind address; 0 (the default) picks a
         *             free one. The host names it to each peer when the peer authenticates, so only a
         *             firewall needs to know it (a peer that cannot reach it sends over RMI)
         * @return this
         */
        public Builder wirePort(int port) {
            if (port < 0 || port > 65535) {
                throw new IllegalArgumentException("wire port " + port + " is not a TCP port");
            }
            this.wirePort = port;
            return this;
        }

        /**
         * @param spin how long a transfer this host sends on the agent wire spins (yielding the
         *             processor) for the acknowledgement before it blocks reading it (default 50 µs;
         *             zero, the default on a machine with one processor, never spins; plain connections only)
         * @return this
         */
        public Builder wireSpin(Duration spin) {
            if (spin.isNegative() || spin.compareTo(Duration.ofMillis(10)) > 0) {
                throw new IllegalArgumentException("wire spin " + spin + " must be between 0 and 10 ms: a spinning sender holds a processor");
            }
            this.wireSpin = spin;
            return this;
        }

        /**
         * @param spin how long a connection thread of the host's agent wire spins (yielding the
         *             processor) for the next transfer before it blocks reading (default 0: never;
         *             plain connections only)
         * @return this
         */
        public Builder wireReadSpin(Duration spin) {
            if (spin.isNegative() || spin.compareTo(Duration.ofMillis(10)) > 0) {
                throw new IllegalArgumentException("wire read spin " + spin + " must be between 0 and 10 ms: a spinning connection thread holds a processor");
            }
            this.wireReadSpin = spin;
            return this;
        }

        /**
         * Lets this host's links talk to hosts of builds before agent protocol version 4 (for a
         * cluster upgraded host by host): a link to a host that refuses version 4 authenticates with
         * version 3, or 2, whose authentication does not bind the channel, so a relay between the two
         * hosts goes unnoticed (docs/security.md). Off by default: such a link fails, saying why.
         *
         * @return this
         */
        public Builder olderHosts() {
            this.olderHosts = true;
            return this;
        }

        /** For tests of mixed versions: the host acts as one of a build before the agent wire (protocol version 2 only, no wire). */
        Builder version2Only() {
            this.version2Only = true;
            return this;
        }

        /** For tests: what makes the agent wire's connection threads (one that fails, to see the wire end cleanly). */
        Builder wireThreads(java.util.concurrent.ThreadFactory factory) {
            this.wireThreads = factory;
            return this;
        }

        /** For tests: the agent wire's limits. */
        Builder wireLimits(WireServer.Limits limits) {
            this.wireLimits = limits;
            return this;
        }

        /**
         * Starts the host: opens its store, resumes the agents it holds, and binds its RMI endpoint.
         *
         * @return the running host
         * @throws IOException if the store or the port cannot be used
         */
        public AgentHost start() throws IOException {
            if (key == null && tls == null) {
                throw new IllegalStateException("agent host " + name + " needs a cluster key or TLS: a host must only trust authenticated peers");
            }
            if (key == null) {
                key = ClusterKey.tlsOnly();
            }
            String atBroker = null;
            if (withMessaging && node == null) {
                try {
                    String address = messagingAddress != null ? messagingAddress : "tcp://" + (bind.contains(":") ? "[" + bind + "]" : bind) + ":0";
                    MessagingNode.Builder nb = MessagingNode.builder(name).settings(messagingSettings).failures(failures);
                    if (address.startsWith("mqtt://") || address.startsWith("mqtts://")) {
                        atBroker = address; // joined once the host's address is known (HostMessaging.joinWhenStarted)
                    } else {
                        nb.bind(address);
                    }
                    node = nb.build();
                    ownsNode = true;
                } catch (MessagingException e) {
                    throw new IOException("agent host " + name + " cannot start its messaging node: " + e.getMessage(), e);
                }
            }
            AgentHost host;
            try {
                host = new AgentHost(this);
            } catch (RuntimeException e) {
                if (ownsNode) {
                    node.close();
                }
                throw e;
            }
            if (atBroker != null) {
                host.messaging.joinWhenStarted(atBroker);
            }
            try {
                host.open();
            } catch (io.robomw.api.MessagingException e) {
                host.close();
                throw new IOException("agent host " + name + " cannot start its messaging node: " + e.getMessage(), e);
            } catch (IOException | RuntimeException e) {
                host.close();
                throw e;
            }
            return host;
        }
    }

    /**
     * Serves a call as if a verified peer had made it, without RMI: for tests and fuzzing of what
     * the host does with call bodies.
     */
    Reply serve(String peer, Op op, byte[] body) {
        return calls.handle(peer, op, body, 0, body.length);
    }

    /** Serves a call this host makes to itself (its {@link Calls} are made after its {@link Peers}). */
    private Reply serveSelf(String peer, Op op, byte[] message, int offset, int length) {
        return calls.handle(peer, op, message, offset, length);
    }

    // ---- life ----

    private void open() throws IOException {
        state.store = storeDir == null ? new MemoryStore() : JournalStore.open(storeDir);
        InetAddress bindAddress = InetAddress.getByName(bind);
        SSLContext ssl = tls == null ? null : tls.context();
        long maxCall = state.codec.maxBytes() + (1 << 20);
        HostConnections connections = new HostConnections(name, maxCall);
        HostSockets.Server serverSockets = new HostSockets.Server(bindAddress, ssl, counters, connections, endpointSpin.toNanos());
        HostSockets.Client clientSockets = new HostSockets.Client(bind, tls != null, state.timeoutMillis);
        endpoint = new HostEndpoint(name, key, calls, version2Only ? Session.PROTOCOL_VERSION : Session.BOUND_VERSION, state.failures, connections);
        peers.wire(ssl, wireSpin, version2Only, !wire);
        peers.olderHosts(olderHosts);
        if (wire) {
            wireServer = new WireServer(endpoint, bindAddress, wirePort, ssl, wireLimits, state.failures);
            wireServer.readSpin(wireReadSpin);
            wireServer.tagger(state.wireTaggers);
            if (wireThreads != null) {
                wireServer.connectionThreads(wireThreads);
            }
            wireServer.countBytesIn(counters);
            endpoint.wirePort(wireServer.port());
        }
        ObjectInputFilter onlyBytes = info -> {
            if (info.arrayLength() > maxCall || info.depth() > 2) {
                return ObjectInputFilter.Status.REJECTED;
            }
            if (info.arrayLength() >= 0 && !connections.mayRead(info.arrayLength())) {
                // before a call on this connection has proved the cluster key, only small calls; and all calls being read within a budget
                return ObjectInputFilter.Status.REJECTED;
            }
            Class<?> c = info.serialClass();
            return c == null || c == byte[].class ? ObjectInputFilter.Status.ALLOWED : ObjectInputFilter.Status.REJECTED;
        };
        int port = requestedPort;
        for (int attempt = 0; ; attempt++) {
            int tryPort = port != 0 ? port : freePort(bindAddress);
            try {
                endpoint.address(bindAddress, tryPort);
                registry = LocateRegistry.createRegistry(tryPort, clientSockets, serverSockets);
                AgentHostRemote stub = (AgentHostRemote) UnicastRemoteObject.exportObject(endpoint, tryPort, clientSockets, serverSockets, onlyBytes);
                // In-process: the registry refuses every change from outside (HostSockets hides callers' addresses from RMI).
                registry.rebind(name, stub);
                port = tryPort;
                break;
            } catch (ExportException e) {
                if (port != 0 || attempt >= 5) {
                    throw new IOException("agent host " + name + " cannot listen on " + bind + ":" + tryPort + ": " + e.getMessage(), e);
                }
            }
        }
        state.address = new HostAddress(bind, port, name).toString();
        messaging.started();
        new Recovery(state, code, trips, owed).resume();
        LOG.info("agent host {} listening at {} ({} store{}, {}, robot: {}, messaging: {})", name, state.address,
                state.store.durable() ? "durable " + storeDir : "memory-only", tls != null ? ", mutual TLS" : "",
                wireServer != null ? "agent wire on port " + wireServer.port() : "no agent wire (protocol version 2)",
                state.robot == null ? "none" : state.robot.name(), messaging.addresses().isEmpty() ? "none" : messaging.addresses());
    }

    private static int freePort(InetAddress bindAddress) throws IOException {
        try (ServerSocket s = new ServerSocket()) {
            s.bind(new InetSocketAddress(bindAddress, 0));
            return s.getLocalPort();
        }
    }

    /** Stops serving: no new agents; running stops get the stop grace (5 s by default) to finish; durable agents stay in the store for the next start. */
    @Override
    public void close() {
        if (state.closed) {
            return;
        }
        state.closed = true;
        if (wireServer != null) {
            wireServer.close(Duration.ofMillis(Math.max(stopGrace.toMillis(), 1000)));
        }
        if (endpoint != null) {
            unexportAfterCallsInProgress(endpoint);
        }
        peers.close();
        try {
            if (registry != null) {
                UnicastRemoteObject.unexportObject(registry, true);
            }
        } catch (NoSuchObjectException ignored) {
            // never exported
        }
        state.runners.shutdown();
        state.requests.shutdown();
        try {
            if (!state.runners.awaitTermination(stopGrace.toMillis(), TimeUnit.MILLISECONDS)) {
                state.runners.shutdownNow();
            }
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
            state.runners.shutdownNow();
        }
        state.wireTaggers.shutdown();
        owed.close();
        int held = state.hosted.size();
        if (held > 0) {
            if (state.store != null && state.store.durable()) {
                LOG.info("agent host {} closed holding {} agents; they resume when it starts again with store {}", name, held, storeDir);
            } else {
                LOG.warn("agent host {} closed holding {} agents in a memory-only store: they are gone", name, held);
            }
        }
        try {
            if (state.store != null) {
                state.store.close();
            }
        } catch (IOException e) {
            LOG.warn("agent host {}: closing the store failed: {}", name, e.toString());
        }
        messaging.close();
    }

    /**
     * Stops taking calls, letting the calls in progress finish and their replies go out first (for
     * up to the stop grace): a home that closes right after a result came must still acknowledge
     * it, or the sending host would owe it again ("Error unmarshaling return header" at the other end).
     */
    private void unexportAfterCallsInProgress(HostEndpoint served) {
        long deadline = System.nanoTime() + Math.max(stopGrace.toNanos(), TimeUnit.SECONDS.toNanos(1));
        try {
            while (!UnicastRemoteObject.unexportObject(served, false)) {
                if (System.nanoTime() - deadline > 0) {
                    LOG.warn("agent host {}: calls still in progress after {}; closing without waiting for them", name, stopGrace);
                    UnicastRemoteObject.unexportObject(served, true);
                    return;
                }
                java.util.concurrent.locks.LockSupport.parkNanos(TimeUnit.MILLISECONDS.toNanos(5)); // new calls are refused: these end soon
            }
        } catch (NoSuchObjectException ignored) {
            // never exported
        }
    }

    // ---- what the host is ----

    /** @return the host's name */
    public String name() {
        return name;
    }

    /** @return the host's address, {@code rmi://host:port/name} */
    public String address() {
        return state.address;
    }

    /** Takes the robot for the calling agent's stop (waiting for the agent that has it), unless it already has it. */
    Robot claimRobot(HostedAgent h) {
        Robot r = robot.claim(h);
        h.drives = r != null;
        return r;
    }

    /** @return the agent host address of a host an agent here names (its address, or its name as messages use it) */
    String hostAddressOf(String nameOrAddress, HostedAgent h) {
        return messaging.hostAddress(nameOrAddress, h);
    }

    /** @return an agent's view of this host's messaging node */
    Messaging messagingFor(HostedAgent h) {
        return messaging.forAgent(h);
    }

    /** @return where this host's messaging node receives (empty when it has none), as agents and {@code mw host} give it */
    public List<String> messagingAddresses() {
        return messaging.addresses();
    }

    /** @return this host's messaging node, or empty when it has none (for serving its robot on it) */
    public Optional<MessagingNode> messagingNode() {
        return Optional.ofNullable(messaging.node());
    }

    /** @return the agents at this host now */
    public List<AgentInfo> agents() {
        return calls.agents();
    }

    /** @return the reports and results this host owes agents' homes and has not delivered yet, the oldest first */
    public List<OwedDelivery> owed() {
        return owed.owed();
    }

    /**
     * Drops deliveries this host owes: it stops trying and forgets them, durably. For a home that
     * is gone for good (a {@code mw dispatch} that was stopped), rather than wait for their expiry.
     *
     * @param which the deliveries to drop
     * @return the ones dropped
     */
    public List<OwedDelivery> dropOwed(OwedSelector which) {
        return owed.drop(which::matches, "dropped by the operator (" + which + ")");
    }

    /**
     * @param id an agent
     * @return the host an agent went to from here, once that host acknowledged it, or {@code null}
     */
    String forwardOf(java.util.UUID id) {
        return state.forwardOf(id);
    }

    /** @return how many threads deliver to homes now (one per home with something to deliver, until idle) */
    int deliveryThreads() {
        return owed.deliveryThreads();
    }

    /** @return bytes received by this host's RMI endpoint (without TLS) and agent wire (its frames) so far */
    public long wireBytesIn() {
        return counters.in.sum();
    }

    /** @return bytes sent by this host's RMI endpoint (without TLS) and agent wire (its frames) so far */
    public long wireBytesOut() {
        return counters.out.sum();
    }

    /** @return the port of the host's agent wire, or 0 if it has none */
    public int wirePort() {
        return wireServer == null ? 0 : wireServer.port();
    }

    /** @return what ended the agent wire's accept thread, or {@code null} while it serves (for tests) */
    Throwable wireFailure() {
        return wireServer == null ? null : wireServer.failure();
    }

    /** @return the frames (calls) this host's agent wire has served (for tests) */
    long wireFramesServed() {
        return wireServer == null ? 0 : wireServer.served();
    }

    /** @return the agent wire connections open now (for tests) */
    int wireConnections() {
        return wireServer == null ? 0 : wireServer.open();
    }

    /** @return the peers' sessions this host keeps now (for tests) */
    int sessionsKept() {
        return endpoint.sessions();
    }

    /** @return how many peers, calls, archives and agents this host has refused */
    public long refused() {
        return endpoint.refused() + state.refused();
    }

    // ---- Agency: this host as home ----

    /**
     * @return this host as a home: the {@link Agency} whose agents (and their clones) report and
     *         bring their results here, and can be retracted from here
     */
    public Agency agency() {
        return home;
    }

    /** A clone an agent here makes of itself, sent with its own plan; this host is its home. */
    AgentRef cloneOf(HostedAgent parent, Itinerary plan) {
        return home.cloneOf(parent, plan);
    }

    /** An agent here sends a value home. */
    void report(HostedAgent h, Serializable value) {
        owed.report(h, value);
    }

    // ---- asking another host ----

    /**
     * Asks a host who it is (for {@code mw agents} and tools): its name, robot, messaging
     * addresses and the hosts it knows.
     *
     * @param address the host
     * @param key     the cluster key
     * @param useTls  whether the host uses TLS
     * @return its description
     * @throws IOException if the host cannot be reached, refuses this peer, or answers something else
     */
    public static HostDescription describe(String address, ClusterKey key, boolean useTls) throws IOException {
        try (HostClient client = new HostClient(key, useTls, 10_000)) {
            return client.describe(address);
        }
    }

    // ---- listing another host ----

    /**
     * Lists the agents at a host (for {@code mw agents}).
     *
     * @param address the host
     * @param key     the cluster key
     * @param useTls  whether the host uses TLS (then the JVM's default TLS context must hold this peer's key)
     * @return its agents
     * @throws IOException if the host cannot be reached or refuses this peer
     */
    public static List<AgentInfo> list(String address, ClusterKey key, boolean useTls) throws IOException {
        try (HostClient client = new HostClient(key, useTls, 10_000)) {
            return client.agents(address);
        }
    }

    @Override
    public String toString() {
        return "AgentHost[" + name + " at " + state.address + "]";
    }
}
