package io.robomw.agents.messaging.mqtt;

import com.hivemq.client.mqtt.MqttClient;
import com.hivemq.client.mqtt.MqttGlobalPublishFilter;
import com.hivemq.client.mqtt.datatypes.MqttQos;
import com.hivemq.client.mqtt.mqtt5.Mqtt5AsyncClient;
import com.hivemq.client.mqtt.mqtt5.Mqtt5ClientBuilder;
import com.hivemq.client.mqtt.mqtt5.message.publish.Mqtt5Publish;
import io.robomw.agents.messaging.Address;
import io.robomw.agents.messaging.PresenceRecord;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.io.IOException;
import java.security.SecureRandom;
import java.time.Duration;
import java.util.ArrayList;
import java.util.Comparator;
import java.util.HexFormat;
import java.util.List;
import java.util.Map;
import java.util.concurrent.ConcurrentHashMap;
import java.util.concurrent.ExecutionException;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.TimeoutException;

/**
 * The nodes, agent hosts and robots announced at a broker: every retained presence under the
 * address's prefix ({@link MqttTopics#everyPresence()}), kept up to date while it is open. A
 * presence that cannot be read is logged and left out. Thread-safe; close it to disconnect.
 *
 * <pre>{@code
 * for (PresenceRecord p : BrokerDirectory.read("mqtt://127.0.0.1:1883", Duration.ofSeconds(3))) {
 *     System.out.println(p.node() + (p.online() ? " online" : " offline") + " " + p.agents());
 * }
 * }</pre>
 */
public final class BrokerDirectory implements AutoCloseable {

    private static final Logger LOG = LoggerFactory.getLogger(BrokerDirectory.class);
    /** A burst of retained presences is over when none came for this long. */
    private static final long QUIET_NANOS = Duration.ofMillis(300).toNanos();

    private final Address address;
    private final MqttTopics topics;
    private final Mqtt5AsyncClient client;
    private final Map<String, PresenceRecord> byClient = new ConcurrentHashMap<>();
    private final Object changes = new Object();
    private final List<java.util.function.Consumer<PresenceRecord>> listeners = new java.util.concurrent.CopyOnWriteArrayList<>();
    private volatile long lastChange = System.nanoTime();

    private volatile io.robomw.agents.messaging.security.PresenceSeal seal;
    private final java.util.concurrent.atomic.LongAdder ignored = new java.util.concurrent.atomic.LongAdder();
    private final java.util.concurrent.atomic.LongAdder stale = new java.util.concurrent.atomic.LongAdder();
    private volatile PresenceWindow window;
    private volatile io.robomw.agents.messaging.security.ReplayStore windowStore;
    private final io.robomw.agents.net.ThrottledWarnings unsigned = new io.robomw.agents.net.ThrottledWarnings(LOG, Duration.ofSeconds(1));

    private BrokerDirectory(Address address, MqttOptions options, BrokerCredentials credentials, com.hivemq.client.mqtt.MqttClientSslConfig ssl) {
        this.address = address;
        this.topics = options.topics();
        Mqtt5ClientBuilder b = MqttClient.builder().useMqttVersion5()
                .identifier("mw-directory-" + HexFormat.of().formatHex(new SecureRandom().generateSeed(4)))
                .transportConfig().serverHost(options.host()).serverPort(options.port()).sslConfig(ssl).applyTransportConfig();
        if (credentials.username() != null) {
            var auth = b.simpleAuth().username(credentials.username());
            b = credentials.password() == null ? auth.applySimpleAuth() : auth.password(credentials.password()).applySimpleAuth();
        }
        this.client = b.buildAsync();
        client.publishes(MqttGlobalPublishFilter.SUBSCRIBED, this::onPresence);
    }

    /**
     * Connects and subscribes to every presence.
     *
     * @param brokerAddress an mqtt or mqtts address (its path is the prefix)
     * @param timeout       how long connecting may take
     * @return the open directory
     * @throws IOException if the broker cannot be reached
     */
    public static BrokerDirectory open(String brokerAddress, Duration timeout) throws IOException {
        return open(brokerAddress, timeout, null);
    }

    /**
     * {@link #open(String, Duration)} with a node's TLS settings, for an {@code mqtts} broker.
     *
     * @param brokerAddress an mqtt or mqtts address (its path is the prefix)
     * @param timeout       how long connecting may take
     * @param tls           the key and trust store to use with {@code mqtts}, or {@code null} (then the
     *                      address's {@code truststore}, else the JVM's)
     * @return the open directory
     * @throws IOException if the broker cannot be reached
     */
    public static BrokerDirectory open(String brokerAddress, Duration timeout, io.robomw.agents.messaging.security.TlsSettings tls)
            throws IOException {
        return open(brokerAddress, timeout, tls, null);
    }

