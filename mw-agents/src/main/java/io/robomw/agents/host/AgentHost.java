package io.robomw.agents.host;

import io.robomw.agents.host.core.Calls;
import io.robomw.agents.host.core.CodeLoaders;
import io.robomw.agents.host.core.HostState;
import io.robomw.agents.host.home.AgentRequests;
import io.robomw.agents.host.home.Home;
import io.robomw.agents.host.home.OwedEvents;
import io.robomw.agents.host.messaging.HostMessaging;
import io.robomw.agents.host.ops.HostClient;
import io.robomw.agents.host.protocol.Bodies;
import io.robomw.agents.host.protocol.Op;
import io.robomw.agents.host.protocol.Reply;
import io.robomw.agents.host.rmi.AgentHostRemote;
import io.robomw.agents.host.rmi.HostConnections;
import io.robomw.agents.host.rmi.HostEndpoint;
import io.robomw.agents.host.rmi.HostSockets;
import io.robomw.agents.host.rmi.Peers;
import io.robomw.agents.host.rmi.Session;
import io.robomw.agents.host.visit.AgentPlace;
import io.robomw.agents.host.visit.HopSender;
import io.robomw.agents.host.visit.HostContext;
import io.robomw.agents.host.visit.HostedAgent;
import io.robomw.agents.host.visit.Recovery;
import io.robomw.agents.host.visit.RobotTurns;
import io.robomw.agents.host.visit.SpinHandoff;
import io.robomw.agents.host.visit.Transfers;
import io.robomw.agents.host.visit.Trips;
import io.robomw.agents.host.wire.WireServer;
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
 * <p><b>Parts.</b> This class starts and stops the host and is its public face
 * ({@link AgentHostBuilder} sets it up); its parts are in sub-packages by job, public only so that
 * they can call each other (no other module may use them: {@code InternalPackagesTest}):
 * <ul>
 *   <li>{@code host.protocol}: the layouts and codes of calls, replies, agent images and events;</li>
 *   <li>{@code host.security}: the MACs and tags of calls and wire frames;</li>
 *   <li>{@code host.rmi}: authenticated calls, served ({@link HostEndpoint}) and made ({@link Peers});</li>
 *   <li>{@code host.wire}: the agent wire (protocol version 3) that carries hops and calls;</li>
 *   <li>{@code host.core}: what the parts share ({@link HostState}), the verified calls'
 *       dispatch ({@link Calls}), agents' code ({@link CodeLoaders}), and what watchers see;</li>
 *   <li>{@code host.visit}: the agents visiting here: taken in ({@link Transfers}), run stop by
 *       stop and sent on ({@link Trips}), resumed after a restart ({@link Recovery});</li>
 *   <li>{@code host.home}: the agents sent from here ({@link Home}) and the deliveries owed to
 *       homes ({@link OwedEvents});</li>
 *   <li>{@code host.messaging}: the host's messaging node, as agents and other hosts see it;</li>
 *   <li>{@code host.ops}: asking and watching hosts from outside ({@code mw agents}, the console).</li>
 * </ul>
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
    /** For tests: acts as a host of a build before the compact form of agent state (protocol version 4 at most). */
    private final boolean beforeCompactForm;
    private final boolean version2Only;
    private final boolean olderHosts;
    private final WireServer.Limits wireLimits;
    private final java.util.concurrent.ThreadFactory wireThreads;
    private HostEndpoint endpoint;
    private WireServer wireServer;
    private Registry registry;

    AgentHost(AgentHostBuilder b) {
        this.name = b.name;
        this.bind = b.bind;
        this.requestedPort = b.port;
        this.key = b.key;
        this.tls = b.tls;
        this.storeDir = b.storeDir;
        this.stopGrace = b.stopGrace;
        this.endpointSpin = b.endpointSpin;
        this.state = new HostState(new Place(), b.name, b.robot, new StateCodec(b.allowed, b.maxStateBytes,
                b.beforeCompactForm || b.version2Only ? StateCodec.Form.STANDARD : StateCodec.Form.COMPACT), (int) b.callTimeout.toMillis(),
                b.runnerSpin, b.failures);
        this.robot = new RobotTurns(b.name, b.robot);
        this.code = new CodeLoaders(state);
        this.wire = b.wire && !b.version2Only;
        this.wirePort = b.wirePort;
        this.wireSpin = b.wireSpin;
        this.wireReadSpin = b.wireReadSpin;
        this.version2Only = b.version2Only;
        this.beforeCompactForm = b.beforeCompactForm;
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
    public static AgentHostBuilder builder(String name) {
        return new AgentHostBuilder(name);
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

    /** Joins the broker of a messaging address at {@code mqtt://} once the host's own address is known. */
    void joinWhenStarted(String broker) {
        messaging.joinWhenStarted(broker);
    }

    /** Opens the store, binds the endpoints, resumes what the store held: the builder's last step. */
    void open() throws IOException {
        state.store = storeDir == null ? new MemoryStore() : JournalStore.open(storeDir);
        InetAddress bindAddress = InetAddress.getByName(bind);
        SSLContext ssl = tls == null ? null : tls.context();
        long maxCall = state.codec.maxBytes() + (1 << 20);
        HostConnections connections = new HostConnections(name, maxCall);
        HostSockets.Server serverSockets = new HostSockets.Server(bindAddress, ssl, counters, connections, endpointSpin.toNanos());
        HostSockets.Client clientSockets = new HostSockets.Client(bind, tls != null, state.timeoutMillis);
        endpoint = new HostEndpoint(name, key, calls, version2Only ? Session.PROTOCOL_VERSION : beforeCompactForm ? Session.BOUND_VERSION
                : Session.COMPACT_VERSION, state.failures, connections);
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

    /** What this host gives the agents at it ({@link HostContext}): the facade's parts, not the facade. */
    private final class Place implements AgentPlace {
        @Override
        public String name() {
            return name;
        }

        @Override
        public String address() {
            return state.address;
        }

        @Override
        public Robot claimRobot(HostedAgent h) {
            Robot r = robot.claim(h);
            h.drives = r != null;
            return r;
        }

        @Override
        public Messaging messagingFor(HostedAgent h) {
            return messaging.forAgent(h);
        }

        @Override
        public String hostAddressOf(String nameOrAddress, HostedAgent h) {
            return messaging.hostAddress(nameOrAddress, h);
        }

        @Override
        public AgentRef cloneOf(HostedAgent parent, Itinerary plan) {
            return home.cloneOf(parent, plan);
        }

        @Override
        public void report(HostedAgent h, Serializable value) {
            owed.report(h, value);
        }

        @Override
        public Agency agency() {
            return home;
        }
    }

    @Override
    public String toString() {
        return "AgentHost[" + name + " at " + state.address + "]";
    }
}
