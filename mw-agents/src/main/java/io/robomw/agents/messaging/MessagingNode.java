package io.robomw.agents.messaging;

import io.robomw.agents.messaging.frame.Frame;
import io.robomw.agents.messaging.frame.FrameKind;
import io.robomw.agents.messaging.security.FrameMac;
import io.robomw.agents.messaging.security.PayloadSealer;
import io.robomw.agents.messaging.security.ReplayStore;
import io.robomw.agents.messaging.security.PayloadCodec;
import io.robomw.agents.messaging.security.TopicKeys;
import io.robomw.agents.messaging.spi.Channel;
import io.robomw.agents.messaging.spi.Endpoint;
import io.robomw.agents.messaging.spi.Link;
import io.robomw.agents.messaging.spi.Publication;
import io.robomw.agents.messaging.spi.Transport;
import io.robomw.agents.messaging.spi.TransportContext;
import io.robomw.agents.messaging.spi.TransportProvider;
import io.robomw.agents.net.OwnerThreads;
import io.robomw.api.Message;
import io.robomw.api.MessageListener;
import io.robomw.api.Messaging;
import io.robomw.api.spi.FailurePolicy;

import io.robomw.api.MessagingException;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import javax.crypto.SecretKey;
import java.io.IOException;
import java.io.Serializable;
import java.security.SecureRandom;
import java.time.Duration;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.List;
import java.util.Map;
import java.util.Objects;
import java.util.ServiceLoader;
import java.util.Set;
import java.util.UUID;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.ConcurrentHashMap;
import java.util.concurrent.CopyOnWriteArrayList;
import java.util.concurrent.ExecutionException;
import java.util.concurrent.Executors;
import java.util.concurrent.ScheduledExecutorService;
import java.util.concurrent.ThreadFactory;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.TimeoutException;
import java.util.concurrent.atomic.AtomicInteger;

/**
 * A messaging node: the paper's communication component for one robot, agent host or program.
 *
 * <p>A node <em>binds</em> addresses where it receives ({@code tcp://127.0.0.1:7000},
 * {@code rmi://127.0.0.1:1099/robot}, {@code udp://...}), <em>connects</em> to peers whose
 * publications it wants, <em>joins</em> multicast groups, and joins MQTT brokers
 * ({@code mqtt://broker:1883}, by binding or connecting: there it receives, publishes and
 * subscribes through the broker); the transports are found by scheme through the SPI in
 * {@link io.robomw.agents.messaging.spi}. Messages to a host it has no link to open one on demand.
 *
 * <pre>{@code
 * try (MessagingNode node = MessagingNode.builder("nxt-1").bind("tcp://127.0.0.1:0").build()) {
 *     node.addMessageListener("cmd", "secret", m -> node.replyMessage(m, "done", "ok"));
 *     ...
 * }
 * }</pre>
 *
 * <p>Publications go to every peer that subscribed to the topic over a connection or UDP, and to
 * every multicast group the node joined; a node never receives its own publications. Listeners
 * run on the receiving thread of the link the message came on (one per TCP connection, one per
 * datagram socket): a listener that takes long delays the messages behind it on that link, and
 * must not wait for a reply that would come on the same link (that wait is refused).
 *
 * <p>Thread-safe. Close it to close every socket and thread it opened.
 */
public final class MessagingNode implements Messaging, AutoCloseable {

    private static final Logger LOG = LoggerFactory.getLogger(MessagingNode.class);
    private static final int REMEMBERED_REQUESTS = 65_536;
    /** The correlation id of a refusal of a whole connection (an ERROR that answers no request). */
    private static final UUID REFUSAL = new UUID(0, 0);

    /** Where a received request came from, for its reply. */
    record Origin(Channel channel, SecretKey key) {
    }

    /** A request this node sent, for routing and checking its reply. */
    record Sent(String host, String topic, SecretKey key) {
    }

