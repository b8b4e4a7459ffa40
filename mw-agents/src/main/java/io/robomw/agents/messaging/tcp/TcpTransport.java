package io.robomw.agents.messaging.tcp;

import io.robomw.agents.messaging.Address;
import io.robomw.agents.messaging.shm.SharedSegment;
import io.robomw.agents.messaging.spi.Endpoint;
import io.robomw.agents.messaging.spi.Link;
import io.robomw.agents.messaging.spi.Transport;
import io.robomw.agents.messaging.spi.TransportContext;

import javax.net.ssl.SSLContext;
import javax.net.ssl.SSLServerSocket;
import javax.net.ssl.SSLSocket;
import java.io.IOException;
import java.net.InetAddress;
import java.net.InetSocketAddress;
import java.net.ServerSocket;
import java.net.Socket;
import java.util.List;
import java.util.concurrent.CopyOnWriteArrayList;

/**
 * TCP for one node: listening endpoints and outgoing connections, all made of
 * {@link TcpConnection}s. With TLS settings, every socket is TLS and both sides must present a
 * certificate the other trusts. Thread-safe.
 */
final class TcpTransport implements Transport {

    private static final org.slf4j.Logger LOG = org.slf4j.LoggerFactory.getLogger(TcpTransport.class);
    /** The most subscriber connections one segment has cells for. */
    private static final int MAX_CELLS = 4096;

    private final TransportContext context;
    /** The segment large publications go through to subscribers on this host; made on first use, under {@code this}. */
    private SharedSegment segment;
    private boolean segmentFailed;
    private boolean closed;
    private final List<AutoCloseable> open = new CopyOnWriteArrayList<>();
    private final ConnectionTimeouts timeouts;
    private SSLContext tls;

    TcpTransport(TransportContext context) {
        this.context = context;
        this.timeouts = new ConnectionTimeouts(context.settings().limits(), context.threads("tcp-timeouts"), context.failures());
    }

    @Override
    public Endpoint bind(Address address) throws IOException {
        ServerSocket server = tls() == null ? new ServerSocket() : tls().getServerSocketFactory().createServerSocket();
        if (server instanceof SSLServerSocket ssl) {
            ssl.setNeedClientAuth(true);
        }
        server.setReuseAddress(true);
        server.bind(new InetSocketAddress(InetAddress.getByName(address.host()), address.port()), 128);
        SharedMemoryOption.allows(address); // a bad value is refused now, not at the first connection
        TcpAcceptor acceptor = new TcpAcceptor(server, address.withPort(server.getLocalPort()), context, open, timeouts, this::segment);
        open.add(acceptor);
        acceptor.start();
        return acceptor;
    }

    @Override
    public Link connect(Address address) throws IOException {
        SharedMemoryOption.allows(address);
        Socket socket = tls() == null ? new Socket() : tls().getSocketFactory().createSocket();
        try {
            socket.connect(new InetSocketAddress(address.host(), address.port()), (int) context.settings().connectTimeout().toMillis());
            if (socket instanceof SSLSocket ssl) {
                ssl.setSoTimeout((int) context.settings().connectTimeout().toMillis());
                ssl.startHandshake();
                ssl.setSoTimeout(0);
            }
        } catch (IOException e) {
            socket.close();
            throw e;
        }
        TcpConnection c = new TcpConnection(socket, address, address.toString(), context, open, timeouts, this::segment);
        c.start();
        return c;
    }

    @Override
    public void close() {
        for (AutoCloseable c : java.util.List.copyOf(open)) {
            try {
                c.close();
            } catch (Exception e) {
                // closing anyway
            }
        }
        open.clear();
        timeouts.close();
        synchronized (this) {
            closed = true;
            if (segment != null) {
                segment.close();
                segment = null;
            }
        }
    }

    /**
     * @return the segment, made now if this is its first use; {@code null} if it cannot be made (logged once:
     *         publications then go over TCP) or the transport is closed
     */
    private synchronized SharedSegment segment() {
        if (segment == null && !segmentFailed && !closed) {
            var settings = context.settings();
            long ring = Math.max(settings.sharedMemory().segmentBytes(), 2L * settings.maxFrameSize() + 64);
            int cells = Math.max(16, Math.min(MAX_CELLS, settings.limits().maxConnections()));
            try {
                segment = SharedSegment.create(SharedSegment.DIRECTORY, (int) Math.min(Integer.MAX_VALUE - 4096 - 7, ring + 7) & ~7, cells);
                LOG.debug("node '{}': large publications to subscribers on this host go through {}", context.nodeName(), segment.file());
            } catch (IOException | RuntimeException e) {
                segmentFailed = true;
                LOG.warn("node '{}': cannot make a shared-memory segment in {} ({}); large publications go over TCP", context.nodeName(),
                        SharedSegment.DIRECTORY, e.toString());
            }
        }
        return segment;
    }

    private synchronized SSLContext tls() throws IOException {
        if (tls == null && context.settings().tls() != null) {
            tls = context.settings().tls().context();
        }
        return tls;
    }
}
