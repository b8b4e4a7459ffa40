package io.robomw.agents.net;

import javax.net.ssl.SSLContext;
import javax.net.ssl.SSLServerSocket;
import javax.net.ssl.SSLSocket;
import java.io.IOException;
import java.net.InetAddress;
import java.net.InetSocketAddress;
import java.net.ServerSocket;
import java.net.Socket;
import java.security.NoSuchAlgorithmException;

/**
 * What the RMI socket factories of the messaging transport and of agent hosts share: a server
 * socket bound to one address only (not every interface), TLS with a required client certificate;
 * a client socket connected to a fixed host with TCP_NODELAY, TLS over the JVM's default context
 * (a factory that travels in a stub cannot carry keys).
 */
public final class RmiSocketSetup {

    /** Makes the plain (non-TLS) server socket, unbound. */
    @FunctionalInterface
    public interface PlainServerSocket {
        /**
         * @return an unbound server socket
         * @throws IOException if it cannot be made
         */
        ServerSocket create() throws IOException;
    }

    private RmiSocketSetup() {
    }

    /**
     * @param plain       the server socket to use without TLS
     * @param tls         the TLS context, or {@code null} for plain sockets
     * @param bindAddress the one address to listen on
     * @param port        the port, 0 for any
     * @return the bound server socket (TLS ones require a client certificate)
     * @throws IOException if it cannot be bound
     */
    public static ServerSocket listen(PlainServerSocket plain, SSLContext tls, InetAddress bindAddress, int port) throws IOException {
        ServerSocket s;
        if (tls != null) {
            SSLServerSocket ssl = (SSLServerSocket) tls.getServerSocketFactory().createServerSocket();
            ssl.setNeedClientAuth(true);
            s = ssl;
        } else {
            s = plain.create();
        }
        s.setReuseAddress(true);
        s.bind(new InetSocketAddress(bindAddress, port), 128);
        return s;
    }

    /**
     * @param raw           an unconnected socket (its other options already set)
     * @param host          the host to connect to
     * @param port          the port
     * @param timeoutMillis the connect timeout
     * @param tls           whether to wrap it in TLS (the JVM's default context) and shake hands
     * @return the connected socket
     * @throws IOException if it cannot connect, or the handshake fails
     */
    public static Socket connect(Socket raw, String host, int port, int timeoutMillis, boolean tls) throws IOException {
        raw.setTcpNoDelay(true);
        raw.connect(new InetSocketAddress(host, port), timeoutMillis);
        if (!tls) {
            return raw;
        }
        try {
            SSLSocket ssl = (SSLSocket) SSLContext.getDefault().getSocketFactory().createSocket(raw, host, port, true);
            ssl.setUseClientMode(true);
            ssl.startHandshake();
            return ssl;
        } catch (NoSuchAlgorithmException e) {
            raw.close();
            throw new IOException("no default TLS context: " + e.getMessage(), e);
        } catch (IOException e) {
            raw.close();
            throw e;
        }
    }
}
