package io.robomw.agents.messaging.mqtt;

import com.hivemq.client.mqtt.MqttClient;
import com.hivemq.client.mqtt.MqttClientSslConfig;
import com.hivemq.client.mqtt.MqttGlobalPublishFilter;
import com.hivemq.client.mqtt.datatypes.MqttQos;
import com.hivemq.client.mqtt.lifecycle.MqttClientDisconnectedContext;
import com.hivemq.client.mqtt.lifecycle.MqttDisconnectSource;
import com.hivemq.client.mqtt.mqtt5.Mqtt5AsyncClient;
import com.hivemq.client.mqtt.mqtt5.Mqtt5ClientBuilder;
import com.hivemq.client.mqtt.mqtt5.datatypes.Mqtt5UserProperties;
import com.hivemq.client.mqtt.mqtt5.datatypes.Mqtt5UserProperty;
import com.hivemq.client.mqtt.mqtt5.message.connect.connack.Mqtt5ConnAck;
import com.hivemq.client.mqtt.mqtt5.message.publish.Mqtt5Publish;
import com.hivemq.client.mqtt.mqtt5.message.publish.Mqtt5PublishResult;
import com.hivemq.client.mqtt.mqtt5.message.subscribe.suback.Mqtt5SubAck;
import com.hivemq.client.mqtt.mqtt5.message.subscribe.suback.Mqtt5SubAckReasonCode;
import io.robomw.agents.messaging.Address;
import io.robomw.agents.messaging.DropReason;
import io.robomw.agents.messaging.PresenceRecord;
import io.robomw.agents.messaging.frame.FrameException;
import io.robomw.agents.messaging.frame.FrameKind;
import io.robomw.agents.messaging.spi.Channel;
import io.robomw.agents.messaging.spi.Endpoint;
import io.robomw.agents.messaging.spi.Link;
import io.robomw.agents.messaging.spi.Publication;
import io.robomw.agents.messaging.spi.TransportContext;
import io.robomw.api.MessagingException;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.io.IOException;
import java.nio.ByteBuffer;
import java.time.Duration;
import java.time.Instant;
import java.util.List;
import java.util.Map;
import java.util.Set;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.ConcurrentHashMap;
import java.util.concurrent.ExecutionException;
import java.util.concurrent.ExecutorService;
import java.util.concurrent.LinkedBlockingQueue;
import java.util.concurrent.ThreadPoolExecutor;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.TimeoutException;
import java.util.concurrent.atomic.AtomicLong;
import java.util.concurrent.locks.Condition;
import java.util.concurrent.locks.ReentrantLock;

