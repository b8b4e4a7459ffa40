package io.robomw.agents.host;

import io.robomw.agents.host.code.CodeArchive;
import io.robomw.agents.host.code.StateCodec;
import io.robomw.agents.host.code.StateRejectedException;
import io.robomw.agents.host.store.JournalStore;
import io.robomw.agents.host.store.MemoryStore;
import io.robomw.agents.messaging.security.TlsSettings;
import io.robomw.api.Agency;
import io.robomw.api.Agent;
import io.robomw.api.AgentException;
import io.robomw.api.AgentMessage;
import io.robomw.api.AgentRef;
import io.robomw.api.AgentStatus;
import io.robomw.api.Itinerary;
import io.robomw.api.Messaging;
import io.robomw.api.NotHandledException;
import io.robomw.api.Robot;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import javax.net.ssl.SSLContext;
import java.io.ByteArrayInputStream;
import java.io.IOException;
import java.io.ObjectInputFilter;
import java.io.ObjectInputStream;
import java.io.ObjectStreamClass;
import java.io.Serializable;
import java.net.InetAddress;
import java.net.InetSocketAddress;
import java.net.ServerSocket;
import java.nio.charset.StandardCharsets;
import java.nio.file.Path;
import java.rmi.NoSuchObjectException;
import java.rmi.registry.LocateRegistry;
import java.rmi.registry.Registry;
import java.rmi.server.ExportException;
import java.rmi.server.UnicastRemoteObject;
import java.security.SecureRandom;
import java.time.Duration;
import java.util.ArrayList;
import java.util.Arrays;
import java.util.List;
import java.util.Objects;
import java.util.UUID;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.CompletionException;
import java.util.concurrent.TimeUnit;

/**
 * An agent host (paper section III.A.4, after the Aglets server): an RMI server, bound to a
 * robot or to none, that receives mobile agents, runs each stop of theirs on a named thread with
 * its robot, sends them on along their itineraries, and tells their homes how they are doing. It
 * is also an {@link Agency}: agents sent from here have this host as their home, where their
 * results arrive.
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
 * <p><b>Parts.</b> This class starts and stops the host, serves the verified calls
 * ({@link HostEndpoint} checks them) and is the home of the agents sent from here; the rest is
 * done by package-private parts that share a {@link HostState}: {@link Transfers} takes agents in,
 * {@link Trips} runs their stops and sends them on through {@link HopSender}, {@link OwedEvents}
 * tells homes what happened, {@link Recovery} resumes what the store held, {@link CodeLoaders}
 * keeps agents' code, {@link Peers} calls other hosts, {@link RobotTurns} lends the robot to one
 * stop at a time, and {@link Bodies} lays out the call bodies.
 */
public final class AgentHost implements Agency, AutoCloseable {

    private static final Logger LOG = LoggerFactory.getLogger(AgentHost.class);
    /** How many moves a call follows before it gives up on an agent that keeps moving. */
    private static final int MAX_ROUTE_HOPS = 16;

    private final String name;
    private final String bind;
    private final int requestedPort;
    private final Messaging messaging;
    private final ClusterKey key;
    private final TlsSettings tls;
    private final Path storeDir;
    private final HostState state;
    private final RobotTurns robot;
    private final CodeLoaders code;
    private final OwedEvents owed;
    private final Trips trips;
    private final Peers peers;
    private final Transfers transfers;
    private final HostSockets.Counters counters = new HostSockets.Counters();
    private HostEndpoint endpoint;
    private Registry registry;

    private AgentHost(Builder b) {
        this.name = b.name;
        this.bind = b.bind;
        this.requestedPort = b.port;
        this.messaging = b.messaging;
        this.key = b.key;
        this.tls = b.tls;
        this.storeDir = b.storeDir;
        this.state = new HostState(this, b.name, b.robot, new StateCodec(b.allowed, b.maxStateBytes), (int) b.callTimeout.toMillis());
        this.robot = new RobotTurns(b.name, b.robot);
        this.code = new CodeLoaders(state);
        this.peers = new Peers(state, key, tls != null, this::handle);
        this.owed = new OwedEvents(state, peers);
        this.trips = new Trips(state, new HopSender(state, peers), owed, robot);
        this.transfers = new Transfers(state, code, trips, this, owed);
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
        private Messaging messaging;
        private ClusterKey key;
        private TlsSettings tls;
        private Path storeDir;
        private List<String> allowed = List.of();
        private long maxStateBytes = 64L << 20;
        private Duration callTimeout = Duration.ofSeconds(30);

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

        /** @param messaging the messaging agents here use, or {@code null} @return this */
        public Builder messaging(Messaging messaging) {
            this.messaging = messaging;
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
            AgentHost host = new AgentHost(this);
            try {
                host.open();
            } catch (IOException | RuntimeException e) {
                host.close();
                throw e;
            }
            return host;
        }
    }

