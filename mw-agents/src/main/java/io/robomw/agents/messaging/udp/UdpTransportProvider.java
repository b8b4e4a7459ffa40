package io.robomw.agents.messaging.udp;

import io.robomw.agents.messaging.spi.Transport;
import io.robomw.agents.messaging.spi.TransportContext;
import io.robomw.agents.messaging.spi.TransportProvider;

/**
 * {@code udp://host:port}: one frame per datagram. No delivery, order or duplicate guarantee;
 * frames up to one datagram (65,507 bytes); losses are counted from stream sequence numbers.
 */
public final class UdpTransportProvider implements TransportProvider {

    @Override
    public String scheme() {
        return "udp";
    }

    @Override
    public Transport create(TransportContext context) {
        return new UdpTransport(context);
    }
}