    /**
     * {@link #open(String, Duration, io.robomw.agents.messaging.security.TlsSettings)} taking only the presences signed with
     * the cluster's seal: the others are ignored and counted ({@link #ignored()}).
     *
     * @param brokerAddress an mqtt or mqtts address (its path is the prefix)
     * @param timeout       how long connecting may take
     * @param tls           the key and trust store to use with {@code mqtts}, or {@code null}
     * @param seal          the cluster's presence seal, or {@code null} to take every presence (unverified)
     * @return the open directory
     * @throws IOException if the broker cannot be reached
     */
    public static BrokerDirectory open(String brokerAddress, Duration timeout, io.robomw.agents.messaging.security.TlsSettings tls,
            io.robomw.agents.messaging.security.PresenceSeal seal) throws IOException {
        return open(brokerAddress, timeout, tls, seal, null);
    }

    /**
     * {@link #open(String, Duration, io.robomw.agents.messaging.security.TlsSettings, io.robomw.agents.messaging.security.PresenceSeal)}
     * keeping its replay window for presences ({@link PresenceWindow}) in a file, so that a presence replayed at the broker
     * is refused after this reader restarts too. With a seal, a signed presence of an earlier connection of its client than
     * one taken, or an online one older than the newest of the same connection, is ignored and counted ({@link #stale()}).
     *
     * @param brokerAddress an mqtt or mqtts address (its path is the prefix)
     * @param timeout       how long connecting may take
     * @param tls           the key and trust store to use with {@code mqtts}, or {@code null}
     * @param seal          the cluster's presence seal, or {@code null} to take every presence (unverified)
     * @param windowFile    where to keep the window across restarts ({@link io.robomw.agents.messaging.security.ReplayStore}),
     *                      or {@code null} for memory only
     * @return the open directory
     * @throws IOException if the broker cannot be reached
     */
    public static BrokerDirectory open(String brokerAddress, Duration timeout, io.robomw.agents.messaging.security.TlsSettings tls,
            io.robomw.agents.messaging.security.PresenceSeal seal, java.nio.file.Path windowFile) throws IOException {
        Address a = Address.parse(brokerAddress);
        if (!a.scheme().equals("mqtt") && !a.scheme().equals("mqtts")) {
            throw new IllegalArgumentException("'" + brokerAddress + "' is not a broker address (mqtt://host:port or mqtts://host:port)");
        }
        MqttOptions options = MqttOptions.of(a, "directory");
        BrokerDirectory d = new BrokerDirectory(a, options, BrokerCredentials.load(options.credentials(), System.getenv(), a.host()),
                MqttTransport.ssl(options, tls, System.getenv(), timeout.toMillis()));
        d.seal = seal;
        d.windowStore = windowFile == null ? io.robomw.agents.messaging.security.ReplayStore.memoryOnly()
                : io.robomw.agents.messaging.security.ReplayStore.in(windowFile, PresenceWindow.KEEP);
        d.window = new PresenceWindow(a.endpoint() + "/" + d.topics.prefix(), d.windowStore);
        if (seal != null) {
            d.windowStore.floor(0); // opens the window's file now, not while the first presence is being read
        }
        try {
            d.client.connectWith().cleanStart(true).send().get(timeout.toMillis(), TimeUnit.MILLISECONDS);
            d.client.subscribeWith().topicFilter(d.topics.everyPresence()).qos(MqttQos.AT_LEAST_ONCE).send()
                    .get(timeout.toMillis(), TimeUnit.MILLISECONDS);
        } catch (ExecutionException | TimeoutException e) {
            d.close();
            throw new IOException("cannot read the presences at " + a.endpoint() + ": "
                    + (e instanceof TimeoutException ? "no answer within " + timeout : BrokerSession.rootMessage(e.getCause())), e);
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
            d.close();
            throw new IOException("interrupted", e);
        }
        d.lastChange = System.nanoTime();
        return d;
    }

    /**
     * Opens, waits for the retained presences (until none came for 0.3 s, at most {@code timeout}),
     * and closes.
     *
     * @param brokerAddress an mqtt or mqtts address
     * @param timeout       the longest wait
     * @return every presence, online ones first, then by name
     * @throws IOException if the broker cannot be reached
     */
    public static List<PresenceRecord> read(String brokerAddress, Duration timeout) throws IOException {
        try (BrokerDirectory d = open(brokerAddress, timeout)) {
            d.awaitQuiet(timeout);
            return d.records();
        }
    }

