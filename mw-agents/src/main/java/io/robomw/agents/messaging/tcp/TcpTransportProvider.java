package io.robomw.agents.messaging.tcp;

import io.robomw.agents.messaging.spi.Transport;
import io.robomw.agents.messaging.spi.TransportContext;
import io.robomw.agents.messaging.spi.TransportProvider;

/** {@code tcp://host:port}: frames over TCP connections, optionally TLS with mutual authentication. */
public final class TcpTransportProvider implements TransportProvider {

    @Override
    public String scheme() {
        return "tcp";
    }

    @Override
    public Transport create(TransportContext context) {
        return new TcpTransport(context);
    }
}