    private final String name;
    private final long id;
    private final MessagingSettings settings;
    private final FailurePolicy failures;
    private final Set<String> names = ConcurrentHashMap.newKeySet();
    private final AtomicInteger threadNumbers = new AtomicInteger();
    private final NodeCounters counters;
    private final TopicKeys keys = new TopicKeys();
    private final FrameFactory frames;
    private final LocalTopics topics;
    private final RemoteSubscribers remoteSubscribers;
    /** The topics this node published on, for discovery (at most {@link #MAX_ANNOUNCED_TOPICS}). */
    private final java.util.Set<String> published = new java.util.concurrent.ConcurrentSkipListSet<>();
    /** The topic published on last: a stream of publications on one topic skips the set. */
    private volatile String lastPublished;
    /** How many published topics a node remembers for {@link #publishedTopics()}. */
    static final int MAX_ANNOUNCED_TOPICS = 256;
    private final Replies replies = new Replies();
    private final BoundedMap<UUID, Sent> sentRequests = new BoundedMap<>(REMEMBERED_REQUESTS);
    private final BoundedMap<UUID, Origin> receivedRequests = new BoundedMap<>(REMEMBERED_REQUESTS);
    private final Inbound inbound;
    private final Map<String, TransportProvider> providers = new ConcurrentHashMap<>();
    private final Map<String, Transport> transports = new ConcurrentHashMap<>();
    private final Links links;
    private final List<Endpoint> endpoints = new CopyOnWriteArrayList<>();
    /** The endpoints publications are broadcast to (a multicast group), as an array read by every publication. */
    private volatile Endpoint[] broadcasters = new Endpoint[0];
    private final Set<Channel> connections = ConcurrentHashMap.newKeySet();
    /** Channels to brokers (MQTT): every publication goes to each of them once. */
    private final Set<Channel> brokers = ConcurrentHashMap.newKeySet();
    private final List<Address> peers = new CopyOnWriteArrayList<>();
    private final ScheduledExecutorService housekeeping;
    private final Context context = new Context();
    private final Presence presence;
    private final ReplayStore replayStore;
    private volatile boolean closed;
    private volatile boolean joinedGroup;

    /** @return where nodes keep their replay windows unless told otherwise: {@code ~/.robomw/replay} */
    public static Path defaultReplayDirectory() {
        return Path.of(System.getProperty("user.home"), ".robomw", "replay");
    }

    /** @return the folder this node keeps its replay window in ({@link Builder#replayDirectory}), or empty when it keeps it in memory only */
    public java.util.Optional<Path> replayDirectory() {
        Path f = replayStore.file();
        return f == null ? java.util.Optional.empty() : java.util.Optional.ofNullable(f.toAbsolutePath().getParent());
    }

    private MessagingNode(String name, MessagingSettings settings, ClassLoader classLoader, FailurePolicy failures, ReplayStore store) {
        this.name = name;
        this.settings = settings;
        this.failures = failures;
        this.id = new SecureRandom().nextLong();
        this.names.add(name);
        this.counters = new NodeCounters(name);
        PayloadCodec payloads = new PayloadCodec(settings.allowList(), classLoader);
        FrameMac mac = new FrameMac();
        PayloadSealer sealer = new PayloadSealer();
        this.replayStore = store;
        this.frames = new FrameFactory(name, id, payloads, mac, sealer, settings.maxFrameSize());
        this.topics = new LocalTopics(name);
        this.remoteSubscribers = new RemoteSubscribers(settings.limits());
        this.inbound = new Inbound(this, counters, mac, payloads, settings, failures, sealer, store);
        this.links = new Links(name, this::transport, this::linkOpened);
        this.presence = new Presence(name, this::boundAddresses);
        for (TransportProvider p : ServiceLoader.load(TransportProvider.class, MessagingNode.class.getClassLoader())) {
            providers.putIfAbsent(p.scheme(), p);
        }
        this.housekeeping = Executors.newSingleThreadScheduledExecutor(context.threads("housekeeping"));
        long period = settings.subscriptionRefresh().toMillis();
        housekeeping.scheduleWithFixedDelay(OwnerThreads.rounds(failures, this::keepHouse), period, period, TimeUnit.MILLISECONDS);
        long keepAlive = Math.max(1, settings.limits().keepAliveInterval().toMillis() / 2);
        housekeeping.scheduleWithFixedDelay(OwnerThreads.rounds(failures, this::keepAlive), keepAlive, keepAlive, TimeUnit.MILLISECONDS);
    }

    /**
     * @param name the node's name: the sender name of its messages, and a receiver name it answers to
     * @return a builder
     */
    public static Builder builder(String name) {
        return new Builder(name);
    }