/**
 * One node's MQTT 5 connection to one broker (HiveMQ MQTT client): the node's link there and its
 * endpoint there at once. Frames travel whole as MQTT payloads, so passwords stay end-to-end: the
 * HMAC is inside the payload, the broker never sees a key.
 *
 * <p>What each frame the node hands it becomes ({@link MqttTopics} has the topics):
 * <ul>
 * <li>a publication: a PUBLISH on {@code PREFIX/pub/TOPIC}; one without a password whose payload
 *     is at least {@value Publication#APART_FROM_BYTES} bytes travels apart from its frame: the
 *     PUBLISH's payload is the publication's payload itself (a plain MQTT client reads a scan's
 *     bytes as they are), and its frame without the payload, a {@code PUBLISH_SHARED} head, is the
 *     user property {@value ApartHead#PROPERTY}, in base64 ({@link Publication});</li>
 * <li>a request: a PUBLISH on {@code PREFIX/msg/RECEIVER} with this client's reply topic as the
 *     MQTT 5 response topic and the correlation id as correlation data; the receiver's reply goes
 *     back there ({@link ReplyRoute});</li>
 * <li>a subscription: an MQTT SUBSCRIBE to {@code PREFIX/pub/TOPIC}, with No Local (a node never
 *     gets its own publications back).</li>
 * </ul>
 * At start it subscribes to its reply topic and to {@code PREFIX/msg/NAME} for every name the node
 * answers to, publishes the node's presence (retained) and leaves the offline presence as its will.
 *
 * <p>Everything is sent with the address's QoS (1 by default: at least once; the node's replay
 * guard drops duplicates of authenticated frames). Received messages are handed to the node on
 * one named delivery thread, in the order the broker sent them, and acknowledged after the
 * node's listeners ran (so the broker's flow control holds back a slow node).
 *
 * <p><b>Losing the broker.</b> Once connected, a lost connection is logged and retried with
 * growing pauses (0.1 s to 5 s) until the node closes; subscriptions are made again if the broker
 * lost the session, and messages not yet acknowledged are sent again. Up to {@code max-queued}
 * messages, of {@code max-queued-bytes} together, wait meanwhile; beyond that a send fails at once
 * with a {@link MessagingException} saying since when the broker is unreachable. (The bytes bound
 * is what holds for sensor-sized messages: ten thousand camera frames would not fit in a heap.)
 *
 * <p><b>Back-pressure while connected.</b> At most {@code max-in-flight} messages (64 by default)
 * are handed to the client and not yet acknowledged; a send beyond them, or beyond the queue's
 * bounds, waits up to the send timeout for the broker's acknowledgements, then fails naming the
 * bounds. A sender faster than the broker is held there rather than piling messages up inside the
 * client, where hundreds of 100 KB scans cost a fifth of the throughput (issue 36). If the broker
 * is lost while a send waits, the send joins the queue of what waits for its return (or is
 * refused if that is full); if the session closes, it fails.
 *
 * <p>Thread-safe.
 */
final class BrokerSession implements Link, Endpoint {

    private static final Logger LOG = LoggerFactory.getLogger(BrokerSession.class);
    private static final long MAX_RECONNECT_DELAY_MS = 5_000;
    /** Bytes an MQTT PUBLISH adds to a frame (fixed header, topic, properties), kept free below the broker's packet limit. */
    private static final int PUBLISH_OVERHEAD = 1024;
    /** The longest head sent apart (its base64 fits {@link #PUBLISH_OVERHEAD} with the topic); a longer one's publication travels whole. */
    private static final int MAX_APART_HEAD = 384;

    private final MqttOptions options;
    private final Address address;
    private final TransportContext context;
    private final MqttTopics topics;
    private final MqttQos qos;
    private final Mqtt5AsyncClient client;
    private final ExecutorService delivery;
    private final java.util.concurrent.atomic.AtomicReference<Thread> deliveryThread = new java.util.concurrent.atomic.AtomicReference<>();
    /** Guards {@link #queuedMessages} and {@link #queuedBytes}; {@link #room} is signalled as messages leave the queue. */
    private final ReentrantLock queueLock = new ReentrantLock();
    private final Condition room = queueLock.newCondition();
    /** Messages waiting for the broker (in flight or while it is away), at most {@code max-queued}, and while connected {@code max-in-flight}. */
    private int queuedMessages;
    /** Their bytes together, at most {@code max-queued-bytes} (but for one larger message, which waits alone). */
    private long queuedBytes;
    private final Set<String> subscribed = ConcurrentHashMap.newKeySet();
    private final Map<String, Boolean> requestSubscriptions = new ConcurrentHashMap<>();
    private final Map<String, com.hivemq.client.mqtt.datatypes.MqttTopic> topicCache = new ConcurrentHashMap<>();
    private final AtomicLong failedSends = new AtomicLong();
    /** Where the payloads of publications that travel apart are copied for the client (at most 16 MiB of them kept unused). */
    private final PayloadBuffers buffers;
    private final Runnable presenceListener = this::announce;
    private final String replyTopic;
    /** When this session was made, the time of its will: every presence it announces carries it ({@link PresenceRecord#since()}). */
    private final Instant since = Instant.now();
    private volatile boolean established;
    private volatile boolean connected;
    private volatile boolean closed;
    private volatile Instant lostSince;
    private volatile int maxFrameBytes;

