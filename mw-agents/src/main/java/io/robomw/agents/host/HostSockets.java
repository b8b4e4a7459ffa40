package io.robomw.agents.host;

import io.robomw.agents.net.RmiSocketSetup;

import javax.net.ssl.SSLContext;
import java.io.FilterInputStream;
import java.io.FilterOutputStream;
import java.io.IOException;
import java.io.InputStream;
import java.io.OutputStream;
import java.io.Serializable;
import java.net.InetAddress;
import java.net.ServerSocket;
import java.net.Socket;
import java.rmi.server.RMIClientSocketFactory;
import java.rmi.server.RMIServerSocketFactory;
import java.util.Objects;
import java.util.concurrent.atomic.LongAdder;

/**
 * Socket factories of an agent host's RMI endpoint. The server listens on the one address it was
 * given, counts the bytes its accepted connections carry (for the wire-bytes benchmark and
 * {@code mw agents}), and with TLS requires a client certificate. The client side travels in the
 * host's stub: it connects to the host's own address, sets TCP_NODELAY and a read timeout (so a
 * hung host fails a call instead of blocking it forever), and with TLS uses the JVM's default
 * context ({@code javax.net.ssl.*} properties).
 */
final class HostSockets {

    private HostSockets() {
    }

    /**
     * Connections a host's plain RMI endpoint keeps open at once; one more is closed as soon as it
     * is accepted (RMI peers reuse a few connections each: hundreds held open are an attack).
     */
    static final int MAX_CONNECTIONS = 256;

    /** Bytes read and written by a host's accepted connections, and the connections open and refused. */
    static final class Counters {
        final LongAdder in = new LongAdder();
        final LongAdder out = new LongAdder();
        final java.util.concurrent.atomic.AtomicInteger open = new java.util.concurrent.atomic.AtomicInteger();
        final LongAdder refused = new LongAdder();
    }

    /** The listening side; identity equality, so the registry and the endpoint share its one socket. */
    static final class Server implements RMIServerSocketFactory {
        private final InetAddress bindAddress;
        private final SSLContext tls;
        private final Counters counters;

        Server(InetAddress bindAddress, SSLContext tls, Counters counters) {
            this.bindAddress = bindAddress;
            this.tls = tls;
            this.counters = counters;
        }

        @Override
        public ServerSocket createServerSocket(int port) throws IOException {
            // Plain and TLS endpoints alike accept through the counting socket, so the connection
            // limit holds for both; a TLS connection is layered over the counted one once accepted
            // (its handshake runs on RMI's connection thread, at the first read).
            return RmiSocketSetup.listen(() -> new CountingServerSocket(counters, tls), null, bindAddress, port);
        }
    }

    /** A server socket whose connections count their bytes, at most {@link #MAX_CONNECTIONS} at a time, TLS ones too. */
    private static final class CountingServerSocket extends ServerSocket {
        private final Counters counters;
        private final SSLContext tls;

        CountingServerSocket(Counters counters, SSLContext tls) throws IOException {
            this.counters = counters;
            this.tls = tls;
        }

        @Override
        public Socket accept() throws IOException {
            while (true) {
                CountingSocket s = new CountingSocket(counters);
                implAccept(s);
                if (counters.open.incrementAndGet() > MAX_CONNECTIONS) {
                    counters.open.decrementAndGet();
                    counters.refused.increment();
                    s.closeUncounted();
                    continue;
                }
                s.setTcpNoDelay(true);
                if (tls == null) {
                    return s;
                }
                try {
                    // closing the TLS socket closes the counted one (autoClose), which gives the slot back
                    javax.net.ssl.SSLSocket ssl = (javax.net.ssl.SSLSocket) tls.getSocketFactory()
                            .createSocket(s, s.getInetAddress().getHostAddress(), s.getPort(), true);
                    ssl.setUseClientMode(false);
                    ssl.setNeedClientAuth(true);
                    return ssl;
                } catch (IOException e) {
                    s.close();
                    throw e;
                }
            }
        }
    }

    private static final class CountingSocket extends Socket {
        private final Counters counters;
        private final java.util.concurrent.atomic.AtomicBoolean closed = new java.util.concurrent.atomic.AtomicBoolean();

        CountingSocket(Counters counters) {
            this.counters = counters;
        }

        @Override
        public synchronized void close() throws IOException {
            if (closed.compareAndSet(false, true)) {
                counters.open.decrementAndGet();
            }
            super.close();
        }

        void closeUncounted() {
            closed.set(true);
            try {
                super.close();
            } catch (IOException e) {
                // refused anyway
            }
        }

        @Override
        public InputStream getInputStream() throws IOException {
            return new FilterInputStream(super.getInputStream()) {
                @Override
                public int read() throws IOException {
                    int b = super.read();
                    if (b >= 0) {
                        counters.in.increment();
                    }
                    return b;
                }

                @Override
                public int read(byte[] buf, int off, int len) throws IOException {
                    int n = super.read(buf, off, len);
                    if (n > 0) {
                        counters.in.add(n);
                    }
                    return n;
                }
            };
        }

