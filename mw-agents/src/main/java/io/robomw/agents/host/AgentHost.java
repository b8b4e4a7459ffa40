package io.robomw.agents.host;

import io.robomw.agents.host.code.ArchiveClassLoader;
import io.robomw.agents.host.code.CodeArchive;
import io.robomw.agents.host.code.CodeSources;
import io.robomw.agents.host.code.StateCodec;
import io.robomw.agents.host.code.StateRejectedException;
import io.robomw.agents.host.store.AgentStore;
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
import java.io.ByteArrayOutputStream;
import java.io.DataInputStream;
import java.io.DataOutputStream;
import java.io.IOException;
import java.io.ObjectInputFilter;
import java.io.ObjectInputStream;
import java.io.ObjectStreamClass;
import java.io.Serializable;
import java.io.UncheckedIOException;
import java.net.InetAddress;
import java.net.InetSocketAddress;
import java.net.ServerSocket;
import java.nio.ByteBuffer;
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
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Map;
import java.util.Objects;
import java.util.Optional;
import java.util.UUID;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.CompletionException;
import java.util.concurrent.ConcurrentHashMap;
import java.util.concurrent.ExecutorService;
import java.util.concurrent.Executors;
import java.util.concurrent.ThreadFactory;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicInteger;

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
 */
public final class AgentHost implements Agency, AutoCloseable {

    private static final Logger LOG = LoggerFactory.getLogger(AgentHost.class);
    private static final int MAX_FORWARDS = 100_000;
    private static final int MAX_ROUTE_HOPS = 16;
    private static final long REPORT_FLUSH_MILLIS = 5_000;
    private static final byte[] NO_STATE = new byte[0];

    private final String name;
    private final String bind;
    private final int requestedPort;
    private final Robot robot;
    private final Messaging messaging;
    private final ClusterKey key;
    private final TlsSettings tls;
    private final Path storeDir;
    private final int timeoutMillis;
    private final StateCodec codec;
    private final CodeSources codeSources = new CodeSources();
    private final Map<CodeArchive.Digest, ArchiveClassLoader> loaders = new ConcurrentHashMap<>();
    private final Map<String, PeerLink> peers = new ConcurrentHashMap<>();
    private final Map<UUID, HostedAgent> hosted = new ConcurrentHashMap<>();
    private final Map<UUID, AgentHandle> handles = new ConcurrentHashMap<>();
    private final Map<UUID, String> forwards = new LinkedHashMap<>(256, 0.75f, false) {
        private static final long serialVersionUID = 1L;

        @Override
        protected boolean removeEldestEntry(Map.Entry<UUID, String> eldest) {
            return size() > MAX_FORWARDS;
        }
    };
    private final Object acceptLock = new Object();
    /** Who drives the robot: one agent's stop at a time, so two agents' moves never pre-empt each other. */
    private final java.util.concurrent.locks.ReentrantLock robotLock = new java.util.concurrent.locks.ReentrantLock(true);
    private final SecureRandom random = new SecureRandom();
    private final HostSockets.Counters counters = new HostSockets.Counters();
    private final ExecutorService runners;
    private final ExecutorService requests;
    private final HomeEvents events;
    private AgentStore store;
    private HostEndpoint endpoint;
    private Registry registry;
    private String address;
    private volatile boolean closed;