    BrokerSession(MqttOptions options, Address address, TransportContext context, BrokerCredentials credentials, MqttClientSslConfig ssl) {
        this.options = options;
        this.address = address;
        this.context = context;
        this.topics = options.topics();
        this.qos = options.qos() == 0 ? MqttQos.AT_MOST_ONCE : MqttQos.AT_LEAST_ONCE;
        this.replyTopic = topics.replies(options.clientId());
        this.maxFrameBytes = context.settings().maxFrameSize();
        this.buffers = new PayloadBuffers(Math.min(options.maxQueuedBytes(), 16L << 20));
        java.util.concurrent.ThreadFactory threads = context.threads("mqtt-in-" + options.host() + ":" + options.port());
        // One thread, in order; after close, what the client still hands over (the end of its flows) is dropped.
        this.delivery = new ThreadPoolExecutor(1, 1, 0, TimeUnit.MILLISECONDS, new LinkedBlockingQueue<>(), r -> {
            Thread t = threads.newThread(r);
            deliveryThread.set(t);
            return t;
        }, new ThreadPoolExecutor.DiscardPolicy());
        int connectMillis = (int) Math.min(Integer.MAX_VALUE, context.settings().connectTimeout().toMillis());
        // Server, TLS and timeouts in one transport configuration: set one by one, a later setter of the
        // client builder replaces the transport configuration made by an earlier one.
        Mqtt5ClientBuilder b = MqttClient.builder().useMqttVersion5()
                .identifier(options.clientId())
                .transportConfig().serverHost(options.host()).serverPort(options.port()).sslConfig(ssl)
                .socketConnectTimeout(connectMillis, TimeUnit.MILLISECONDS)
                .mqttConnectTimeout(connectMillis, TimeUnit.MILLISECONDS).applyTransportConfig()
                .addDisconnectedListener(this::onDisconnected)
                .addConnectedListener(c -> onConnected());
        if (credentials.username() != null) {
            var auth = b.simpleAuth().username(credentials.username());
            b = credentials.password() == null ? auth.applySimpleAuth() : auth.password(credentials.password()).applySimpleAuth();
        }
        PresenceRecord offline = context.presence().now(options.clientId(), options.sessionExpirySeconds(), address.toString(), since).offline(since);
        b = b.willPublish().topic(topics.presence(options.clientId())).qos(MqttQos.AT_LEAST_ONCE).retain(true)
                .payload(context.presence().encode(offline)).applyWillPublish();
        this.client = b.buildAsync();
        client.publishes(MqttGlobalPublishFilter.ALL, this::onPublish, delivery, true);
    }

    /**
     * Connects within the connect timeout, then subscribes and announces.
     *
     * @throws IOException if the broker cannot be reached or refuses the client
     */
    void start() throws IOException {
        long timeout = context.settings().connectTimeout().toMillis() + 1_000;
        Mqtt5ConnAck ack;
        try {
            ack = client.connectWith()
                    .cleanStart(options.sessionExpirySeconds() == 0)
                    .sessionExpiryInterval(options.sessionExpirySeconds())
                    .keepAlive(options.keepAliveSeconds())
                    // Receive maximum stays at MQTT's 65,535: Mosquitto 2.0.11 sends more unacknowledged messages than a
                    // lower one allows, which the client must treat as a protocol error (it disconnects).
                    .restrictions().maximumPacketSize(context.settings().maxFrameSize() + PUBLISH_OVERHEAD).applyRestrictions()
                    .send().get(timeout, TimeUnit.MILLISECONDS);
        } catch (ExecutionException e) {
            shutDownDelivery();
            throw new IOException("broker " + address.endpoint() + " refused or could not be reached: " + rootMessage(e.getCause()), e.getCause());
        } catch (TimeoutException e) {
            client.disconnect();
            shutDownDelivery();
            throw new IOException("broker " + address.endpoint() + " did not accept the connection within " + timeout + " ms");
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
            shutDownDelivery();
            throw new IOException("interrupted while connecting to " + address.endpoint(), e);
        }
        established = true;
        connected = true;
        int brokerLimit = ack.getRestrictions().getMaximumPacketSize();
        maxFrameBytes = Math.min(context.settings().maxFrameSize(), brokerLimit - PUBLISH_OVERHEAD);
        LOG.info("node '{}' connected to broker {} as '{}' ({} session{})", context.nodeName(), address.endpoint(), options.clientId(),
                options.sessionExpirySeconds() == 0 ? "clean" : "persistent", ack.isSessionPresent() ? ", resumed" : "");
        subscribeOrThrow(replyTopic);
        for (String name : context.receiverNames()) {
            answerToOrThrow(name);
        }
        context.presence().onChange(presenceListener);
        announce();
        context.opened(this);
    }

