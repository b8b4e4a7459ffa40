package io.robomw.agents.messaging.multicast;

import io.robomw.agents.messaging.spi.Transport;
import io.robomw.agents.messaging.spi.TransportContext;
import io.robomw.agents.messaging.spi.TransportProvider;

/**
 * {@code multicast://group:port}: one datagram to every member of an IPv4 group. Same limits as
 * UDP (no delivery, order or duplicate guarantee; one datagram per frame), on the interface and
 * with the TTL of the settings or the address ({@code ?interface=lo&ttl=0}); by default the
 * loopback interface with TTL 0, so nothing leaves the host unless configured to.
 */
public final class MulticastTransportProvider implements TransportProvider {

    @Override
    public String scheme() {
        return "multicast";
    }

    @Override
    public Transport create(TransportContext context) {
        return new MulticastTransport(context);
    }
}