    // ---- life ----

    private void open() throws IOException {
        state.store = storeDir == null ? new MemoryStore() : JournalStore.open(storeDir);
        InetAddress bindAddress = InetAddress.getByName(bind);
        SSLContext ssl = tls == null ? null : tls.context();
        HostSockets.Server serverSockets = new HostSockets.Server(bindAddress, ssl, counters);
        HostSockets.Client clientSockets = new HostSockets.Client(bind, tls != null, state.timeoutMillis);
        endpoint = new HostEndpoint(name, key, this::handle);
        long maxCall = state.codec.maxBytes() + (1 << 20);
        ObjectInputFilter onlyBytes = info -> {
            if (info.arrayLength() > maxCall || info.depth() > 2) {
                return ObjectInputFilter.Status.REJECTED;
            }
            Class<?> c = info.serialClass();
            return c == null || c == byte[].class ? ObjectInputFilter.Status.ALLOWED : ObjectInputFilter.Status.REJECTED;
        };
        int port = requestedPort;
        for (int attempt = 0; ; attempt++) {
            int tryPort = port != 0 ? port : freePort(bindAddress);
            try {
                registry = LocateRegistry.createRegistry(tryPort, clientSockets, serverSockets);
                AgentHostRemote stub = (AgentHostRemote) UnicastRemoteObject.exportObject(endpoint, tryPort, clientSockets, serverSockets, onlyBytes);
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
        new Recovery(state, code, trips, owed).resume(storeDir);
        LOG.info("agent host {} listening at {} ({} store{}, robot: {})", name, state.address, state.store.durable() ? "durable " + storeDir : "memory-only",
                tls != null ? ", mutual TLS" : "", state.robot == null ? "none" : state.robot.name());
    }

    private static int freePort(InetAddress bindAddress) throws IOException {
        try (ServerSocket s = new ServerSocket()) {
            s.bind(new InetSocketAddress(bindAddress, 0));
            return s.getLocalPort();
        }
    }

    /** Stops serving: no new agents; running stops get 5 s to finish; durable agents stay in the store for the next start. */
    @Override
    public void close() {
        if (state.closed) {
            return;
        }
        state.closed = true;
        try {
            if (endpoint != null) {
                UnicastRemoteObject.unexportObject(endpoint, true);
            }
        } catch (NoSuchObjectException ignored) {
            // never exported
        }
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
            if (!state.runners.awaitTermination(5, TimeUnit.SECONDS)) {
                state.runners.shutdownNow();
            }
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
            state.runners.shutdownNow();
        }
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
        return robot.claim(h);
    }

    Messaging messaging() {
        return messaging;
    }

    /** @return bytes received by this host's RMI endpoint so far (without TLS) */
    public long wireBytesIn() {
        return counters.in.sum();
    }

    /** @return bytes sent by this host's RMI endpoint so far (without TLS) */
    public long wireBytesOut() {
        return counters.out.sum();
    }

    /** @return how many peers, calls, archives and agents this host has refused */
    public long refused() {
        return endpoint.refused() + state.refused();
    }

    // ---- Agency: this host as home ----

    /** An agent here sends a value home. */
    void report(HostedAgent h, Serializable value) {
        owed.report(h, value);
    }

    @Override
    public AgentRef sendAgent(String to, Agent agent) {
        HostAddress.parse(to);
        agent.itinerary().insertNext(to, null);
        return startTrip(agent);
    }

    @Override
    public AgentRef startTrip(Agent agent) {
        if (agent.itinerary().stops().isEmpty()) {
            throw new IllegalArgumentException("agent " + agent.getClass().getName() + " has no stops in its itinerary");
        }
        agent.onCreation(null);
        return launch(agent, UUID.randomUUID());
    }

    @Override
    public List<AgentRef> dispatchClones(Agent agent, String... hosts) {
        for (String h : hosts) {
            HostAddress.parse(h);
        }
        agent.onCreation(null);
        byte[] bytes;
        try {
            bytes = StateCodec.write(agent);
        } catch (IOException e) {
            throw new AgentException("agent " + agent.getClass().getName() + " cannot be cloned: its state is not serializable: " + e.getMessage(), e);
        }
        List<CompletableFuture<AgentRef>> sends = new ArrayList<>();
        for (String h : hosts) {
            sends.add(CompletableFuture.supplyAsync(() -> {
                Agent clone = copy(bytes, agent.getClass().getClassLoader());
                clone.itinerary().clear();
                clone.itinerary().addStop(h);
                return launch(clone, UUID.randomUUID());
            }, state.requests));
        }
        List<AgentRef> refs = new ArrayList<>();
        List<String> failures = new ArrayList<>();
        for (int i = 0; i < hosts.length; i++) {
            try {
                refs.add(sends.get(i).join());
            } catch (CompletionException e) {
                failures.add(hosts[i] + ": " + e.getCause().getMessage());
            }
        }
        if (!failures.isEmpty()) {
            throw new AgentException("clones of " + agent.getClass().getName() + " could not be sent to " + failures.size() + " of " + hosts.length
                    + " hosts (the others were sent): " + String.join("; ", failures));
        }
        return refs;
    }

    /** A copy of an agent from this process's own state: no filter, the bytes were made here. */
    private static Agent copy(byte[] state, ClassLoader loader) {
        try (ObjectInputStream in = new ObjectInputStream(new ByteArrayInputStream(state)) {
            @Override
            protected Class<?> resolveClass(ObjectStreamClass desc) throws IOException, ClassNotFoundException {
                return Class.forName(desc.getName(), false, loader);
            }
        }) {
            return (Agent) in.readObject();
        } catch (IOException | ClassNotFoundException e) {
            throw new AgentException("cannot copy agent state: " + e, e);
        }
    }

    /** A clone of an agent at this host, made by the agent itself, sent with its own plan; this host is its home. */
    AgentRef cloneOf(HostedAgent parent, Itinerary plan) {
        Agent clone;
        try {
            clone = state.codec.read(StateCodec.write(parent.agent), parent.loader, Agent.class);
        } catch (IOException | StateRejectedException e) {
            throw new AgentException("agent " + parent.id + " cannot be cloned: " + e.getMessage(), e);
        }
        clone.itinerary().copyPlan(plan);
        return launch(clone, UUID.randomUUID());
    }

    /** Sends a new agent from here (its home) to its first reachable stop; blocks until that host has it. */
    private AgentRef launch(Agent agent, UUID id) {
        Class<?> type = agent.getClass();
        CodeArchive archive = code.archiveOf(type);
        AgentImage origin = new AgentImage(id, 0, AgentImage.Kind.TRIP, true, state.address, archive.digest(), 1, new byte[0]);
        HostedAgent h = new HostedAgent(origin, agent, type.getClassLoader());
        AgentHandle handle = new AgentHandle(this, id, type.getName(), type.getClassLoader(), state.address);
        state.handles.put(id, handle);
        Trips.Departure d = trips.depart(h);
        if (d.delivered()) {
            handle.location(d.target());
            return handle;
        }
        state.handles.remove(id);
        throw new AgentException("agent " + type.getName() + " " + id + " could not be sent: " + d.reason());
    }

    /**
     * News of an agent sent from here: it arrived somewhere, reported, ended with a result,
     * failed, or was disposed of.
     *
     * @param peer the host that sends it
     * @param body the event, {@link AgentEvent#encode}
     * @return the reply (OK also for an event of an agent not sent from here: there is nothing to retry)
     */
    Reply onEvent(String peer, byte[] body) {
        AgentEvent e;
        try {
            e = AgentEvent.decode(body);
        } catch (IllegalArgumentException ex) {
            return state.refuse("refused an event from peer '" + peer + "': " + ex.getMessage());
        }
        AgentHandle h = state.handles.get(e.id());
        if (h == null) {
            LOG.debug("host {}: {} for agent {} which was not sent from here; dropped", state.name, e.kind(), e.id());
            return Reply.ok();
        }
        switch (e.kind()) {
            case ARRIVED -> h.arrived(e.location());
            case REPORT, RESULT -> {
                Serializable value;
                try {
                    value = state.codec.read(e.payload(), h.loader, Serializable.class);
                } catch (StateRejectedException ex) {
                    state.refuse("dropped a " + e.kind() + " of agent " + e.id() + " from peer '" + peer + "': " + ex.getMessage());
                    if (e.kind() == AgentEvent.Kind.RESULT) {
                        h.failed(e.location(), AgentStatus.FAILED, "ended at " + e.location() + " but its result was refused at home: " + ex.getMessage());
                    }
                    return Reply.ok();
                }
                if (e.kind() == AgentEvent.Kind.REPORT) {
                    h.report(e.seq(), value);
                } else {
                    h.completed(e.location(), value);
                }
            }
            case FAILED -> h.failed(e.location(), AgentStatus.FAILED, new String(e.payload(), StandardCharsets.UTF_8));
            case DISPOSED -> h.failed(e.location(), AgentStatus.DISPOSED, new String(e.payload(), StandardCharsets.UTF_8));
        }
        return Reply.ok();
    }

    /**
     * A retracted agent of this home comes back: its state completes the retract.
     *
     * @param peer  the host that sends it
     * @param image its image, decoded in place
     * @return the reply
     */
    Reply onHomecoming(String peer, AgentImage image) {
        AgentHandle handle = state.handles.get(image.id());
        if (handle == null) {
            return state.refuse("refused homecoming agent " + image.id() + " from peer '" + peer + "': it was not sent from here");
        }
        try {
            Agent agent = state.codec.read(image.state(), image.stateOffset(), image.stateLength(), handle.loader, Agent.class);
            state.store.accepted(image.id(), image.hop(), new byte[0], 0, 0);
            handle.retracted(peer, agent);
            return Reply.ok();
        } catch (StateRejectedException | IOException e) {
            return state.refuse("refused homecoming agent " + image.id() + " from peer '" + peer + "': " + e.getMessage());
        }
    }
    /**
     * @param handle  the agent
     * @param content the message
     * @param oneway  whether nobody waits for the answer
     * @return the agent's answer; fails with {@link NotHandledException} if it did not handle the message
     */
    CompletableFuture<Serializable> messageAgent(AgentHandle handle, Serializable content, boolean oneway) {
        byte[] bytes;
        try {
            bytes = StateCodec.write(content);
        } catch (IOException e) {
            return CompletableFuture.failedFuture(new AgentException("message to agent " + handle.id() + " is not serializable: " + e.getMessage(), e));
        }
        byte[] body = Bodies.message(handle.id(), oneway, bytes);
        return handle.inOrder(() -> {
            Reply r = agentCall(handle, Op.MESSAGE, body);
            return switch (r.status()) {
                case OK -> {
                    if (r.body().length == 0) {
                        yield null;
                    }
                    try {
                        yield state.codec.read(r.body(), handle.loader, Serializable.class);
                    } catch (StateRejectedException e) {
                        throw new AgentException("reply of agent " + handle.id() + " refused: " + e.getMessage(), e);
                    }
                }
                case NOT_HANDLED -> throw new NotHandledException(r.text());
                default -> throw failure(handle, r);
            };
        }, state.requests);
    }

    /**
     * @param handle the agent
     * @param op     {@link Op#RETRACT} or {@link Op#DISPOSE}
     * @return completes once the agent's host has taken the request (it takes effect when the agent's current callback returns)
     */
    CompletableFuture<Void> requestOfAgent(AgentHandle handle, Op op) {
        byte[] body = Bodies.agentRequest(handle.id());
        return handle.inOrder(() -> {
            Reply r = agentCall(handle, op, body);
            if (r.status() != Reply.Status.OK) {
                throw failure(handle, r);
            }
            return null;
        }, state.requests).thenApply(x -> null);
    }

    private Reply agentCall(AgentHandle handle, Op op, byte[] body) {
        if (handle.ended()) {
            throw new AgentException("agent " + handle.id() + " has ended its trip (" + handle.status() + " at " + handle.location() + ")");
        }
        try {
            return routeToAgent(handle, op, body);
        } catch (PeerException e) {
            throw new AgentException(op + " to agent " + handle.id() + " failed: " + e.getMessage(), e);
        }
    }

    private Reply routeToAgent(AgentHandle handle, Op op, byte[] body) throws PeerException {
        String location = handle.location();
        for (int i = 0; i < MAX_ROUTE_HOPS; i++) {
            Reply r = peers.call(location, op, body);
            if (r.status() != Reply.Status.MOVED) {
                return r;
            }
            location = r.text();
            handle.location(location);
        }
        throw new PeerException("agent " + handle.id() + " moved more than " + MAX_ROUTE_HOPS + " times while a call chased it", false, null);
    }

    private static AgentException failure(AgentHandle handle, Reply r) {
        if (r.status() == Reply.Status.GONE && handle.ended()) {
            return new AgentException("agent " + handle.id() + " has ended its trip");
        }
        return new AgentException(r.status() + ": " + r.text());
    }
    /** Serves a verified call; a transfer is decoded in place (it may be megabytes), other bodies are copied out. */
    private Reply handle(String peer, Op op, byte[] message, int offset, int length) {
        if (op == Op.TRANSFER && !state.closed) {
            return transfers.acceptWithRunner(peer, message, offset, length);
        }
        byte[] body = Arrays.copyOfRange(message, offset, offset + length);
        if (state.closed) {
            return Reply.of(Reply.Status.REFUSED, "host " + state.name + " is closing");
        }
        return switch (op) {
            case TRANSFER -> transfers.accept(peer, body, 0, body.length, null);
            case PUT_ARCHIVE -> code.onArchive(peer, body);
            case LIST -> Reply.ok(Bodies.listReply(agents()));
            case EVENT -> onEvent(peer, body);
            case MESSAGE -> onMessage(body);
            case RETRACT, DISPOSE -> onRequest(op, body);
        };
    }

    /** @return the agents at this host now */
    public List<AgentInfo> agents() {
        return state.hosted.values().stream().map(HostedAgent::info).toList();
    }

    /** Where an agent went, for calls that arrive after it left. */
    private Reply whereIs(UUID id) {
        String to = state.forwardOf(id);
        return to != null ? Reply.of(Reply.Status.MOVED, to) : Reply.of(Reply.Status.GONE, "agent " + id + " is not at host " + state.name);
    }

    /** The agent, once it has settled: one that is leaving is waited for until it has left (then it is not here). */
    private HostedAgent present(UUID id) {
        HostedAgent h = state.hosted.get(id);
        if (h != null && h.status == AgentStatus.IN_TRANSIT) {
            try {
                h.departure.get(state.timeoutMillis, TimeUnit.MILLISECONDS);
            } catch (Exception e) {
                return h;
            }
            return state.hosted.get(id);
        }
        return h;
    }

    private Reply onMessage(byte[] body) {
        Bodies.Message sent = Bodies.readMessage(body);
        UUID id = sent.id();
        HostedAgent h = present(id);
        if (h == null) {
            return whereIs(id);
        }
        Serializable value;
        try {
            value = state.codec.read(sent.content(), h.loader, Serializable.class);
        } catch (StateRejectedException e) {
            return state.refuse("refused a message for agent " + id + ": " + e.getMessage());
        }
        Message m = new Message(value);
        boolean handled;
        try {
            handled = h.agent.handleMessage(m);
        } catch (RuntimeException e) {
            return Reply.of(Reply.Status.REFUSED, "agent " + id + " threw while handling the message: " + e);
        }
        if (!handled) {
            if (sent.oneway()) {
                LOG.info("host {}: agent {} did not handle a one-way message; dropped", state.name, id);
            }
            return Reply.of(Reply.Status.NOT_HANDLED, "agent " + id + " (" + h.className + ") did not handle the message");
        }
        try {
            return Reply.ok(m.reply == null ? new byte[0] : StateCodec.write(m.reply));
        } catch (IOException e) {
            return Reply.of(Reply.Status.REFUSED, "agent " + id + "'s reply is not serializable: " + e.getMessage());
        }
    }

    /** A message as an agent handles it; the first reply it sends is the answer. */
    private static final class Message implements AgentMessage {
        private final Serializable content;
        private volatile Serializable reply;

        Message(Serializable content) {
            this.content = content;
        }

        @Override
        public Serializable content() {
            return content;
        }

        @Override
        public void sendReply(Serializable r) {
            if (reply == null) {
                reply = r;
            }
        }
    }

    private Reply onRequest(Op op, byte[] body) {
        UUID id = Bodies.readAgentRequest(body);
        HostedAgent h = present(id);
        if (h == null) {
            return whereIs(id);
        }
        if (op == Op.RETRACT) {
            h.retractRequested = true;
        } else {
            h.disposeRequested = true;
        }
        LOG.info("host {}: {} requested for agent {}; it takes effect when its current callback returns", state.name, op, id);
        return Reply.ok();
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
        HostAddress a = HostAddress.parse(address);
        PeerLink link = new PeerLink(a, "mw-agents-" + ProcessHandle.current().pid(), key, new HostSockets.Client(a.host(), useTls, 10_000), new SecureRandom());
        Reply r = link.call(Op.LIST, new byte[0]);
        if (r.status() != Reply.Status.OK) {
            throw new IOException(address + " answered " + r.status() + ": " + r.text());
        }
        return Bodies.readListReply(r.body());
    }

    @Override
    public String toString() {
        return "AgentHost[" + name + " at " + state.address + "]";
    }
}
