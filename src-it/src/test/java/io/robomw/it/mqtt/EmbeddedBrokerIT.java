package io.robomw.it.mqtt;

/** {@link BrokerMessagingIT} through {@code mw broker} (HiveMQ CE embedded). */
class EmbeddedBrokerIT extends BrokerMessagingIT {

    @Override
    Broker.Kind kind() {
        return Broker.Kind.EMBEDDED;
    }
}