    /** Builds a node: settings, then where it binds, connects and joins. */
    public static final class Builder {
        private final String name;
        private MessagingSettings settings = MessagingSettings.defaults();
        private ClassLoader classLoader = Thread.currentThread().getContextClassLoader();
        private FailurePolicy failures = FailurePolicy.logging();
        private final List<String> binds = new ArrayList<>();
        private final List<String> connects = new ArrayList<>();
        private Path replayDirectory = defaultReplayDirectory();

        private Builder(String name) {
            if (name == null || name.isBlank()) {
                throw new IllegalArgumentException("a messaging node needs a name, got '" + name + "'");
            }
            this.name = name;
        }

        /** @param s the settings @return this builder */
        public Builder settings(MessagingSettings s) {
            this.settings = Objects.requireNonNull(s, "settings");
            return this;
        }

        /** @param loader where payload classes are loaded from (default: the building thread's context loader) @return this builder */
        public Builder classLoader(ClassLoader loader) {
            this.classLoader = Objects.requireNonNull(loader, "classLoader");
            return this;
        }

        /**
         * @param policy where whatever the node's threads (transports' read, write and accept loops,
         *               housekeeping) and its listeners throw goes (default {@link FailurePolicy#logging()})
         * @return this builder
         */
        public Builder failures(FailurePolicy policy) {
            this.failures = Objects.requireNonNull(policy, "policy");
            return this;
        }

        /**
         * Where the node keeps its replay window across restarts ({@link ReplayStore}, a file named
         * after the node): by default {@code ~/.robomw/replay}; {@code null} keeps it in memory only
         * (a replay of a frame taken before a restart is then refused only once it is older than
         * the allowed clock skew).
         *
         * @param dir the folder, or {@code null}
         * @return this builder
         */
        public Builder replayDirectory(Path dir) {
            this.replayDirectory = dir;
            return this;
        }

        /** @param address where to receive: tcp, udp, rmi (listen) or multicast (join) @return this builder */
        public Builder bind(String address) {
            binds.add(address);
            return this;
        }

        /** @param address a peer whose publications this node subscribes to; reconnected when lost @return this builder */
        public Builder connect(String address) {
            connects.add(address);
            return this;
        }

        /**
         * @return the started node
         * @throws MessagingException if an address cannot be bound (a connect that fails is retried in the background)
         */
        public MessagingNode build() {
            ReplayStore store = replayDirectory == null ? ReplayStore.memoryOnly()
                    // a frame taken now may carry a timestamp up to the skew ahead, so it is stale only twice the skew from now
                    : ReplayStore.in(ReplayStore.fileFor(replayDirectory, name), settings.maxClockSkew().multipliedBy(2));
            MessagingNode node = new MessagingNode(name, settings, classLoader == null ? MessagingNode.class.getClassLoader() : classLoader, failures,
                    store);
            try {
                for (String b : binds) {
                    node.bind(b);
                }
                for (String c : connects) {
                    node.connect(c);
                }
            } catch (RuntimeException e) {
                node.close();
                throw e;
            }
            return node;
        }
    }

    // ---- configuration ----

    /**
     * Starts receiving at an address.
     *
     * @param address tcp, udp or rmi to listen; multicast to join the group
     * @return the address bound, with the real port
     */
    public Address bind(String address) {
        Address a = Address.parse(address);
        try {
            Endpoint e = transport(a.scheme()).bind(a);
            endpoints.add(e);
            if (e.broadcasts()) {
                synchronized (endpoints) {
                    broadcasters = endpoints.stream().filter(Endpoint::broadcasts).toArray(Endpoint[]::new);
                }
            }
            if (e instanceof Channel c && c.isBroker()) {
                brokers.add(c);
            }
            joinedGroup |= a.scheme().equals("multicast");
            LOG.info("node '{}' receiving at {}", name, e.address());
            return e.address();
        } catch (IOException e) {
            throw new MessagingException("node '" + name + "' cannot bind " + address + ": " + e.getMessage(), e);
        }
    }

    /**
     * Connects to a peer whose publications this node wants; the subscriptions are sent to it now
     * and whenever the link is re-established. A peer that cannot be reached now is retried in
     * the background.
     *
     * @param address the peer
     */
    public void connect(String address) {
        Address a = Address.parse(address);
        transport(a.scheme());
        peers.add(a);
        try {
            links.link(a);
        } catch (MessagingException e) {
            LOG.warn("node '{}': {}; retrying every {}", name, e.getMessage(), settings.subscriptionRefresh());
        }
    }