    /** Subscribes to the messages for another receiver name; returns once the broker confirmed it (or logged why not). */
    void answerTo(String name) {
        if (name.isEmpty() || name.equals("*") || requestSubscriptions.putIfAbsent(name, Boolean.TRUE) != null) {
            return;
        }
        subscribe(topics.request(name));
    }

    private void answerToOrThrow(String name) throws IOException {
        if (!name.isEmpty() && !name.equals("*") && requestSubscriptions.putIfAbsent(name, Boolean.TRUE) == null) {
            subscribeOrThrow(topics.request(name));
        }
    }

    /** @return the client identifier */
    String clientId() {
        return options.clientId();
    }

    // ---- Channel, Link, Endpoint ----

    @Override
    public String peer() {
        return address.toString();
    }

    @Override
    public Address address() {
        return address;
    }

    @Override
    public void send(byte[] frame) throws IOException {
        FrameKind kind = FramePeek.kind(frame);
        if (kind == null) {
            throw new IllegalArgumentException("not a frame of a known kind");
        }
        switch (kind) {
            case PUBLISH -> publish(topic(topics.publication(FramePeek.topic(frame))), frame, null, null);
            case MESSAGE -> {
                String receiver = FramePeek.receiver(frame);
                if (receiver.isEmpty() || receiver.equals("*")) {
                    throw new MessagingException("node '" + context.nodeName() + "': a message through broker " + address
                            + " needs the receiver's name (several nodes share a broker, so '" + receiver + "' names none)");
                }
                publish(topic(topics.request(receiver)), frame, replyTopic, FramePeek.correlation(frame));
            }
            case SUBSCRIBE -> {
                String t = topics.publication(FramePeek.topic(frame));
                if (subscribed.add(t)) {
                    subscribe(t);
                }
            }
            case UNSUBSCRIBE -> {
                String t = topics.publication(FramePeek.topic(frame));
                if (subscribed.remove(t)) {
                    client.unsubscribeWith().topicFilter(t).send();
                }
            }
            case REPLY, ERROR -> LOG.debug("node '{}': an answer with no request to answer through {} was not sent", context.nodeName(), address);
            default -> throw new IllegalStateException("unhandled kind " + kind);
        }
    }

    @Override
    public void sendPublication(Publication publication) throws IOException {
        byte[] head = publication.travelsApart() ? publication.head() : null;
        if (head == null || head.length > MAX_APART_HEAD) {
            send(publication.frame());
            return;
        }
        Mqtt5UserProperties apart = Mqtt5UserProperties.of(Mqtt5UserProperty.of(ApartHead.PROPERTY, ApartHead.encode(head)));
        // The client keeps the payload until the broker acknowledged it (and sends it again after a reconnection), long
        // after publishMessage returned and its caller may refill the array (a camera's buffer): it gets a copy of its own,
        // in a direct buffer, which it sends as it is (a heap payload it would copy once more into one of its own).
        publish(topic(topics.publication(FramePeek.topic(head))), publication.payload(), null, null, null, apart, true);
    }

