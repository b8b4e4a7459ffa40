package io.robomw.agents.messaging.tcp;

import io.robomw.agents.messaging.Address;
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

    private final TransportContext context;
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
        TcpAcceptor acceptor = new TcpAcceptor(server, address.withPort(server.getLocalPort()), context, open, timeouts);
        open.add(acceptor);
        acceptor.start();
        return acceptor;
    }

    @Override
    public Link connect(Address address) throws IOException {
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
        TcpConnection c = new TcpConnection(socket, address, address.toString(), context, open, timeouts);
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
    }

    private synchronized SSLContext tls() throws IOException {
        if (tls == null && context.settings().tls() != null) {
            tls = context.settings().tls().context();
        }
        return tls;
    }
}