    /**
     * Makes this node answer messages addressed to another name as well (a robot it serves).
     *
     * @param receiverName the name
     */
    public void answerTo(String receiverName) {
        if (names.add(receiverName)) {
            transports.values().forEach(t -> t.answerTo(receiverName));
        }
    }

    /** @return where whatever the node's threads and listeners throw goes */
    public FailurePolicy failures() {
        return failures;
    }

    /** @return the node's name */
    public String name() {
        return name;
    }

    /** @return the addresses it receives at, with real ports */
    public List<Address> boundAddresses() {
        return endpoints.stream().map(Endpoint::address).toList();
    }

    /**
     * @param scheme a scheme
     * @return the first address bound with that scheme, as text
     * @throws IllegalStateException if none is
     */
    public String address(String scheme) {
        return boundAddresses().stream().filter(a -> a.scheme().equals(scheme)).findFirst().map(Address::toString)
                .orElseThrow(() -> new IllegalStateException("node '" + name + "' has no " + scheme + " address; it is bound at " + boundAddresses()));
    }

    /** @return what this node announces about itself where it can (the brokers it is connected to) */
    public Presence presence() {
        return presence;
    }

    /** @return its counters */
    public MessagingStats stats() {
        return counters.snapshot();
    }

    /**
     * @param topic a topic
     * @return how many peers (over connections or UDP) currently subscribe to it here
     */
    public int subscriberCount(String topic) {
        return remoteSubscribers.count(topic);
    }

    /** @return the topics this node listens to or subscribes to, sorted (what a discovery beacon announces) */
    public List<String> listenedTopics() {
        return topics.names();
    }

    /**
     * Says that this node publishes on a topic before it first does (as ROS's advertise), so that
     * a discovery beacon announces it and subscribers can find it.
     *
     * @param topic the topic
     */
    public void advertise(String topic) {
        if (published.size() < MAX_ANNOUNCED_TOPICS) {
            published.add(requireTopic(topic));
        }
    }

    private void remember(String topic) {
        if (!published.contains(topic) && published.size() < MAX_ANNOUNCED_TOPICS) {
            published.add(topic);
        }
        lastPublished = topic;
    }

    /** @return the topics this node has published on or advertised, sorted (at most 256; what a discovery beacon announces) */
    public List<String> publishedTopics() {
        return List.copyOf(published);
    }

    /** @return the settings */
    public MessagingSettings settings() {
        return settings;
    }

    // ---- Messaging ----

    @Override
    public UUID sendMessage(String name, String host, String pass, String topic, Serializable object, String function) {
        Outgoing out = prepare(FrameKind.MESSAGE, name, host, pass, topic, object, function);
        transmit(out);
        return out.correlationId;
    }

    /**
     * Sends a request and returns a future of its reply, registered before the request leaves
     * (so no reply can be missed).
     *
     * @param name     the receiver's name
     * @param host     its address
     * @param pass     the topic password, or {@code null}
     * @param topic    the topic
     * @param object   the payload
     * @param function the function
     * @param timeout  how long to wait for the reply
     * @return completes with the reply, or fails with {@link MessagingException} (timeout, refusal, link closed)
     */
    public CompletableFuture<Message> request(String name, String host, String pass, String topic, Serializable object,
                                              String function, Duration timeout) {
        return startRequest(name, host, pass, topic, object, function, timeout).reply();
    }

    /**
     * A request on its way.
     *
     * @param correlationId what its reply names, and what a later message about it (a cancel) can name
     * @param reply         completes with the reply, or fails with {@link MessagingException}
     */
    public record Request(UUID correlationId, CompletableFuture<Message> reply) {
    }