    @Override
    public int maxFrameBytes() {
        return maxFrameBytes;
    }

    @Override
    public boolean isOpen() {
        return !closed;
    }

    @Override
    public boolean isConnection() {
        return true;
    }

    @Override
    public boolean isBroker() {
        return true;
    }

    @Override
    public boolean deliversOn(Thread thread) {
        return thread == deliveryThread.get();
    }

    @Override
    public boolean broadcast(byte[] frame) {
        return false; // publications reach the broker through send(), once (the node lists this session among its brokers)
    }

    /** Announces the node as offline, disconnects, and ends the delivery thread. Idempotent. */
    @Override
    public void close() {
        if (closed) {
            return;
        }
        closed = true;
        roomChanged();
        context.presence().removeListener(presenceListener);
        try {
            if (connected) {
                PresenceRecord offline = context.presence().now(options.clientId(), options.sessionExpirySeconds(), address.toString(), since).offline(Instant.now());
                client.publishWith().topic(topics.presence(options.clientId())).qos(MqttQos.AT_LEAST_ONCE).retain(true)
                        .payload(context.presence().encode(offline)).send().get(1, TimeUnit.SECONDS);
            }
        } catch (Exception e) {
            LOG.debug("node '{}': offline presence not sent to {}: {}", context.nodeName(), address, e.toString());
        }
        try {
            client.disconnect().get(2, TimeUnit.SECONDS);
        } catch (Exception e) {
            LOG.debug("node '{}': disconnecting from {}: {}", context.nodeName(), address, e.toString());
        }
        shutDownDelivery();
        context.closed(this);
    }

    @Override
    public String toString() {
        return "BrokerSession[" + options.clientId() + " at " + address + "]";
    }

    // ---- sending ----

    /**
     * Sends one PUBLISH, holding a queue place until the broker acknowledged it (QoS 1) or it was
     * written (QoS 0).
     */
    void publish(com.hivemq.client.mqtt.datatypes.MqttTopic topic, byte[] payload, String responseTopic, byte[] correlation) throws IOException {
        publish(topic, payload, responseTopic, correlation, null);
    }

    /** {@link #publish(com.hivemq.client.mqtt.datatypes.MqttTopic, byte[], String, byte[])}, for a reply: its correlation data. */
    void publish(com.hivemq.client.mqtt.datatypes.MqttTopic topic, byte[] payload, String responseTopic, byte[] correlation,
                 byte[] replyCorrelation) throws IOException {
        publish(topic, payload, responseTopic, correlation, replyCorrelation, null, false);
    }

    /**
     * @param copied whether the client gets a copy of the payload ({@link #buffers}), so that the caller may change it
     *               once this returned; else the array itself, which nobody may change
     */
    private void publish(com.hivemq.client.mqtt.datatypes.MqttTopic topic, byte[] payload, String responseTopic, byte[] correlation,
                         byte[] replyCorrelation, Mqtt5UserProperties properties, boolean copied) throws IOException {
        if (closed) {
            throw new IOException("the session with broker " + address + " is closed");
        }
        int bytes = payload.length;
        acquireQueuePlace(bytes);
        // copied only once it has a place in the queue (what waits for one holds no buffer); a pooled buffer only at QoS 1,
        // where the client is done with it once the broker acknowledged it (at QoS 0 it reports a message sent, not written)
        ByteBuffer buffer = copied && qos == MqttQos.AT_LEAST_ONCE ? buffers.copyOf(payload) : null;
        var builder = Mqtt5Publish.builder().topic(topic).qos(qos);
        if (buffer != null) {
            builder.payload(buffer);
        } else {
            builder.payload(copied ? payload.clone() : payload);
        }
        if (properties != null) {
            builder.userProperties(properties);
        }
        Mqtt5Publish p;
        if (responseTopic != null) {
            p = builder.responseTopic(responseTopic).correlationData(correlation).build();
        } else if (replyCorrelation != null) {
            p = builder.correlationData(replyCorrelation).build();
        } else {
            p = builder.build();
        }
        CompletableFuture<Mqtt5PublishResult> sent;
        try {
            sent = client.publish(p);
        } catch (RuntimeException e) {
            releaseQueuePlace(bytes);
            if (buffer != null) {
                buffers.release(buffer);
            }
            throw new IOException("broker " + address + ": " + e.getMessage(), e);
        }
        sent.whenComplete((result, failure) -> {
            // acknowledged (or given up): the client no longer reads the payload
            if (buffer != null) {
                buffers.release(buffer);
            }
            releaseQueuePlace(bytes);
            Throwable error = failure != null ? failure : result.getError().orElse(null);
            if (error != null) {
                long n = failedSends.incrementAndGet();
                if (n == 1 || Long.bitCount(n) == 1) {
                    LOG.warn("node '{}': a message on {} was not taken by broker {}: {} ({} so far)", context.nodeName(), topic, address,
                            rootMessage(error), n);
                }
            }
        });
    }

