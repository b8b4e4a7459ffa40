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
     * RMI names the address a stub carries in its errors ("Connection refused to host: 127.0.0.1"),
     * which is the exporting machine's name, not always where the factory connected; the cause it
     * wraps is this exception, of the same kind as the socket's, and names the address tried.
     */
    private static IOException naming(IOException e, String host, int port, int timeoutMillis) {
        String where = (host.contains(":") ? "[" + host + "]" : host) + ":" + port;
        IOException named;
        if (e instanceof java.net.SocketTimeoutException) {
            named = new java.net.SocketTimeoutException("connecting to " + where + " timed out after " + timeoutMillis + " ms");
        } else if (e instanceof java.net.ConnectException) {
            named = new java.net.ConnectException("cannot connect to " + where + ": " + e.getMessage());
        } else if (e instanceof java.net.NoRouteToHostException) {
            named = new java.net.NoRouteToHostException("no route to " + where + ": " + e.getMessage());
        } else if (e instanceof java.net.UnknownHostException) {
            named = new java.net.UnknownHostException("unknown host " + host + " (port " + port + "): " + e.getMessage());
        } else {
            return new IOException("cannot connect to " + where + ": " + e, e);
        }
        named.initCause(e);
        return named;
    }

    /**
     * Where a failed RMI call really failed: RMI wraps the socket factory's exception in one that
     * names the host the stub carries; this is the message of the innermost cause (which names the
     * address the factory connected to) when there is one, else the exception's own.
     *
     * @param e a failure of an RMI call
     * @return a message naming the address that failed
     */
    public static String reason(Throwable e) {
        Throwable t = e;
        while (t instanceof java.rmi.RemoteException && t.getCause() != null) {
            t = t.getCause();
        }
        if (t == e) {
            return String.valueOf(e.getMessage());
        }
        boolean connecting = t instanceof java.net.ConnectException || t instanceof java.net.SocketTimeoutException
                || t instanceof java.net.NoRouteToHostException || t instanceof java.net.UnknownHostException;
        return connecting ? t.getMessage() : t.getClass().getSimpleName() + ": " + t.getMessage();
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
        try {
            raw.connect(new InetSocketAddress(host, port), timeoutMillis);
        } catch (IOException e) {
            raw.close();
            throw naming(e, host, port, timeoutMillis);
        }
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