    /**
     * {@link #request}, also saying which correlation id the request has.
     *
     * @param name     the receiver's name
     * @param host     its address
     * @param pass     the topic password, or {@code null}
     * @param topic    the topic
     * @param object   the payload
     * @param function the function
     * @param timeout  how long to wait for the reply
     * @return the request: its correlation id and the future of its reply
     */
    public Request startRequest(String name, String host, String pass, String topic, Serializable object, String function, Duration timeout) {
        Outgoing out = prepare(FrameKind.MESSAGE, name, host, pass, topic, object, function);
        UUID id = out.correlationId;
        CompletableFuture<Message> reply = replies.await(out.sent.host(), r -> r.message().correlationId().equals(id));
        try {
            transmit(out);
        } catch (RuntimeException e) {
            replies.cancel(reply);
            throw e;
        }
        return new Request(id, withTimeout(reply, timeout, () -> "no reply to " + id + " on topic '" + topic + "' from " + host + " within " + timeout));
    }

    @Override
    public Message waitForReply(String topic, String host) {
        return waitForReply(topic, host, settings.replyTimeout());
    }

    @Override
    public Message waitForReply(String topic, String host, Duration timeout) {
        String h = links.key(links.parse(host));
        refuseWaitOnDeliveryThread(h);
        return await(h, replies.await(h, r -> r.host().equals(h) && r.message().topic().equals(topic)), timeout,
                () -> "no reply on topic '" + topic + "' from " + h + " within " + timeout
                        + "; check that the receiver runs, listens to the topic and replies");
    }

    @Override
    public Message waitForReply(UUID correlationId, Duration timeout) {
        Sent sent = sentRequests.get(correlationId);
        if (sent == null) {
            throw new MessagingException("node '" + name + "' sent no request with correlation id " + correlationId + " (or forgot it: it keeps the last "
                    + REMEMBERED_REQUESTS + ")");
        }
        refuseWaitOnDeliveryThread(sent.host());
        return await(sent.host(), replies.await(sent.host(), r -> r.message().correlationId().equals(correlationId)), timeout,
                () -> "no reply to " + correlationId + " on topic '" + sent.topic() + "' from " + sent.host() + " within " + timeout);
    }

    @Override
    public void replyMessage(Message request, Serializable object, String function) {
        Origin origin = receivedRequests.get(request.correlationId());
        if (origin == null) {
            throw new MessagingException("node '" + name + "' cannot reply to " + request.correlationId() + " on topic '" + request.topic()
                    + "': no such request was received here by sendMessage (publications cannot be answered), or it is one of more than "
                    + REMEMBERED_REQUESTS + " since");
        }
        byte[] frame = frames.answer(FrameKind.REPLY, request.correlationId(), request.sender(), request.topic(), object, function, origin.key());
        send(origin.channel(), frame);
    }

    @Override
    public void publishMessage(String topic, Serializable object, String function, String password) {
        SecretKey key = keys.key(requireTopic(topic), password);
        if (topic != lastPublished) {
            remember(topic);
        }
        topics.checkIfRegistered(topic, key);
        Publication publication = frames.publication(topic, object, function, key);
        List<Channel> subscribers = remoteSubscribers.of(topic);
        int limit = settings.maxFrameSize();
        for (int i = 0; i < subscribers.size(); i++) {
            limit = Math.min(limit, subscribers.get(i).maxFrameBytes());
        }
        boolean viaBrokers = !brokers.isEmpty(); // iterating an empty concurrent set still walks its table
        if (viaBrokers) {
            for (Channel c : brokers) {
                limit = Math.min(limit, c.maxFrameBytes());
            }
        }
        if (joinedGroup) {
            limit = Math.min(limit, MessagingSettings.MAX_DATAGRAM);
        }
        long length = publication.length();
        if (length > limit) {
            throw new MessagingException("node '" + name + "': a publication of " + length + " bytes on '" + topic
                    + "' does not fit one datagram (limit " + limit + " bytes) for a UDP or multicast subscriber; nothing was sent");
        }
        for (int i = 0; i < subscribers.size(); i++) {
            Channel c = subscribers.get(i);
            try {
                c.sendPublication(publication);
                counters.out();
            } catch (IOException e) {
                LOG.warn("node '{}': closing {}, a subscriber of '{}': {}", name, c.peer(), topic, e.getMessage());
                remoteSubscribers.forget(c);
                c.close();
            }
        }
        for (Channel b : viaBrokers ? brokers : Set.<Channel>of()) {
            try {
                b.sendPublication(publication);
                counters.out();
            } catch (IOException e) {
                LOG.warn("node '{}': cannot publish on '{}' through {}: {}", name, topic, b.peer(), e.getMessage());
                brokers.remove(b);
            }
        }
        for (Endpoint e : broadcasters) {
            try {
                if (e.broadcast(publication.frame())) {
                    counters.out();
                }
            } catch (IOException ex) {
                throw new MessagingException("node '" + name + "' cannot publish on " + e.address() + ": " + ex.getMessage(), ex);
            }
        }
    }