    /**
     * @return whether a message of this many bytes may join the queue now: within {@code max-queued}, within
     *         {@code max-in-flight} while connected, and within {@code max-queued-bytes} (one larger: when the queue is
     *         empty); under the lock
     */
    private boolean fits(int bytes) {
        int most = connected ? Math.min(options.maxQueued(), options.maxInFlight()) : options.maxQueued();
        return queuedMessages == 0 || (queuedMessages < most && queuedBytes + bytes <= options.maxQueuedBytes());
    }

    /** Wakes the senders waiting for room: the connection came or went, or the session closed, and what fits changed with it. */
    private void roomChanged() {
        queueLock.lock();
        try {
            room.signalAll();
        } finally {
            queueLock.unlock();
        }
    }

    private void releaseQueuePlace(int bytes) {
        queueLock.lock();
        try {
            queuedMessages--;
            queuedBytes -= bytes;
            room.signalAll();
        } finally {
            queueLock.unlock();
        }
    }

    /**
     * Takes a place in the queue to the broker for a message of this many bytes: one of
     * {@code max-queued} (of {@code max-in-flight} while connected), and its bytes of
     * {@code max-queued-bytes}. While the broker is unreachable a full queue refuses at once;
     * while connected a send waits up to the send timeout for room, and if the broker is lost
     * meanwhile, the away rule holds from then on.
     */
    private void acquireQueuePlace(int bytes) throws IOException {
        queueLock.lock();
        try {
            Duration limit = context.settings().sendTimeout();
            long left = limit.toNanos();
            while (!fits(bytes)) {
                Instant lost = lostSince;
                if (closed) {
                    throw new IOException("the session with broker " + address + " closed while a message waited for room; it was not sent");
                }
                if (!connected && lost != null) {
                    throw new MessagingException("node '" + context.nodeName() + "': broker " + address + " is unreachable since " + lost
                            + " and the messages waiting for it fill the queue (" + queueLimits() + "); this one was not sent");
                }
                if (left <= 0) {
                    throw new MessagingException("node '" + context.nodeName() + "': broker " + address + " acknowledged none of the "
                            + queuedMessages + " messages waiting for it (" + queueLimits() + ") within " + limit + "; this one was not sent");
                }
                left = room.awaitNanos(left);
            }
            queuedMessages++;
            queuedBytes += bytes;
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
            throw new IOException("interrupted while waiting for room in the queue to " + address, e);
        } finally {
            queueLock.unlock();
        }
    }

    /** @return the queue's bounds, as a message names them */
    private String queueLimits() {
        return "max-in-flight " + options.maxInFlight() + " while connected, max-queued " + options.maxQueued() + " messages, max-queued-bytes "
                + options.maxQueuedBytes();
    }