    /** @return how many presences were ignored for being unsigned or not signed with the seal (0 without a seal) */
    public long ignored() {
        return ignored.sum();
    }

    /**
     * @return how many signed presences were ignored as stale: of an earlier connection of their client than one taken, an
     *         online one older than the newest of its connection, or one naming another client than the topic it came on
     *         (0 without a seal)
     */
    public long stale() {
        return stale.sum();
    }

    /** @return every presence known now, online ones first, then by name */
    public List<PresenceRecord> records() {
        List<PresenceRecord> out = new ArrayList<>(byClient.values());
        out.sort(Comparator.comparing((PresenceRecord p) -> !p.online()).thenComparing(PresenceRecord::node).thenComparing(PresenceRecord::client));
        return out;
    }

    /**
     * @param name a node or agent host name
     * @return the online presence of that node, or of the node of that agent host, if announced
     */
    public java.util.Optional<PresenceRecord> find(String name) {
        return records().stream().filter(PresenceRecord::online)
                .filter(p -> p.node().equals(name) || name.equals(p.host())).findFirst();
    }

    /**
     * @param listener told of every presence read from now on (new, changed, or gone offline), on the client's thread;
     *                 it must return quickly
     */
    public void onPresence(java.util.function.Consumer<PresenceRecord> listener) {
        listeners.add(listener);
        byClient.values().forEach(listener);
    }

    /**
     * Waits until no presence came for a moment (the broker sends the retained ones at once).
     *
     * @param max the longest wait
     */
    public void awaitQuiet(Duration max) {
        long deadline = System.nanoTime() + max.toNanos();
        synchronized (changes) {
            while (true) {
                long now = System.nanoTime();
                long quietFor = now - lastChange;
                if (quietFor >= QUIET_NANOS || now >= deadline) {
                    return;
                }
                try {
                    TimeUnit.NANOSECONDS.timedWait(changes, Math.min(QUIET_NANOS - quietFor, deadline - now));
                } catch (InterruptedException e) {
                    Thread.currentThread().interrupt();
                    return;
                }
            }
        }
    }

    @Override
    public void close() {
        try {
            client.disconnect().get(2, TimeUnit.SECONDS);
        } catch (Exception e) {
            LOG.debug("disconnecting the directory from {}: {}", address, e.toString());
        }
        io.robomw.agents.messaging.security.ReplayStore w = windowStore;
        if (w != null) {
            w.close();
        }
    }

    private void onPresence(Mqtt5Publish p) {
        String t = p.getTopic().toString();
        if (!t.startsWith(topics.presencePrefix())) {
            return;
        }
        String client = MqttTopics.unescape(t.substring(topics.presencePrefix().length()));
        lastChange = System.nanoTime(); // a presence is being read: not quiet yet
        byte[] bytes = p.getPayloadAsBytes();
        if (bytes.length == 0) {
            byClient.remove(client);
        } else {
            try {
                String where = "presence " + t + " at " + address.endpoint();
                io.robomw.agents.messaging.security.PresenceSeal s = seal;
                PresenceRecord record;
                if (s == null) {
                    record = PresenceRecord.decode(bytes, where);
                } else {
                    record = PresenceRecord.decodeSealed(bytes, where, s).orElse(null);
                    if (record == null) {
                        ignored.increment();
                        unsigned.warn("ignored the {}: it is unsigned or not signed with this cluster's key ({} ignored so far)", where, ignored.sum());
                    } else if (!record.client().equals(client) || !window.take(client, record, System.currentTimeMillis())) {
                        stale.increment();
                        unsigned.warn("ignored the {} of node '{}' (connected since {}, made {}): {} ({} ignored so far)", where, record.node(),
                                record.since(), record.time(), record.client().equals(client) ? "a newer one of that client was taken (a replay)"
                                        : "it names client '" + record.client() + "', not the one whose topic it came on", stale.sum());
                        record = null;
                    }
                }
                if (record != null) {
                    byClient.put(client, record);
                }
                for (var l : record == null ? List.<java.util.function.Consumer<PresenceRecord>>of() : listeners) {
                    try {
                        l.accept(record);
                    } catch (RuntimeException e) {
                        LOG.warn("a presence listener failed on {}: {}", record.node(), e.toString());
                    }
                }
            } catch (IllegalArgumentException e) {
                LOG.warn("left out an unreadable presence: {}", e.getMessage());
            }
        }
        synchronized (changes) {
            lastChange = System.nanoTime();
            changes.notifyAll();
        }
    }
}