    @Override
    public void subscribeMessage(String topic, String password) {
        LocalTopics.Topic t = topics.register(requireTopic(topic), keys.key(topic, password));
        t.subscribed = true;
        byte[] frame = frames.control(FrameKind.SUBSCRIBE, topic);
        for (Channel c : subscriptionTargets()) {
            trySend(c, frame);
        }
    }

    @Override
    public void addMessageListener(String topic, String password, MessageListener listener) {
        Objects.requireNonNull(listener, "listener");
        topics.listen(requireTopic(topic), keys.key(topic, password), listener);
    }

    /** Removes a listener; once a topic has no listener left (and is not subscribed to), the node forgets it: it is not announced, and messages to it are refused. */
    @Override
    public void removeMessageListener(String topic, MessageListener listener) {
        topics.unlisten(topic, listener);
    }

    /** Closes every link, endpoint, transport and thread. Idempotent. */
    @Override
    public void close() {
        if (closed) {
            return;
        }
        closed = true;
        housekeeping.shutdownNow();
        transports.values().forEach(t -> {
            try {
                t.close();
            } catch (RuntimeException e) {
                LOG.warn("node '{}': closing a transport: {}", name, e.toString());
            }
        });
        links.close();
        endpoints.clear();
        broadcasters = new Endpoint[0];
        // Accepted connections too: their reader threads must not go on serving a closed node.
        for (Channel c : List.copyOf(connections)) {
            try {
                c.close();
            } catch (RuntimeException e) {
                LOG.warn("node '{}': closing a connection: {}", name, e.toString());
            }
        }
        connections.clear();
        replayStore.close();
    }

    @Override
    public String toString() {
        return "MessagingNode[" + name + " at " + boundAddresses() + "]";
    }

    // ---- used by Inbound ----

    long id() {
        return id;
    }

    boolean answersTo(String receiver) {
        return receiver.isEmpty() || receiver.equals("*") || names.contains(receiver);
    }

    Set<String> names() {
        return Set.copyOf(names);
    }

    LocalTopics topics() {
        return topics;
    }

    RemoteSubscribers remoteSubscribers() {
        return remoteSubscribers;
    }

    Replies replies() {
        return replies;
    }

    BoundedMap<UUID, Sent> sentRequests() {
        return sentRequests;
    }

    BoundedMap<UUID, Origin> receivedRequests() {
        return receivedRequests;
    }

    /** A peer refused the connection to it (it serves its maximum): fails what waited on it, with its reason. */
    void refusedBy(Channel channel, String why) {
        LOG.warn("node '{}': {} refused the connection: {}", name, channel.peer(), why);
        for (String host : links.forget(channel)) {
            replies.linkClosed(host, "it refused the connection: " + why);
        }
        channel.close();
    }

    void sendError(Frame request, Channel to, String why) {
        trySend(to, frames.answer(FrameKind.ERROR, request.correlationId(), request.sender(), request.topic(), why, "error", null));
    }

    static long nowMicros() {
        return FrameFactory.nowMicros();
    }

    // ---- internals ----

    private record Outgoing(Link link, UUID correlationId, byte[] frame, Sent sent) {
    }

    private Outgoing prepare(FrameKind kind, String receiver, String host, String pass, String topic, Serializable object, String function) {
        Objects.requireNonNull(receiver, "name");
        Objects.requireNonNull(host, "host");
        SecretKey key = keys.key(requireTopic(topic), pass);
        topics.checkIfRegistered(topic, key);
        Address address = links.parse(host);
        Link link = links.link(address);
        FrameFactory.Made made = frames.message(kind, receiver, topic, object, function, key);
        return new Outgoing(link, frames.correlationId(made.number()), made.bytes(), new Sent(links.key(address), topic, key));
    }