    private AgentHost(Builder b) {
        this.name = b.name;
        this.bind = b.bind;
        this.requestedPort = b.port;
        this.robot = b.robot;
        this.messaging = b.messaging;
        this.key = b.key;
        this.tls = b.tls;
        this.storeDir = b.storeDir;
        this.timeoutMillis = (int) b.callTimeout.toMillis();
        this.codec = new StateCodec(b.allowed, b.maxStateBytes);
        this.runners = Executors.newCachedThreadPool(named("agent-runner-" + name));
        this.requests = Executors.newCachedThreadPool(named("agent-requests-" + name));
        this.events = new HomeEvents(name, this::deliverEvent, this::eventDelivered);
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

        /** The host gives its agents no messaging (a home that only receives results). @return this */
        public Builder noMessaging() {
            this.messaging = null;
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
        store = storeDir == null ? new MemoryStore() : JournalStore.open(storeDir);
        InetAddress bindAddress = InetAddress.getByName(bind);
        SSLContext ssl = tls == null ? null : tls.context();
        HostSockets.Server serverSockets = new HostSockets.Server(bindAddress, ssl, counters);
        HostSockets.Client clientSockets = new HostSockets.Client(bind, tls != null, timeoutMillis);
        endpoint = new HostEndpoint(name, key, this::handle);
        long maxCall = codec.maxBytes() + (1 << 20);
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
        address = new HostAddress(bind, port, name).toString();
        recover();
        LOG.info("agent host {} listening at {} ({} store{}, robot: {})", name, address, store.durable() ? "durable " + storeDir : "memory-only",
                tls != null ? ", mutual TLS" : "", robot == null ? "none" : robot.name());
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
        if (closed) {
            return;
        }
        closed = true;
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
        runners.shutdown();
        requests.shutdown();
        try {
            if (!runners.awaitTermination(5, TimeUnit.SECONDS)) {
                runners.shutdownNow();
            }
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
            runners.shutdownNow();
        }
        events.close();
        if (!hosted.isEmpty()) {
            if (store != null && store.durable()) {
                LOG.info("agent host {} closed holding {} agents; they resume when it starts again with store {}", name, hosted.size(), storeDir);
            } else {
                LOG.warn("agent host {} closed holding {} agents in a memory-only store: they are gone", name, hosted.size());
            }
        }
        try {
            if (store != null) {
                store.close();
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
        return address;
    }

    Robot robot() {
        return robot;
    }

    /** Takes the robot for the calling agent's stop (waiting for the agent that has it), unless it already has it. */
    Robot claimRobot(HostedAgent h) {
        if (robot != null && !robotLock.isHeldByCurrentThread()) {
            if (!robotLock.tryLock()) {
                LOG.info("host {}: agent {} waits for the robot, which another agent's stop is using", name, h.id);
                robotLock.lock();
            }
        }
        return robot;
    }

    Messaging messaging() {
        return messaging;
    }

    /** @return the agents at this host now */
    public List<AgentInfo> agents() {
        return hosted.values().stream().map(HostedAgent::info).toList();
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
        return endpoint.refused() + refusedHere.get();
    }

    private final AtomicInteger refusedHere = new AtomicInteger();

    // ---- Agency: this host as home ----

    @Override
    public AgentRef sendAgent(String host, Agent agent) {
        HostAddress.parse(host);
        agent.itinerary().insertNext(host, null);
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
        byte[] state;
        try {
            state = StateCodec.write(agent);
        } catch (IOException e) {
            throw new AgentException("agent " + agent.getClass().getName() + " cannot be cloned: its state is not serializable: " + e.getMessage(), e);
        }
        List<CompletableFuture<AgentRef>> sends = new ArrayList<>();
        for (String h : hosts) {
            sends.add(CompletableFuture.supplyAsync(() -> {
                Agent clone = copy(state, agent.getClass().getClassLoader());
                clone.itinerary().clear();
                clone.itinerary().addStop(h);
                return launch(clone, UUID.randomUUID());
            }, requests));
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

    AgentRef cloneOf(HostedAgent parent, Itinerary plan) {
        Agent clone;
        try {
            clone = codec.read(StateCodec.write(parent.agent), parent.loader, Agent.class);
        } catch (IOException | StateRejectedException e) {
            throw new AgentException("agent " + parent.id + " cannot be cloned: " + e.getMessage(), e);
        }
        clone.itinerary().copyPlan(plan);
        return launch(clone, UUID.randomUUID());
    }

    /** Sends a new agent from here (its home) to its first reachable stop; blocks until that host has it. */
    private AgentRef launch(Agent agent, UUID id) {
        Class<?> type = agent.getClass();
        CodeArchive archive = codeSources.archiveOf(type);
        try {
            store.putArchive(archive);
        } catch (IOException e) {
            throw new UncheckedIOException("cannot keep the archive of " + type.getName() + ": " + e.getMessage(), e);
        }
        AgentImage origin = new AgentImage(id, 0, AgentImage.Kind.TRIP, true, address, archive.digest(), 1, new byte[0]);
        HostedAgent h = new HostedAgent(origin, agent, type.getClassLoader());
        AgentHandle handle = new AgentHandle(this, id, type.getName(), type.getClassLoader(), address);
        handles.put(id, handle);
        Departure d = depart(h);
        if (d.delivered()) {
            handle.location(d.target());
            return handle;
        }
        handles.remove(id);
        throw new AgentException("agent " + type.getName() + " " + id + " could not be sent: " + d.reason());
    }

    // ---- the trip ----

    private record Departure(boolean delivered, String target, String reason) {
    }

    private void runStop(HostedAgent h, boolean interrupted) {
        Thread t = Thread.currentThread();
        String poolName = t.getName();
        t.setName("agent-" + h.shortId() + "-" + simpleName(h.className) + "@" + name);
        try {
            Itinerary it = h.agent.itinerary();
            String stopHost = it.currentStop().map(Itinerary.Stop::host).orElse(address);
            if (interrupted) {
                it.record(stopHost, Itinerary.Outcome.INTERRUPTED, "host " + name + " stopped while this stop's work ran; it is not run twice");
                LOG.info("host {}: agent {} ({}) was mid-stop when the host stopped; going on without running the stop again", name, h.id, h.className);
            } else {
                boolean marked = false;
                try {
                    store.started(h.id, h.hop);
                    marked = true;
                } catch (IOException e) {
                    LOG.error("host {}: cannot mark agent {}'s stop as started ({}); not running it", name, h.id, e.toString());
                    it.record(stopHost, Itinerary.Outcome.FAILED, "the host's store failed: " + e.getMessage());
                }
                if (marked) {
                    HostContext ctx = new HostContext(this, h);
                    h.agent.attach(ctx);
                    try {
                        h.agent.onArrival();
                        Itinerary.Task task = it.currentStop().map(Itinerary.Stop::task).orElse(null);
                        if (task != null) {
                            task.execute(ctx);
                        } else {
                            h.agent.run();
                        }
                        it.record(stopHost, Itinerary.Outcome.DONE, "");
                    } catch (Exception | LinkageError | AssertionError | StackOverflowError e) {
                        LOG.warn("host {}: agent {} ({}) failed at its stop: {}", name, h.id, h.className, e.toString());
                        it.record(stopHost, Itinerary.Outcome.FAILED, e.toString());
                    }
                }
            }
            releaseRobot();
            moveOn(h);
        } catch (RuntimeException e) {
            LOG.error("host {}: agent {} ({}) could not go on: {}", name, h.id, h.className, e.toString(), e);
        } finally {
            releaseRobot();
            t.setName(poolName);
        }
    }

    private void releaseRobot() {
        while (robotLock.isHeldByCurrentThread()) {
            robotLock.unlock();
        }
    }

    private void moveOn(HostedAgent h) {
        h.agent.attach(new HostContext(this, h));
        if (h.retractRequested) {
            goHome(h);
            return;
        }
        if (h.disposeRequested) {
            finish(h, AgentEvent.Kind.DISPOSED);
            return;
        }
        Departure d = depart(h);
        if (d.delivered()) {
            hosted.remove(h.id);
            return;
        }
        if (!closed) {
            LOG.info("host {}: agent {} ends its trip here: {}", name, h.id, d.reason());
            finish(h, AgentEvent.Kind.RESULT);
        }
    }

    /**
     * Sends an agent on to its next reachable stop, following its itinerary's policy for stops
     * that cannot be reached. Stops at this host run here without a network hop.
     */
    private Departure depart(HostedAgent h) {
        Itinerary it = h.agent.itinerary();
        List<String> unreachable = new ArrayList<>();
        while (!closed) {
            Optional<Itinerary.Stop> next = it.goToNext();
            if (next.isEmpty()) {
                return new Departure(false, null, unreachable.isEmpty() ? "its itinerary is done" : "no further stop could be reached: " + String.join("; ", unreachable));
            }
            String target = next.get().host();
            try {
                h.agent.onDispatching();
            } catch (RuntimeException e) {
                LOG.warn("host {}: agent {} onDispatching threw {}", name, h.id, e.toString());
            }
            events.awaitDelivered(h.id, REPORT_FLUSH_MILLIS);
            h.agent.attach(null);
            AgentImage image = new AgentImage(h.id, h.hop + 1, AgentImage.Kind.TRIP, h.home.equals(address), h.home, h.digest, h.eventSeq, NO_STATE);
            Frame frame;
            try {
                frame = image.frame(h.agent, h.imageSize);
            } catch (IOException e) {
                h.agent.attach(new HostContext(this, h));
                return new Departure(false, null, "its state is not serializable: " + e.getMessage());
            }
            h.imageSize = frame.bodyLength();
            String why = send(h, image, frame, target, it);
            if (why == null) {
                return new Departure(true, target, null);
            }
            h.agent.attach(new HostContext(this, h));
            it.record(target, Itinerary.Outcome.UNREACHABLE, why);
            unreachable.add(target + " (" + why + ")");
            LOG.warn("host {}: agent {} cannot reach {}: {}", name, h.id, target, why);
            if (it.unreachablePolicy() == Itinerary.UnreachablePolicy.RETURN_HOME) {
                return new Departure(false, null, "its stop " + target + " could not be reached and its policy is to return home");
            }
        }
        return new Departure(false, null, "the host is closing");
    }

    /**
     * Delivers an image to a host, with the itinerary's retries.
     *
     * @return {@code null} once delivered; why not, if the stop is unreachable
     */
    private String send(HostedAgent h, AgentImage image, Frame raw, String target, Itinerary it) {
        try {
            store.departing(h.id, image.hop(), raw.bytes, raw.bodyOffset(), raw.bodyLength());
        } catch (IOException e) {
            LOG.warn("host {}: cannot record agent {} departing: {}", name, h.id, e.toString());
        }
        h.status = AgentStatus.IN_TRANSIT;
        int attempts = it.unreachablePolicy() == Itinerary.UnreachablePolicy.RETRY ? 1 + it.retries() : 1;
        String why = null;
        for (int a = 0; a < attempts && !closed; a++) {
            if (a > 0 && !pause(it.retryBackoff().toMillis())) {
                break;
            }
            try {
                transfer(image, raw, target);
                arrivedElsewhere(h, image, target);
                return null;
            } catch (RefusedException e) {
                why = e.getMessage();
                break;
            } catch (PeerException e) {
                why = e.getMessage();
                if (e.delivered()) {
                    // It may be there already: only that host may have it, so ask it until it answers.
                    if (resendUntilAnswered(image, raw, target)) {
                        arrivedElsewhere(h, image, target);
                        return null;
                    }
                    return "host closed while the transfer was unanswered";
                }
            }
        }
        h.status = AgentStatus.ACTIVE;
        return why == null ? "the host is closing" : why;
    }

    private void arrivedElsewhere(HostedAgent h, AgentImage image, String target) {
        h.hop = image.hop();
        try {
            store.departed(h.id);
        } catch (IOException e) {
            LOG.warn("host {}: cannot record agent {} departed: {}", name, h.id, e.toString());
        }
        synchronized (forwards) {
            forwards.put(h.id, target);
        }
        h.departure.complete(target);
        AgentHandle handle = handles.get(h.id);
        if (handle != null) {
            // This host is the agent's home and the target has acknowledged: it is there now.
            handle.arrived(target);
        }
    }

    private boolean resendUntilAnswered(AgentImage image, Frame raw, String target) {
        long backoff = 200;
        while (!closed) {
            if (!pause(backoff)) {
                return false;
            }
            try {
                transfer(image, raw, target);
                return true;
            } catch (RefusedException e) {
                LOG.error("host {}: {} refused agent {} after a transfer that may have reached it: {}; keeping it here", name, target, image.id(), e.getMessage());
                return false;
            } catch (PeerException e) {
                LOG.warn("host {}: transfer of agent {} to {} still unanswered ({}); asking again in {} ms", name, image.id(), target, e.getMessage(), backoff);
                backoff = Math.min(5_000, backoff * 2);
            }
        }
        return false;
    }

    private boolean pause(long millis) {
        try {
            Thread.sleep(millis); // the itinerary's retry back-off, not a wait for a condition
            return true;
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
            return false;
        }
    }

    /** A host refused an agent or archive outright: it did not take it, and will not. */
    private static final class RefusedException extends Exception {
        private static final long serialVersionUID = 1L;

        RefusedException(String message) {
            super(message);
        }
    }

    private void transfer(AgentImage image, Frame raw, String target) throws PeerException, RefusedException {
        Reply r = call(target, Op.TRANSFER, raw);
        if (r.status() == Reply.Status.NEED_ARCHIVE) {
            CodeArchive archive = store.archive(image.digest())
                    .orElseThrow(() -> new RefusedException("this host lacks archive " + image.digest() + " that " + target + " asks for"));
            byte[] digest = archive.digest().bytes();
            byte[] body = ByteBuffer.allocate(digest.length + archive.bytes().length).put(digest).put(archive.bytes()).array();
            Reply a = call(target, Op.PUT_ARCHIVE, body);
            if (a.status() != Reply.Status.OK) {
                throw new RefusedException(target + " refused archive " + archive.digest() + ": " + a.text());
            }
            r = call(target, Op.TRANSFER, raw);
        }
        switch (r.status()) {
            case OK, DUPLICATE -> {
            }
            case REFUSED -> throw new RefusedException(target + " refused agent " + image.id() + ": " + r.text());
            default -> throw new RefusedException(target + " answered " + r.status() + " to a transfer");
        }
    }

    private Reply call(String target, Op op, byte[] body) throws PeerException {
        if (target.equals(address)) {
            return handle(name, op, body);
        }
        return link(target).call(op, body);
    }

    /** A call whose body is already in its frame (a transfer): sent without copying it into a request. */
    private Reply call(String target, Op op, Frame frame) throws PeerException {
        if (target.equals(address)) {
            return handle(name, op, frame.bytes, frame.bodyOffset(), frame.bodyLength());
        }
        return link(target).call(op, frame);
    }

    private PeerLink link(String target) {
        return peers.computeIfAbsent(target, t -> {
            HostAddress a = HostAddress.parse(t);
            return new PeerLink(a, name, key, new HostSockets.Client(a.host(), tls != null, timeoutMillis), random);
        });
    }

    private void finish(HostedAgent h, AgentEvent.Kind kind) {
        HostContext ctx = new HostContext(this, h);
        h.agent.attach(ctx);
        try {
            h.agent.onDisposing();
        } catch (RuntimeException e) {
            LOG.warn("host {}: agent {} onDisposing threw {}", name, h.id, e.toString());
        }
        h.agent.attach(null);
        byte[] payload;
        AgentEvent.Kind k = kind;
        Optional<Itinerary.Visit> failed = h.agent.itinerary().history().stream()
                .filter(v -> v.outcome() == Itinerary.Outcome.FAILED).reduce((first, second) -> second);
        if (kind == AgentEvent.Kind.RESULT && h.result == null && failed.isPresent()) {
            // Nothing to bring home, and a stop failed: that failure is the outcome of the trip.
            k = AgentEvent.Kind.FAILED;
            payload = ("brought no result home: its stop at " + failed.get().host() + " failed: " + failed.get().detail()).getBytes(StandardCharsets.UTF_8);
        } else if (kind == AgentEvent.Kind.RESULT) {
            try {
                payload = StateCodec.write(h.result);
            } catch (IOException e) {
                k = AgentEvent.Kind.FAILED;
                payload = ("ended at " + name + " but its result is not serializable: " + e.getMessage()).getBytes(StandardCharsets.UTF_8);
            }
        } else {
            payload = ("was disposed of at " + address).getBytes(StandardCharsets.UTF_8);
        }
        h.status = k == AgentEvent.Kind.RESULT ? AgentStatus.COMPLETED : k == AgentEvent.Kind.DISPOSED ? AgentStatus.DISPOSED : AgentStatus.FAILED;
        AgentEvent event = new AgentEvent(h.id, h.eventSeq++, k, address, payload);
        owe(h.home, event);
        try {
            store.departed(h.id);
        } catch (IOException e) {
            LOG.warn("host {}: cannot record agent {} ended: {}", name, h.id, e.toString());
        }
        hosted.remove(h.id);
        h.departure.complete(null);
    }

    private void goHome(HostedAgent h) {
        try {
            h.agent.onDispatching();
        } catch (RuntimeException e) {
            LOG.warn("host {}: agent {} onDispatching threw {}", name, h.id, e.toString());
        }
        h.agent.attach(null);
        AgentImage image = new AgentImage(h.id, h.hop + 1, AgentImage.Kind.HOMECOMING, h.home.equals(address), h.home, h.digest, h.eventSeq, NO_STATE);
        Frame frame;
        try {
            frame = image.frame(h.agent, h.imageSize);
        } catch (IOException e) {
            finish(h, AgentEvent.Kind.RESULT);
            return;
        }
        Itinerary homeward = new Itinerary().onUnreachable(Itinerary.UnreachablePolicy.RETRY).retry(1_000_000, Duration.ofSeconds(1));
        if (send(h, image, frame, h.home, homeward) == null) {
            hosted.remove(h.id);
        }
    }

    private void owe(String home, AgentEvent event) {
        byte[] homeBytes = home.getBytes(StandardCharsets.UTF_8);
        byte[] e = event.encode();
        byte[] record = ByteBuffer.allocate(2 + homeBytes.length + e.length).putShort((short) homeBytes.length).put(homeBytes).put(e).array();
        try {
            store.eventPending(new AgentStore.PendingEvent(event.id(), event.seq(), record));
        } catch (IOException ex) {
            LOG.warn("host {}: cannot store {} of agent {} ({}); sending it anyway", name, event.kind(), event.id(), ex.toString());
        }
        events.send(home, event, true);
    }

    void report(HostedAgent h, Serializable value) {
        byte[] payload;
        try {
            payload = StateCodec.write(value);
        } catch (IOException e) {
            throw new IllegalArgumentException("report value of agent " + h.id + " is not serializable: " + e.getMessage(), e);
        }
        long seq;
        synchronized (h) {
            seq = h.eventSeq++;
        }
        owe(h.home, new AgentEvent(h.id, seq, AgentEvent.Kind.REPORT, address, payload));
    }

    private void deliverEvent(String home, AgentEvent event) throws Exception {
        Reply r = call(home, Op.EVENT, event.encode());
        if (r.status() != Reply.Status.OK) {
            throw new IOException(home + " answered " + r.status() + ": " + r.text());
        }
    }

    private void eventDelivered(AgentEvent event) {
        try {
            store.eventDelivered(event.id(), event.seq());
        } catch (IOException e) {
            LOG.warn("host {}: cannot record an event delivered: {}", name, e.toString());
        }
    }

    // ---- recovery ----

    private void recover() {
        int accepted = 0;
        int interrupted = 0;
        int departing = 0;
        for (AgentStore.StoredAgent s : store.recoveredAgents()) {
            AgentImage image = AgentImage.decode(s.image());
            HostedAgent h;
            try {
                ClassLoader loader = loaderFor(image.digest()).orElseThrow(() -> new StateRejectedException("its archive " + image.digest() + " is missing from the store"));
                h = new HostedAgent(image, codec.read(image.state(), image.stateOffset(), image.stateLength(), loader, Agent.class), loader);
            } catch (StateRejectedException | IOException e) {
                LOG.error("host {}: cannot resume agent {} from the store: {}", name, image.id(), e.getMessage());
                continue;
            }
            switch (s.phase()) {
                case ACCEPTED -> {
                    accepted++;
                    hosted.put(h.id, h);
                    runners.execute(() -> runStop(h, false));
                }
                case STARTED -> {
                    interrupted++;
                    hosted.put(h.id, h);
                    runners.execute(() -> runStop(h, true));
                }
                case DEPARTING -> {
                    departing++;
                    h.hop = image.hop() - 1;
                    hosted.put(h.id, h);
                    runners.execute(() -> resumeDeparture(h, image));
                }
            }
        }
        List<AgentStore.PendingEvent> owed = store.recoveredEvents();
        for (AgentStore.PendingEvent p : owed) {
            ByteBuffer b = ByteBuffer.wrap(p.event());
            byte[] home = new byte[Short.toUnsignedInt(b.getShort())];
            b.get(home);
            byte[] e = new byte[b.remaining()];
            b.get(e);
            events.send(new String(home, StandardCharsets.UTF_8), AgentEvent.decode(e), true);
        }
        if (accepted + interrupted + departing + owed.size() > 0) {
            LOG.info("host {}: resumed {} agents from {} ({} not yet started, {} interrupted mid-stop, {} departing) and {} events owed to homes",
                    name, accepted + interrupted + departing, storeDir, accepted, interrupted, departing, owed.size());
        }
    }

    private void resumeDeparture(HostedAgent h, AgentImage image) {
        String target = image.kind() == AgentImage.Kind.HOMECOMING ? h.home
                : h.agent.itinerary().currentStop().map(Itinerary.Stop::host).orElse(null);
        if (target == null) {
            moveOn(h);
            return;
        }
        Itinerary plan = image.kind() == AgentImage.Kind.HOMECOMING
                ? new Itinerary().onUnreachable(Itinerary.UnreachablePolicy.RETRY).retry(1_000_000, Duration.ofSeconds(1))
                : h.agent.itinerary();
        String why = send(h, image, Frame.of(image.encode()), target, plan);
        if (why == null) {
            hosted.remove(h.id);
            return;
        }
        h.agent.itinerary().record(target, Itinerary.Outcome.UNREACHABLE, why);
        if (h.agent.itinerary().unreachablePolicy() == Itinerary.UnreachablePolicy.RETURN_HOME) {
            finish(h, AgentEvent.Kind.RESULT);
        } else {
            moveOn(h);
        }
    }

    // ---- serving calls ----

    private Reply handle(String peer, Op op, byte[] body) {
        return handle(peer, op, body, 0, body.length);
    }

    /** Serves a verified call; a transfer is decoded in place (it may be megabytes), other bodies are copied out. */
    private Reply handle(String peer, Op op, byte[] message, int offset, int length) {
        if (op == Op.TRANSFER && !closed) {
            return onTransferWithRunner(peer, message, offset, length);
        }
        byte[] body = java.util.Arrays.copyOfRange(message, offset, offset + length);
        if (closed) {
            return Reply.of(Reply.Status.REFUSED, "host " + name + " is closing");
        }
        return switch (op) {
            case TRANSFER -> onTransfer(peer, body, 0, body.length, null);
            case PUT_ARCHIVE -> onArchive(peer, body);
            case LIST -> onList();
            case EVENT -> onEvent(peer, body);
            case MESSAGE -> onMessage(body);
            case RETRACT, DISPOSE -> onRequest(op, body);
        };
    }

    /**
     * A transfer, with a runner thread woken as it comes in rather than once it is accepted: waking
     * a parked thread takes tens of microseconds here, about as long as checking, reading and
     * storing the agent, so the two overlap. The runner waits until the agent is stored (its stop
     * never starts before that) and goes back to the pool if the transfer is not accepted. A warm
     * A→B→A round trip with a 0 B payload: p50 104–163 → 90–129 µs in alternating probe runs.
     */
    private Reply onTransferWithRunner(String peer, byte[] raw, int offset, int length) {
        java.util.concurrent.CompletableFuture<HostedAgent> accepted = new java.util.concurrent.CompletableFuture<>();
        runners.execute(() -> {
            HostedAgent h = accepted.join();
            if (h != null) {
                runStop(h, false);
            }
        });
        HostedAgent[] started = new HostedAgent[1];
        try {
            return onTransfer(peer, raw, offset, length, started);
        } finally {
            accepted.complete(started[0]);
        }
    }

    /** @param started where to put the accepted agent for a runner already woken, or {@code null} to start one */
    private Reply onTransfer(String peer, byte[] raw, int offset, int length, HostedAgent[] started) {
        AgentImage image;
        try {
            image = AgentImage.decode(raw, offset, length);
        } catch (IllegalArgumentException e) {
            return refuse("refused a transfer from peer '" + peer + "': " + e.getMessage());
        }
        if (image.hop() <= store.highestHop(image.id())) {
            return new Reply(Reply.Status.DUPLICATE, new byte[0]);
        }
        if (image.kind() == AgentImage.Kind.HOMECOMING) {
            return onHomecoming(peer, image);
        }
        ClassLoader loader;
        try {
            Optional<ClassLoader> l = loaderFor(image.digest());
            if (l.isEmpty()) {
                return new Reply(Reply.Status.NEED_ARCHIVE, new byte[0]);
            }
            loader = l.get();
        } catch (IOException e) {
            return refuse("refused agent " + image.id() + " from peer '" + peer + "': its archive " + image.digest() + " is not a jar: " + e.getMessage());
        }
        Agent agent;
        try {
            agent = codec.read(image.state(), image.stateOffset(), image.stateLength(), loader, Agent.class);
        } catch (StateRejectedException e) {
            return refuse("refused agent " + image.id() + " from peer '" + peer + "': " + e.getMessage());
        }
        if (agent == null) {
            return refuse("refused agent " + image.id() + " from peer '" + peer + "': its state is null");
        }
        HostedAgent h = new HostedAgent(image, agent, loader);
        h.imageSize = length;
        // Messages may come as soon as the sender has the acknowledgement, before the stop starts.
        agent.attach(new HostContext(this, h));
        synchronized (acceptLock) {
            if (image.hop() <= store.highestHop(image.id())) {
                return new Reply(Reply.Status.DUPLICATE, new byte[0]);
            }
            try {
                store.accepted(image.id(), image.hop(), raw, offset, length);
            } catch (IOException e) {
                LOG.error("host {}: cannot store agent {}: {}; refusing it (the sender keeps it)", name, image.id(), e.toString());
                return Reply.of(Reply.Status.REFUSED, "host " + name + " cannot store the agent: " + e.getMessage());
            }
            hosted.put(h.id, h);
        }
        if (h.home.equals(address)) {
            // Back at its home: the handle is here, no news to send.
            AgentHandle handle = handles.get(h.id);
            if (handle != null) {
                handle.arrived(address);
            }
        } else if (!image.fromHome()) {
            // The home learns from the transfer's acknowledgement when it sent the agent itself;
            // otherwise it is told, once, as news (a later arrival makes an unsent one moot).
            events.send(h.home, new AgentEvent(h.id, 0, AgentEvent.Kind.ARRIVED, address, new byte[0]), false);
        }
        if (started != null) {
            started[0] = h;
        } else {
            runners.execute(() -> runStop(h, false));
        }
        return Reply.ok();
    }

    private Reply onHomecoming(String peer, AgentImage image) {
        AgentHandle handle = handles.get(image.id());
        if (handle == null) {
            return refuse("refused homecoming agent " + image.id() + " from peer '" + peer + "': it was not sent from here");
        }
        try {
            Agent agent = codec.read(image.state(), image.stateOffset(), image.stateLength(), handle.loader, Agent.class);
            store.accepted(image.id(), image.hop(), new byte[0], 0, 0);
            handle.retracted(peer, agent);
            return Reply.ok();
        } catch (StateRejectedException | IOException e) {
            return refuse("refused homecoming agent " + image.id() + " from peer '" + peer + "': " + e.getMessage());
        }
    }

    private Reply onArchive(String peer, byte[] body) {
        if (body.length <= CodeArchive.Digest.LENGTH) {
            return refuse("refused an archive from peer '" + peer + "': " + body.length + " bytes is too short");
        }
        CodeArchive.Digest claimed = new CodeArchive.Digest(java.util.Arrays.copyOf(body, CodeArchive.Digest.LENGTH));
        byte[] jar = java.util.Arrays.copyOfRange(body, CodeArchive.Digest.LENGTH, body.length);
        CodeArchive archive = CodeArchive.of(jar);
        if (!archive.digest().equals(claimed)) {
            return refuse("refused an archive from peer '" + peer + "': it claims " + claimed.hex() + " but its bytes hash to " + archive.digest().hex()
                    + " (tampered with or corrupted)");
        }
        try {
            ArchiveClassLoader checked = new ArchiveClassLoader(archive, AgentHost.class.getClassLoader());
            store.putArchive(archive);
            synchronized (loaders) {
                loaders.putIfAbsent(archive.digest(), checked); // the transfer that asked for it follows: no second read of the jar
            }
        } catch (IOException e) {
            return refuse("refused archive " + claimed + " from peer '" + peer + "': " + e.getMessage());
        }
        LOG.info("host {}: received archive {} ({} bytes) from peer '{}'", name, archive.digest(), jar.length, peer);
        return Reply.ok();
    }

    private Reply refuse(String why) {
        refusedHere.incrementAndGet();
        LOG.warn("host {}: {}", name, why);
        return Reply.of(Reply.Status.REFUSED, why);
    }

    private Optional<ClassLoader> loaderFor(CodeArchive.Digest digest) throws IOException {
        ArchiveClassLoader l = loaders.get(digest);
        if (l != null) {
            return Optional.of(l);
        }
        Optional<CodeArchive> archive = store.archive(digest);
        if (archive.isEmpty()) {
            return Optional.empty();
        }
        synchronized (loaders) {
            l = loaders.get(digest);
            if (l == null) {
                l = new ArchiveClassLoader(archive.get(), AgentHost.class.getClassLoader());
                loaders.put(digest, l);
            }
        }
        return Optional.of(l);
    }

    private Reply onList() {
        try {
            ByteArrayOutputStream bytes = new ByteArrayOutputStream();
            DataOutputStream out = new DataOutputStream(bytes);
            List<AgentInfo> list = agents();
            out.writeInt(list.size());
            for (AgentInfo a : list) {
                out.writeLong(a.id().getMostSignificantBits());
                out.writeLong(a.id().getLeastSignificantBits());
                out.writeUTF(a.className());
                out.writeByte(a.status().ordinal());
                out.writeLong(a.hop());
                out.writeUTF(a.home());
            }
            return Reply.ok(bytes.toByteArray());
        } catch (IOException e) {
            throw new UncheckedIOException(e);
        }
    }

    private Reply onEvent(String peer, byte[] body) {
        AgentEvent e;
        try {
            e = AgentEvent.decode(body);
        } catch (IllegalArgumentException ex) {
            return refuse("refused an event from peer '" + peer + "': " + ex.getMessage());
        }
        AgentHandle h = handles.get(e.id());
        if (h == null) {
            LOG.debug("host {}: {} for agent {} which was not sent from here; dropped", name, e.kind(), e.id());
            return Reply.ok();
        }
        switch (e.kind()) {
            case ARRIVED -> h.arrived(e.location());
            case REPORT, RESULT -> {
                Serializable value;
                try {
                    value = codec.read(e.payload(), h.loader, Serializable.class);
                } catch (StateRejectedException ex) {
                    refuse("dropped a " + e.kind() + " of agent " + e.id() + " from peer '" + peer + "': " + ex.getMessage());
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

    /** Where an agent went, for calls that arrive after it left. */
    private Reply whereIs(UUID id) {
        String to;
        synchronized (forwards) {
            to = forwards.get(id);
        }
        return to != null ? Reply.of(Reply.Status.MOVED, to) : Reply.of(Reply.Status.GONE, "agent " + id + " is not at host " + name);
    }

    private HostedAgent present(UUID id) {
        HostedAgent h = hosted.get(id);
        if (h != null && h.status == AgentStatus.IN_TRANSIT) {
            try {
                h.departure.get(timeoutMillis, TimeUnit.MILLISECONDS);
            } catch (Exception e) {
                return h;
            }
            return hosted.get(id);
        }
        return h;
    }

    private Reply onMessage(byte[] body) {
        ByteBuffer b = ByteBuffer.wrap(body);
        UUID id = new UUID(b.getLong(), b.getLong());
        boolean oneway = b.get() != 0;
        byte[] content = new byte[b.remaining()];
        b.get(content);
        HostedAgent h = present(id);
        if (h == null) {
            return whereIs(id);
        }
        Serializable value;
        try {
            value = codec.read(content, h.loader, Serializable.class);
        } catch (StateRejectedException e) {
            return refuse("refused a message for agent " + id + ": " + e.getMessage());
        }
        Message m = new Message(value);
        boolean handled;
        try {
            handled = h.agent.handleMessage(m);
        } catch (RuntimeException e) {
            return Reply.of(Reply.Status.REFUSED, "agent " + id + " threw while handling the message: " + e);
        }
        if (!handled) {
            if (oneway) {
                LOG.info("host {}: agent {} did not handle a one-way message; dropped", name, id);
            }
            return Reply.of(Reply.Status.NOT_HANDLED, "agent " + id + " (" + h.className + ") did not handle the message");
        }
        try {
            return Reply.ok(m.reply == null ? new byte[0] : StateCodec.write(m.reply));
        } catch (IOException e) {
            return Reply.of(Reply.Status.REFUSED, "agent " + id + "'s reply is not serializable: " + e.getMessage());
        }
    }

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
        ByteBuffer b = ByteBuffer.wrap(body);
        UUID id = new UUID(b.getLong(), b.getLong());
        HostedAgent h = present(id);
        if (h == null) {
            return whereIs(id);
        }
        if (op == Op.RETRACT) {
            h.retractRequested = true;
        } else {
            h.disposeRequested = true;
        }
        LOG.info("host {}: {} requested for agent {}; it takes effect when its current callback returns", name, op, id);
        return Reply.ok();
    }

    // ---- the home's requests of its agents ----

    private Reply routeToAgent(AgentHandle handle, Op op, byte[] body) throws PeerException {
        String location = handle.location();
        for (int i = 0; i < MAX_ROUTE_HOPS; i++) {
            Reply r = call(location, op, body);
            if (r.status() != Reply.Status.MOVED) {
                return r;
            }
            location = r.text();
            handle.location(location);
        }
        throw new PeerException("agent " + handle.id() + " moved more than " + MAX_ROUTE_HOPS + " times while a call chased it", false, null);
    }

    CompletableFuture<Serializable> messageAgent(AgentHandle handle, Serializable content, boolean oneway) {
        byte[] bytes;
        try {
            bytes = StateCodec.write(content);
        } catch (IOException e) {
            return CompletableFuture.failedFuture(new AgentException("message to agent " + handle.id() + " is not serializable: " + e.getMessage(), e));
        }
        byte[] body = ByteBuffer.allocate(17 + bytes.length).putLong(handle.id().getMostSignificantBits())
                .putLong(handle.id().getLeastSignificantBits()).put((byte) (oneway ? 1 : 0)).put(bytes).array();
        return handle.inOrder(() -> {
            Reply r = agentCall(handle, Op.MESSAGE, body);
            return switch (r.status()) {
                case OK -> {
                    if (r.body().length == 0) {
                        yield null;
                    }
                    try {
                        yield codec.read(r.body(), handle.loader, Serializable.class);
                    } catch (StateRejectedException e) {
                        throw new AgentException("reply of agent " + handle.id() + " refused: " + e.getMessage(), e);
                    }
                }
                case NOT_HANDLED -> throw new NotHandledException(r.text());
                default -> throw failure(handle, r);
            };
        }, requests);
    }

    CompletableFuture<Void> requestOfAgent(AgentHandle handle, Op op) {
        byte[] body = ByteBuffer.allocate(16).putLong(handle.id().getMostSignificantBits()).putLong(handle.id().getLeastSignificantBits()).array();
        return handle.inOrder(() -> {
            Reply r = agentCall(handle, op, body);
            if (r.status() != Reply.Status.OK) {
                throw failure(handle, r);
            }
            return null;
        }, requests).thenApply(x -> null);
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

    private static AgentException failure(AgentHandle handle, Reply r) {
        if (r.status() == Reply.Status.GONE && handle.ended()) {
            return new AgentException("agent " + handle.id() + " has ended its trip");
        }
        return new AgentException(r.status() + ": " + r.text());
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
        DataInputStream in = new DataInputStream(new ByteArrayInputStream(r.body()));
        int n = in.readInt();
        List<AgentInfo> out = new ArrayList<>();
        for (int i = 0; i < n; i++) {
            UUID id = new UUID(in.readLong(), in.readLong());
            String cls = in.readUTF();
            AgentStatus status = AgentStatus.values()[in.readByte()];
            long hop = in.readLong();
            String home = in.readUTF();
            out.add(new AgentInfo(id, cls, status, hop, home));
        }
        return out;
    }

    private static String simpleName(String className) {
        return className.substring(className.lastIndexOf('.') + 1);
    }

    private static ThreadFactory named(String prefix) {
        AtomicInteger n = new AtomicInteger();
        return r -> {
            Thread t = new Thread(r, prefix + "-" + n.incrementAndGet());
            t.setDaemon(true);
            return t;
        };
    }

    @Override
    public String toString() {
        return "AgentHost[" + name + " at " + address + "]";
    }
}
