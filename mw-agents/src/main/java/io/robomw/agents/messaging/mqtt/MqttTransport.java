package io.robomw.agents.messaging.mqtt;

import com.hivemq.client.mqtt.MqttClientSslConfig;
import com.hivemq.client.mqtt.MqttClientSslConfigBuilder;
import io.robomw.agents.messaging.Address;
import io.robomw.agents.messaging.security.TlsSettings;
import io.robomw.agents.messaging.spi.Endpoint;
import io.robomw.agents.messaging.spi.Link;
import io.robomw.agents.messaging.spi.Transport;
import io.robomw.agents.messaging.spi.TransportContext;

import java.io.IOException;
import java.util.List;
import java.util.Map;
import java.util.concurrent.ConcurrentHashMap;

/**
 * MQTT 5 for one node: one {@link BrokerSession} per broker and topic prefix, shared by what the
 * node binds there (to receive messages and publish) and what it connects or sends to there.
 * Binding and connecting both join the broker: the node then receives messages addressed to its
 * names, publishes through the broker, and subscribes there. Thread-safe.
 */
final class MqttTransport implements Transport {

    /** Environment variable with the password of an {@code mqtts} address's {@code truststore}. */
    static final String TRUSTSTORE_PASSWORD_ENV = "MW_MQTT_TRUSTSTORE_PASSWORD";

    private final TransportContext context;
    private final Map<String, String> env;
    private final Map<String, BrokerSession> sessions = new ConcurrentHashMap<>();
    private volatile boolean closed;

    MqttTransport(TransportContext context, Map<String, String> env) {
        this.context = context;
        this.env = env;
    }

    @Override
    public Endpoint bind(Address address) throws IOException {
        return session(address);
    }

    @Override
    public Link connect(Address address) throws IOException {
        return session(address);
    }

    @Override
    public void answerTo(String receiverName) {
        sessions.values().forEach(s -> s.answerTo(receiverName));
    }

    @Override
    public void close() {
        closed = true;
        for (BrokerSession s : List.copyOf(sessions.values())) {
            s.close();
        }
        sessions.clear();
    }

    private BrokerSession session(Address address) throws IOException {
        MqttOptions options;
        try {
            options = MqttOptions.of(address, context.nodeName());
        } catch (IllegalArgumentException e) {
            throw new IOException(e.getMessage(), e);
        }
        String key = options.sessionKey();
        synchronized (sessions) {
            if (closed) {
                throw new IOException("the node is closed");
            }
            BrokerSession s = sessions.get(key);
            if (s != null && s.isOpen()) {
                return s;
            }
            BrokerCredentials credentials = BrokerCredentials.load(options.credentials(), env, options.host());
            Address canonical = new Address(address.scheme(), address.host(), address.port(), options.topics().prefix(), Map.of());
            s = new BrokerSession(options, canonical, context, credentials, ssl(options));
            s.start();
            sessions.put(key, s);
            return s;
        }
    }

    private MqttClientSslConfig ssl(MqttOptions options) throws IOException {
        return ssl(options, context.settings().tls(), env, context.settings().connectTimeout().toMillis());
    }

    /**
     * @param options   the address's options
     * @param tls       the node's TLS settings, or {@code null}
     * @param env       the environment (the trust store's password)
     * @param handshake the longest TLS handshake, in milliseconds
     * @return the client's TLS configuration for an {@code mqtts} address, or {@code null} for {@code mqtt}:
     *         the node's key and trust store if it has them, else the address's trust store, else the JVM's
     * @throws IOException naming a store that cannot be read
     */
    static MqttClientSslConfig ssl(MqttOptions options, TlsSettings tls, Map<String, String> env, long handshake) throws IOException {
        if (!options.tls()) {
            return null;
        }
        MqttClientSslConfigBuilder b = MqttClientSslConfig.builder();
        if (tls != null) {
            b = b.keyManagerFactory(tls.keyManagerFactory()).trustManagerFactory(tls.trustManagerFactory());
        } else if (options.trustStore() != null) {
            String password = env.getOrDefault(TRUSTSTORE_PASSWORD_ENV, "");
            b = b.trustManagerFactory(TlsSettings.trustManagerFactory(options.trustStore(), password));
        }
        return b.handshakeTimeout(handshake, java.util.concurrent.TimeUnit.MILLISECONDS).build();
    }
}