    private void transmit(Outgoing out) {
        if (out.frame.length > out.link.maxFrameBytes()) {
            throw new MessagingException("node '" + name + "': a frame of " + out.frame.length + " bytes does not fit the link to "
                    + out.link.address() + " (limit " + out.link.maxFrameBytes() + " bytes, one datagram); send less, or use tcp:// or rmi://");
        }
        sentRequests.put(out.correlationId, out.sent);
        try {
            out.link.send(out.frame);
            counters.out();
        } catch (IOException e) {
            links.drop(out.link);
            replies.linkClosed(out.sent.host(), e.getMessage());
            throw new MessagingException("node '" + name + "' cannot send to " + out.link.address() + ": " + e.getMessage(), e);
        }
    }

    private void send(Channel channel, byte[] frame) {
        try {
            channel.send(frame);
            counters.out();
        } catch (IOException e) {
            channel.close();
            throw new MessagingException("node '" + name + "' cannot send to " + channel.peer() + ": " + e.getMessage(), e);
        }
    }

    private void trySend(Channel channel, byte[] frame) {
        try {
            channel.send(frame);
            counters.out();
        } catch (IOException e) {
            LOG.debug("node '{}': cannot send to {}: {}", name, channel.peer(), e.toString());
            channel.close();
        }
    }

    private List<Channel> subscriptionTargets() {
        List<Channel> targets = new ArrayList<>(connections);
        targets.addAll(links.datagramPeers());
        return targets;
    }

    /** A new datagram link gets the subscriptions at once (connections get them when they open); a broker gets publications. */
    private void linkOpened(Link link) {
        if (link.isBroker()) {
            brokers.add(link);
        }
        if (!link.isConnection() && !link.address().scheme().equals("multicast")) {
            topics.subscribed().forEach(topic -> trySend(link, frames.control(FrameKind.SUBSCRIBE, topic)));
        }
    }

    private Transport transport(String scheme) {
        return transports.computeIfAbsent(scheme, s -> {
            TransportProvider p = providers.get(s);
            if (p == null) {
                throw new MessagingException("no transport for '" + s + "' addresses; available: " + providers.keySet()
                        + " (add a TransportProvider to the class path for more)");
            }
            return p.create(context);
        });
    }

    private void refuseWaitOnDeliveryThread(String host) {
        Link l = links.find(host);
        if (l != null && l.deliversOn(Thread.currentThread())) {
            throw new IllegalStateException("node '" + name + "': waitForReply from " + host + " was called on the thread that delivers "
                    + host + "'s messages (inside a MessageListener), so the reply could never arrive; wait on another thread");
        }
    }

    private static String requireTopic(String topic) {
        if (topic == null || topic.isEmpty()) {
            throw new IllegalArgumentException("topic must not be empty");
        }
        return topic;
    }

    private CompletableFuture<Message> withTimeout(CompletableFuture<Message> reply, Duration timeout, java.util.function.Supplier<String> why) {
        CompletableFuture<Message> timed = new CompletableFuture<>();
        var timer = housekeeping.schedule(() -> {
            if (timed.completeExceptionally(new MessagingException(why.get()))) {
                replies.cancel(reply);
            }
        }, timeout.toNanos(), TimeUnit.NANOSECONDS);
        reply.whenComplete((m, e) -> {
            timer.cancel(false);
            if (e == null) {
                timed.complete(m);
            } else {
                timed.completeExceptionally(e);
            }
        });
        return timed;
    }

    /**
     * Waits for a reply from a host: with a reply spin, spinning for it first (the link's
     * receiving thread hands it over); without, receiving it on this thread while no other thread
     * receives from that link ({@link Link#receiveUntil}: one thread wake-up less per round trip).
     */
    private Message await(String host, CompletableFuture<Message> reply, Duration timeout, java.util.function.Supplier<String> why) {
        long start = System.nanoTime();
        long timeoutNanos = timeout.toNanos();
        long spinNanos = settings.replySpin().toNanos();
        if (spinNanos > 0) {
            long spinUntil = start + Math.min(spinNanos, timeoutNanos);
            while (!reply.isDone() && System.nanoTime() < spinUntil) {
                Thread.onSpinWait();
            }
        } else if (!reply.isDone()) {
            Link link = links.find(host);
            if (link != null) {
                link.receiveUntil(reply, start + timeoutNanos);
            }
        }
        try {
            return reply.get(Math.max(0, timeoutNanos - (System.nanoTime() - start)), TimeUnit.NANOSECONDS);
        } catch (TimeoutException e) {
            replies.cancel(reply);
            throw new MessagingException("node '" + name + "': " + why.get());
        } catch (InterruptedException e) {
            replies.cancel(reply);
            Thread.currentThread().interrupt();
            throw new MessagingException("node '" + name + "': interrupted while waiting for a reply", e);
        } catch (ExecutionException e) {
            if (e.getCause() instanceof MessagingException m) {
                throw new MessagingException(m.getMessage(), m);
            }
            throw new MessagingException("node '" + name + "': " + e.getCause(), e.getCause());
        }
    }

