package io.robomw.agents.messaging.rmi;

import io.robomw.agents.net.RmiSocketSetup;

import javax.net.ssl.SSLContext;
import java.io.IOException;
import java.io.Serializable;
import java.net.InetAddress;
import java.net.ServerSocket;
import java.net.Socket;
import java.rmi.server.RMIClientSocketFactory;
import java.rmi.server.RMIServerSocketFactory;
import java.util.Objects;

/**
 * Socket factories for the RMI transport. The server side listens on the address it was given
 * only (not on every interface); the client side, which travels inside the stub, connects to the
 * host it was made with (not to whatever {@code java.rmi.server.hostname} or the machine's name
 * would say). With TLS, the server requires a client certificate, and the client side uses the
 * JVM's default TLS context ({@code javax.net.ssl.keyStore} and {@code trustStore} properties),
 * because a factory that travels in a stub cannot carry keys.
 */
final class RmiSockets {

    private RmiSockets() {
    }

    /**
     * Listens on one address, plain or TLS with client authentication. Remembers the port it
     * bound. One instance per endpoint: the registry and the endpoint it names share its socket.
     */
    static final class Server implements RMIServerSocketFactory {
        private final InetAddress bindAddress;
        private final SSLContext tls;
        private volatile int boundPort;

        Server(InetAddress bindAddress, SSLContext tls) {
            this.bindAddress = bindAddress;
            this.tls = tls;
        }

        @Override
        public ServerSocket createServerSocket(int port) throws IOException {
            ServerSocket s = RmiSocketSetup.listen(ServerSocket::new, tls, bindAddress, port);
            boundPort = s.getLocalPort();
            return s;
        }

        int boundPort() {
            return boundPort;
        }

        // Identity equality on purpose: RMI shares a listening socket between exports with equal
        // factories, so each endpoint (registry and FrameEndpoint together) gets its own socket.
    }

    /** Connects to a fixed host, plain or TLS (default context). Serializable: it travels in stubs. */
    static final class Client implements RMIClientSocketFactory, Serializable {
        private static final long serialVersionUID = 1L;
        private final String host;
        private final boolean tls;
        private final int connectTimeoutMillis;

        Client(String host, boolean tls, int connectTimeoutMillis) {
            this.host = host;
            this.tls = tls;
            this.connectTimeoutMillis = connectTimeoutMillis;
        }

        @Override
        public Socket createSocket(String ignoredHost, int port) throws IOException {
            return RmiSocketSetup.connect(new Socket(), host, port, connectTimeoutMillis, tls);
        }

        @Override
        public boolean equals(Object o) {
            return o instanceof Client other && other.host.equals(host) && other.tls == tls;
        }

        @Override
        public int hashCode() {
            return Objects.hash(host, tls);
        }
    }
}
