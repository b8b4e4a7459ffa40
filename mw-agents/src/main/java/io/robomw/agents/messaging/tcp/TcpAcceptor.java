package io.robomw.agents.messaging.tcp;

import io.robomw.agents.messaging.Address;
import io.robomw.agents.messaging.spi.Endpoint;
import io.robomw.agents.messaging.spi.TransportContext;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.io.IOException;
import java.net.ServerSocket;
import java.net.Socket;
import java.util.List;

/** A listening TCP socket: accepts connections on its own thread and starts a {@link TcpConnection} for each. */
final class TcpAcceptor implements Endpoint {

    private static final Logger LOG = LoggerFactory.getLogger(TcpAcceptor.class);

    private final ServerSocket server;
    private final Address address;
    private final TransportContext context;
    private final List<AutoCloseable> open;

    TcpAcceptor(ServerSocket server, Address address, TransportContext context, List<AutoCloseable> open) {
        this.server = server;
        this.address = address;
        this.context = context;
        this.open = open;
    }

    void start() {
        context.threads("tcp-accept-" + address.port()).newThread(this::acceptLoop).start();
    }

    @Override
    public Address address() {
        return address;
    }

    @Override
    public void close() {
        try {
            server.close();
        } catch (IOException e) {
            LOG.debug("closing {}: {}", address, e.toString());
        }
    }

    private void acceptLoop() {
        while (!server.isClosed()) {
            Socket s;
            try {
                s = server.accept();
            } catch (IOException e) {
                if (!server.isClosed()) {
                    LOG.warn("node '{}': accepting on {} failed: {}", context.nodeName(), address, e.toString());
                }
                continue;
            }
            String peer = "tcp://" + s.getInetAddress().getHostAddress() + ":" + s.getPort();
            TcpConnection c;
            try {
                c = new TcpConnection(s, address, peer, context, open);
            } catch (IOException | RuntimeException | LinkageError e) {
                LOG.warn("node '{}': connection from {} failed: {}", context.nodeName(), peer, e.toString());
                closeQuietly(s);
                continue;
            }
            c.start();
        }
    }

    private static void closeQuietly(Socket s) {
        try {
            s.close();
        } catch (IOException ignored) {
            // nothing more to do
        }
    }
}