    /**
     * Sends a keep-alive on every connection silent for a third of the idle timeout (run twice
     * as often as that), so the peer's idle timeout never cuts a quiet healthy link.
     */
    private void keepAlive() {
        long now = System.nanoTime();
        long silent = settings.limits().keepAliveInterval().toNanos();
        byte[] frame = null;
        for (Channel c : connections) {
            if (frame == null) {
                frame = frames.control(FrameKind.KEEPALIVE, "");
            }
            c.keepAlive(frame, now, silent);
        }
    }

    private void keepHouse() {
        long now = System.nanoTime();
        long limit = settings.sendTimeout().toNanos();
        for (Channel c : connections) {
            if (c.stuck(now, limit)) {
                LOG.warn("node '{}': closing {}: it has not read for {}", name, c.peer(), settings.sendTimeout());
                c.close();
            }
        }
        for (Address peer : peers) {
            if (links.find(links.key(peer)) == null) {
                try {
                    links.link(peer);
                    LOG.info("node '{}': connected to {}", name, peer);
                } catch (MessagingException e) {
                    LOG.debug("node '{}': still cannot reach {}: {}", name, peer, e.getMessage());
                }
            }
        }
        List<String> subscribed = topics.subscribed();
        for (Link l : links.datagramPeers()) {
            subscribed.forEach(topic -> trySend(l, frames.control(FrameKind.SUBSCRIBE, topic)));
        }
        remoteSubscribers.expire(now, 5 * settings.subscriptionRefresh().toNanos());
    }

    /** The node as its transports see it. */
    private final class Context implements TransportContext {

        @Override
        public String nodeName() {
            return name;
        }

        @Override
        public MessagingSettings settings() {
            return settings;
        }

        @Override
        public Presence presence() {
            return presence;
        }

        @Override
        public Set<String> receiverNames() {
            return Set.copyOf(names);
        }

        @Override
        public void onFrame(byte[] buf, int offset, int length, Channel from) {
            inbound.onFrame(buf, offset, length, null, from);
        }

        @Override
        public void onFrame(byte[] buf, int offset, int length, byte[] payload, Channel from) {
            inbound.onFrame(buf, offset, length, payload, from);
        }

        @Override
        public void dropped(DropReason reason, String where, String detail) {
            counters.drop(reason, where, detail);
        }

        @Override
        public void opened(Channel channel) {
            connections.add(channel);
            if (!channel.isOpen()) {
                // it closed before it was added: closed() found nothing to forget
                connections.remove(channel);
                return;
            }
            // The peer closes a connection that delivers no whole frame within its first-frame
            // timeout; a link with nothing else to say yet says this.
            channel.keepAlive(frames.control(FrameKind.KEEPALIVE, ""), System.nanoTime(), 0);
            for (String topic : topics.subscribed()) {
                trySend(channel, frames.control(FrameKind.SUBSCRIBE, topic));
            }
        }

        @Override
        public byte[] refusal(String why) {
            return frames.answer(FrameKind.ERROR, REFUSAL, "", "", why, "refused", null);
        }

        @Override
        public void closed(Channel channel) {
            connections.remove(channel);
            brokers.remove(channel);
            remoteSubscribers.forget(channel);
            for (String host : links.forget(channel)) {
                replies.linkClosed(host, "connection closed");
            }
        }

        @Override
        public FailurePolicy failures() {
            return failures;
        }

        @Override
        public ThreadFactory threads(String role) {
            // Its loop handles what it can; whatever gets here ends the thread, reported as its death.
            return r -> OwnerThreads.thread("mw-msg-" + name + "-" + role + "-" + threadNumbers.incrementAndGet(), r, failures);
        }
    }
}
