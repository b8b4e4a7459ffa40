package io.robomw.agents.messaging.rmi;

import io.robomw.agents.messaging.spi.Transport;
import io.robomw.agents.messaging.spi.TransportContext;
import io.robomw.agents.messaging.spi.TransportProvider;

/**
 * {@code rmi://host:port/name}: frames over Java RMI. The server binds a {@link FrameEndpoint}
 * under {@code name} in an RMI registry on {@code port} (created if this JVM has none there);
 * clients deliver frames in batches and poll for theirs. Ordered and reliable while the session
 * lives; optionally TLS with client authentication.
 */
public final class RmiTransportProvider implements TransportProvider {

    @Override
    public String scheme() {
        return "rmi";
    }

    @Override
    public Transport create(TransportContext context) {
        return new RmiTransport(context);
    }
}