    com.hivemq.client.mqtt.datatypes.MqttTopic topic(String name) {
        com.hivemq.client.mqtt.datatypes.MqttTopic t = topicCache.get(name);
        if (t == null) {
            t = com.hivemq.client.mqtt.datatypes.MqttTopic.of(name);
            if (topicCache.size() > 4096) {
                topicCache.clear();
            }
            topicCache.put(name, t);
        }
        return t;
    }

    /**
     * Subscribes and waits for the broker's confirmation (at most the connect timeout), so that
     * what is published after {@code subscribeMessage} returned reaches this node. While the
     * broker is away the subscription is queued and made when it is back.
     */
    private void subscribe(String filter) {
        CompletableFuture<Mqtt5SubAck> done = client.subscribeWith().topicFilter(filter).qos(qos).noLocal(true).send();
        if (!connected) {
            done.whenComplete((ack, e) -> {
                if (e != null) {
                    LOG.warn("node '{}': broker {} did not take the subscription to {}: {}", context.nodeName(), address, filter, rootMessage(e));
                } else {
                    checkSubAck(filter, ack);
                }
            });
            return;
        }
        try {
            checkSubAck(filter, done.get(context.settings().connectTimeout().toMillis(), TimeUnit.MILLISECONDS));
        } catch (ExecutionException | TimeoutException e) {
            LOG.warn("node '{}': broker {} did not confirm the subscription to {}: {}", context.nodeName(), address, filter, rootMessage(e));
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
        }
    }

    private void subscribeOrThrow(String filter) throws IOException {
        try {
            Mqtt5SubAck ack = client.subscribeWith().topicFilter(filter).qos(qos).noLocal(true).send()
                    .get(context.settings().connectTimeout().toMillis(), TimeUnit.MILLISECONDS);
            if (!checkSubAck(filter, ack)) {
                throw new IOException("broker " + address + " refused the subscription to " + filter + ": " + ack.getReasonCodes());
            }
        } catch (ExecutionException | TimeoutException e) {
            throw new IOException("broker " + address + " did not take the subscription to " + filter + ": " + rootMessage(e), e);
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
            throw new IOException("interrupted while subscribing at " + address, e);
        }
    }

    private boolean checkSubAck(String filter, Mqtt5SubAck ack) {
        for (Mqtt5SubAckReasonCode code : ack.getReasonCodes()) {
            if (code.isError()) {
                LOG.warn("node '{}': broker {} refused the subscription to {}: {}{}", context.nodeName(), address, filter, code,
                        ack.getReasonString().map(r -> " (" + r + ")").orElse(""));
                return false;
            }
        }
        return true;
    }

    private void announce() {
        if (closed || !established) {
            return;
        }
        try {
            PresenceRecord now = context.presence().now(options.clientId(), options.sessionExpirySeconds(), address.toString(), since);
            client.publishWith().topic(topics.presence(options.clientId())).qos(MqttQos.AT_LEAST_ONCE).retain(true)
                    .payload(context.presence().encode(now)).send();
        } catch (RuntimeException e) {
            LOG.warn("node '{}': cannot announce its presence at {}: {}", context.nodeName(), address, e.toString());
        }
    }

    // ---- receiving ----