        @Override
        public OutputStream getOutputStream() throws IOException {
            return new FilterOutputStream(super.getOutputStream()) {
                @Override
                public void write(int b) throws IOException {
                    out.write(b);
                    counters.out.increment();
                }

                @Override
                public void write(byte[] buf, int off, int len) throws IOException {
                    out.write(buf, off, len);
                    counters.out.add(len);
                }
            };
        }
    }

    /** RMI's transport: the byte a client sends to ask whether a reused connection is alive, and the answer. */
    static final int RMI_PING = 0x52;
    static final int RMI_PING_ACK = 0x53;
    /** A connection that carried an answer this recently is taken to be alive without asking. */
    static final long WARM_NANOS = 100_000_000L;

    /**
     * A client socket that answers RMI's liveness ping itself when the connection carried an
     * answer within the last {@value #WARM_NANOS} ns. RMI pings a pooled connection before reusing
     * it unless it was used within "one round trip", which it measures with the millisecond
     * clock: on loopback or a LAN the round trip measures 0 ms, and from then on every call on the
     * connection is preceded by a ping round trip of its own (a write, a wake-up of the host's
     * connection thread, its answer, a wake-up here), which was a large part of a warm hop. A
     * connection that answered a moment ago is alive as far as a ping can tell; if it died since,
     * the call itself fails and the caller's retry rules apply (a transfer is resent to the same
     * host until it answers). A ping is recognised as what RMI writes after an answer: exactly one
     * byte, {@code 0x52}, in one write and flush, before anything else (calls start with
     * {@code 0x50}, DGC acknowledgements with {@code 0x54}).
     */
    static final class WarmSocket extends Socket {
        private final LongAdder pingsAnswered = new LongAdder();
        private volatile long lastAnswer;
        private volatile boolean answeredSinceWrite;
        private volatile boolean ackPending;
        private InputStream in;
        private OutputStream out;

        @Override
        public synchronized InputStream getInputStream() throws IOException {
            if (in == null) {
                in = new FilterInputStream(super.getInputStream()) {
                    @Override
                    public int read() throws IOException {
                        if (ackPending) {
                            ackPending = false;
                            return RMI_PING_ACK;
                        }
                        int b = super.read();
                        answered(b >= 0 ? 1 : 0);
                        return b;
                    }

                    @Override
                    public int read(byte[] buf, int off, int len) throws IOException {
                        if (ackPending && len > 0) {
                            ackPending = false;
                            buf[off] = (byte) RMI_PING_ACK;
                            return 1;
                        }
                        int n = super.read(buf, off, len);
                        answered(n);
                        return n;
                    }
                };
            }
            return in;
        }

        /** @return how many of RMI's pings this socket answered itself */
        long pingsAnswered() {
            return pingsAnswered.sum();
        }

        private void answered(int n) {
            if (n > 0) {
                lastAnswer = System.nanoTime();
                answeredSinceWrite = true;
            }
        }

        @Override
        public synchronized OutputStream getOutputStream() throws IOException {
            if (out == null) {
                out = new FilterOutputStream(super.getOutputStream()) {
                    @Override
                    public void write(int b) throws IOException {
                        write(new byte[] {(byte) b}, 0, 1);
                    }

                    @Override
                    public void write(byte[] buf, int off, int len) throws IOException {
                        if (len == 1 && buf[off] == RMI_PING && answeredSinceWrite && System.nanoTime() - lastAnswer < WARM_NANOS) {
                            answeredSinceWrite = false;
                            ackPending = true;
                            pingsAnswered.increment();
                            return;
                        }
                        answeredSinceWrite = false;
                        out.write(buf, off, len);
                    }
                };
            }
            return out;
        }
    }

    /** The connecting side, serializable because it travels in the host's stub. */
    static final class Client implements RMIClientSocketFactory, Serializable {
        private static final long serialVersionUID = 1L;
        private final String host;
        private final boolean tls;
        private final int timeoutMillis;

        Client(String host, boolean tls, int timeoutMillis) {
            this.host = host;
            this.tls = tls;
            this.timeoutMillis = timeoutMillis;
        }

        @Override
        public Socket createSocket(String ignoredHost, int port) throws IOException {
            Socket s = tls ? new Socket() : new WarmSocket();
            s.setSoTimeout(timeoutMillis);
            return RmiSocketSetup.connect(s, host, port, timeoutMillis, tls);
        }

        @Override
        public boolean equals(Object o) {
            return o instanceof Client c && c.host.equals(host) && c.tls == tls && c.timeoutMillis == timeoutMillis;
        }

        @Override
        public int hashCode() {
            return Objects.hash(host, tls, timeoutMillis);
        }
    }
}
