package io.robomw.it.mqtt;

/**
 * {@link BrokerMessagingIT} through Debian's Mosquitto (installed by {@code .ci/run}; skipped, saying
 * so, only where it is not installed).
 */
class MosquittoIT extends BrokerMessagingIT {

    @Override
    Broker.Kind kind() {
        return Broker.Kind.MOSQUITTO;
    }
}
