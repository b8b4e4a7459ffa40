package io.robomw.agents.messaging.mqtt;

import io.robomw.agents.messaging.Address;

import java.nio.file.Path;
import java.security.SecureRandom;
import java.util.HexFormat;
import java.util.Set;

/**
 * What an {@code mqtt://} or {@code mqtts://} address says: the broker, the topic prefix (the
 * address's path, default {@value MqttTopics#DEFAULT_PREFIX}) and, in the query:
 *
 * <table>
 * <caption>address options</caption>
 * <tr><th>option</th><th>default</th><th>meaning</th></tr>
 * <tr><td>{@code client-id}</td><td>node name and a random suffix; with a session expiry, {@code PREFIX-NODE}</td>
 *     <td>the MQTT client identifier: a persistent session is found again by it</td></tr>
 * <tr><td>{@code session-expiry}</td><td>0</td><td>seconds the broker keeps the session (subscriptions and
 *     the QoS 1 messages for them) after the client is gone; 0 is a clean session</td></tr>
 * <tr><td>{@code qos}</td><td>1</td><td>0 (at most once) or 1 (at least once) for everything sent</td></tr>
 * <tr><td>{@code keep-alive}</td><td>10</td><td>seconds; a broker that is silent for 1.5 times that is taken as lost</td></tr>
 * <tr><td>{@code max-in-flight}</td><td>64</td><td>while connected, messages handed to the broker and not yet acknowledged;
 *     a send beyond them waits (up to the send timeout) for the broker's acknowledgements, so a fast sender does not pile
 *     messages up in the client (brokers take 10-20 at once: their Receive Maximum)</td></tr>
 * <tr><td>{@code max-queued}</td><td>10000</td><td>messages that may wait for the broker (in flight or while it is away)</td></tr>
 * <tr><td>{@code max-queued-bytes}</td><td>67108864 (64 MiB)</td><td>bytes of messages that may wait for the broker, together:
 *     sensor-sized messages (a scan, a camera frame) reach it long before {@code max-queued}; one message larger than it
 *     waits alone</td></tr>
 * <tr><td>{@code credentials}</td><td>the environment</td><td>a file with {@code username=} and {@code password=} lines
 *     ({@link BrokerCredentials})</td></tr>
 * <tr><td>{@code truststore}</td><td>the JVM's</td><td>{@code mqtts}: a PKCS#12 or JKS file of the certificates to trust
 *     (password in {@code MW_MQTT_TRUSTSTORE_PASSWORD}), unless the node's {@code TlsSettings} give one</td></tr>
 * </table>
 *
 * <p>{@code password} is allowed too and left alone: it is the robot topic's password of
 * {@code Robots.remote} addresses.
 *
 * @param tls                  whether TLS is used ({@code mqtts})
 * @param host                 the broker's host
 * @param port                 its port
 * @param topics               the topic layout
 * @param clientId             the MQTT client identifier
 * @param sessionExpirySeconds 0 for a clean session
 * @param qos                  0 or 1
 * @param keepAliveSeconds     the keep-alive
 * @param maxInFlight          while connected, messages sent and not yet acknowledged
 * @param maxQueued            messages that may wait for the broker
 * @param maxQueuedBytes       bytes of messages that may wait for the broker, together
 * @param credentials          the credentials file, or {@code null} for the environment
 * @param trustStore           the trust store file, or {@code null}
 */
public record MqttOptions(boolean tls, String host, int port, MqttTopics topics, String clientId, long sessionExpirySeconds,
                          int qos, int keepAliveSeconds, int maxInFlight, int maxQueued, long maxQueuedBytes, Path credentials, Path trustStore) {

    /** {@code max-queued-bytes} unless the address says otherwise: 64 MiB. */
    public static final long DEFAULT_MAX_QUEUED_BYTES = 64L << 20;

    /** {@code max-in-flight} unless the address says otherwise: what a sensor stream needs to keep a broker's receive window full. */
    public static final int DEFAULT_MAX_IN_FLIGHT = 64;

    private static final Set<String> KNOWN = Set.of("client-id", "session-expiry", "qos", "keep-alive", "max-in-flight", "max-queued", "max-queued-bytes",
            "credentials", "truststore", "password");

    /**
     * @param a        an mqtt or mqtts address
     * @param nodeName the node's name, for the default client identifier
     * @return its options
     * @throws IllegalArgumentException naming the option that is unknown or out of range
     */
    public static MqttOptions of(Address a, String nodeName) {
        for (String key : a.query().keySet()) {
            if (!KNOWN.contains(key)) {
                throw new IllegalArgumentException("'" + a + "': unknown option '" + key + "'; an mqtt address takes " + KNOWN);
            }
        }
        MqttTopics topics = new MqttTopics(a.path().isEmpty() ? MqttTopics.DEFAULT_PREFIX : a.path());
        long expiry = number(a, "session-expiry", 0, 0, 0xFFFF_FFFFL);
        int qos = (int) number(a, "qos", 1, 0, 1);
        int keepAlive = (int) number(a, "keep-alive", 10, 1, 65_535);
        int maxInFlight = (int) number(a, "max-in-flight", DEFAULT_MAX_IN_FLIGHT, 1, 65_535);
        int maxQueued = (int) number(a, "max-queued", 10_000, 1, 1_000_000);
        long maxQueuedBytes = number(a, "max-queued-bytes", DEFAULT_MAX_QUEUED_BYTES, 1024, 1L << 40);
        String clientId = a.query().get("client-id");
        if (clientId == null || clientId.isEmpty()) {
            clientId = expiry > 0 ? topics.prefix().replace('/', '-') + "-" + nodeName
                    : nodeName + "-" + HexFormat.of().formatHex(new SecureRandom().generateSeed(4));
        }
        String credentials = a.query().get("credentials");
        String trust = a.query().get("truststore");
        return new MqttOptions(a.scheme().equals("mqtts"), a.host(), a.port(), topics, clientId, expiry, qos, keepAlive, maxInFlight, maxQueued, maxQueuedBytes,
                credentials == null || credentials.isEmpty() ? null : Path.of(credentials), trust == null || trust.isEmpty() ? null : Path.of(trust));
    }

    /** @return the broker and prefix: one session per node for each */
    public String sessionKey() {
        return (tls ? "mqtts://" : "mqtt://") + (host.contains(":") ? "[" + host + "]" : host) + ":" + port + "/" + topics.prefix();
    }

    private static long number(Address a, String key, long dflt, long min, long max) {
        String v = a.query().get(key);
        if (v == null || v.isEmpty()) {
            return dflt;
        }
        long n;
        try {
            n = Long.parseLong(v);
        } catch (NumberFormatException e) {
            throw new IllegalArgumentException("'" + a + "': option " + key + "=" + v + " is not a whole number");
        }
        if (n < min || n > max) {
            throw new IllegalArgumentException("'" + a + "': option " + key + "=" + v + " must be " + min + ".." + max);
        }
        return n;
    }
}
