package io.robomw.agents.messaging.mqtt;

import io.robomw.agents.messaging.spi.Transport;
import io.robomw.agents.messaging.spi.TransportContext;
import io.robomw.agents.messaging.spi.TransportProvider;

/**
 * {@code mqtt://broker:1883[/prefix][?options]} and {@code mqtts://broker:8883/...}: messages,
 * publications and presence through an MQTT 5 broker ({@link MqttOptions} lists the options,
 * {@link MqttTopics} the topics, {@link BrokerSession} how frames travel).
 */
public abstract class MqttTransportProvider implements TransportProvider {

    private final String scheme;

    /** @param scheme the scheme this provider serves */
    protected MqttTransportProvider(String scheme) {
        this.scheme = scheme;
    }

    @Override
    public String scheme() {
        return scheme;
    }

    @Override
    public Transport create(TransportContext context) {
        return new MqttTransport(context, System.getenv());
    }

    /** {@code mqtt://}: plain TCP to the broker. */
    public static final class Plain extends MqttTransportProvider {
        /** For {@link java.util.ServiceLoader}. */
        public Plain() {
            super("mqtt");
        }
    }

    /** {@code mqtts://}: TLS to the broker (its certificate checked against the trust store). */
    public static final class Tls extends MqttTransportProvider {
        /** For {@link java.util.ServiceLoader}. */
        public Tls() {
            super("mqtts");
        }
    }
}