    private void onPublish(Mqtt5Publish p) {
        try {
            // read in place, not copied: the node reads a frame only during onFrame and never writes it
            ReceivedPayload bytes = ReceivedPayload.of(p);
            String t = p.getTopic().toString();
            Channel from = this;
            if (t.startsWith(topics.requestPrefix())) {
                from = new ReplyRoute(this, p.getResponseTopic().map(Object::toString).orElse(null),
                        p.getCorrelationData().map(b -> { byte[] c = new byte[b.remaining()]; b.duplicate().get(c); return c; }).orElse(null));
            }
            byte[] head = apartHead(p, t);
            if (head != null) {
                // a publication whose payload travelled apart: the node takes it as the PUBLISH its head stands for
                context.onFrame(head, 0, head.length, bytes.owned(), from);
            } else if (FramePeek.isFrame(bytes.array(), bytes.offset(), bytes.length())) {
                context.onFrame(bytes.array(), bytes.offset(), bytes.length(), from);
            } else if (t.startsWith(topics.publicationPrefix())) {
                byte[] frame = ForeignPublication.frame(topics.topicOfPublication(t), bytes.copy(), p);
                context.onFrame(frame, 0, frame.length, from);
            } else {
                context.dropped(DropReason.MALFORMED, address + " topic " + t, "a " + bytes.length() + "-byte message that is not a RoboMW frame");
            }
        } catch (FrameException e) {
            context.dropped(e.reason(), address + " topic " + p.getTopic(), e.getMessage());
        } catch (Throwable e) {
            context.failures().surviveOrRethrow(Thread.currentThread().getName(), e);
            LOG.warn("node '{}': a message from broker {} on {} could not be handled: {}", context.nodeName(), address, p.getTopic(), e.toString());
        } finally {
            if (p.getQos() != MqttQos.AT_MOST_ONCE) {
                p.acknowledge();
            }
        }
    }

    /**
     * @return the head of a publication whose payload travelled apart ({@value ApartHead#PROPERTY}), decoded, or
     *         {@code null} if the PUBLISH has none
     * @throws FrameException if the property is not base64, or is on a topic that is not a publication's
     */
    private byte[] apartHead(Mqtt5Publish p, String topic) throws FrameException {
        List<? extends Mqtt5UserProperty> properties = p.getUserProperties().asList();
        for (int i = 0; i < properties.size(); i++) {
            Mqtt5UserProperty property = properties.get(i);
            if (property.getName().toString().equals(ApartHead.PROPERTY)) {
                if (!topic.startsWith(topics.publicationPrefix())) {
                    throw new FrameException(DropReason.MALFORMED, "a payload apart from its frame on topic " + topic + ", which is not a publication's");
                }
                return ApartHead.decode(property.getValue().toString());
            }
        }
        return null;
    }

    private void onConnected() {
        boolean wasLost = lostSince != null;
        connected = true;
        if (wasLost) {
            LOG.info("node '{}': broker {} is back (away since {})", context.nodeName(), address, lostSince);
            lostSince = null;
            announce();
        }
        roomChanged();
    }

    private void onDisconnected(MqttClientDisconnectedContext c) {
        connected = false;
        if (closed || !established || c.getSource() == MqttDisconnectSource.USER) {
            return;
        }
        int attempt = c.getReconnector().getAttempts();
        if (lostSince == null) {
            lostSince = Instant.now();
            LOG.warn("node '{}': lost broker {} ({}: {}); reconnecting, messages wait meanwhile ({})", context.nodeName(), address,
                    c.getSource(), rootMessage(c.getCause()), queueLimits());
        } else {
            LOG.debug("node '{}': broker {} still unreachable after {} attempts: {}", context.nodeName(), address, attempt, rootMessage(c.getCause()));
        }
        roomChanged();
        long delay = Math.min(MAX_RECONNECT_DELAY_MS, 100L << Math.min(attempt, 6));
        c.getReconnector().reconnect(true).resubscribeIfSessionExpired(true).republishIfSessionExpired(true)
                .delay(delay, TimeUnit.MILLISECONDS);
    }

    private void shutDownDelivery() {
        delivery.shutdown();
        try {
            if (!delivery.awaitTermination(2, TimeUnit.SECONDS)) {
                delivery.shutdownNow();
            }
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
            delivery.shutdownNow();
        }
    }

    static String rootMessage(Throwable t) {
        Throwable root = t;
        while (root.getCause() != null && root.getCause() != root) {
            root = root.getCause();
        }
        String m = root.getMessage();
        return root.getClass().getSimpleName() + (m == null ? "" : ": " + m);
    }
}
