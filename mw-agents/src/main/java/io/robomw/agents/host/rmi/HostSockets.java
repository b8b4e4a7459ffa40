package io.robomw.agents.host.rmi;

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
import java.net.SocketException;
import java.rmi.server.RMIClientSocketFactory;
import java.rmi.server.RMIServerSocketFactory;
import java.util.Objects;
import java.util.concurrent.atomic.LongAdder;

/**
 * Socket factories of an agent host's RMI endpoint. The server listens on the one address it was
 * given, counts the bytes its accepted connections carry (for the wire-bytes benchmark and
 * {@code mw agents}), keeps its connections within {@link HostConnections}' limits (which
 * connection proved the key, the oldest idle one makes way, a first byte within 5 s), and with TLS
 * requires a client certificate. Its sockets do not tell RMI the client's address (they say
 * {@code 0.0.0.0}, which RMI takes as "origin unknown"), so the JDK's registry refuses every {@code bind},
 * {@code rebind} and {@code unbind} that does not come from the host's own process (the host binds
 * its name in-process); the host knows the address itself ({@link HostConnections#currentRemote}).
 * The client side travels in the
 * host's stub: it connects to the host's own address, sets TCP_NODELAY and a read timeout (so a
 * hung host fails a call instead of blocking it forever), and with TLS uses the JVM's default
 * context ({@code javax.net.ssl.*} properties).
 */
public final class HostSockets {

    private HostSockets() {
    }

    /**
     * Connections a host's RMI endpoint keeps open at once ({@link HostConnections#MAX_CONNECTIONS}); one more makes
     * the oldest that proved nothing make way, or is closed as soon as it is accepted if every open one has proved the key.
     */
    public static final int MAX_CONNECTIONS = HostConnections.MAX_CONNECTIONS;

    /** Bytes read and written by a host's accepted connections, and the connections open and refused. */
    public static final class Counters {
        public final LongAdder in = new LongAdder();
        public final LongAdder out = new LongAdder();
        public final java.util.concurrent.atomic.AtomicInteger open = new java.util.concurrent.atomic.AtomicInteger();
        public final LongAdder refused = new LongAdder();
    }

    /** The listening side; identity equality, so the registry and the endpoint share its one socket. */
    public static final class Server implements RMIServerSocketFactory {
        private final InetAddress bindAddress;
        private final SSLContext tls;
        private final Counters counters;
        private final HostConnections connections;
        private final long readSpinNanos;

        public Server(InetAddress bindAddress, SSLContext tls, Counters counters) {
            this(bindAddress, tls, counters, new HostConnections("endpoint", 0), 0);
        }

        /**
         * @param connections   the limits and state of the accepted connections
         * @param readSpinNanos how long a connection thread spins for the next call before it blocks in a read (0: never)
         */
        public Server(InetAddress bindAddress, SSLContext tls, Counters counters, HostConnections connections, long readSpinNanos) {
            this.bindAddress = bindAddress;
            this.tls = tls;
            this.counters = counters;
            this.connections = connections;
            this.readSpinNanos = readSpinNanos;
        }

        /** @return the state of the connections it accepts */
        HostConnections connections() {
            return connections;
        }

        @Override
        public ServerSocket createServerSocket(int port) throws IOException {
            // Plain and TLS endpoints alike accept through the counting socket, so the connection
            // limit holds for both; a TLS connection is layered over the counted one once accepted
            // (its handshake runs on RMI's connection thread, at the first read).
            return RmiSocketSetup.listen(() -> new CountingServerSocket(counters, connections, tls, readSpinNanos), null, bindAddress, port);
        }
    }

    /** A server socket whose connections count their bytes, at most {@link #MAX_CONNECTIONS} at a time, TLS ones too. */
    private static final class CountingServerSocket extends ServerSocket {
        private final Counters counters;
        private final HostConnections connections;
        private final SSLContext tls;
        private final long readSpinNanos;

        CountingServerSocket(Counters counters, HostConnections connections, SSLContext tls, long readSpinNanos) throws IOException {
            this.counters = counters;
            this.connections = connections;
            this.tls = tls;
            this.readSpinNanos = readSpinNanos;
        }

        @Override
        public Socket accept() throws IOException {
            while (true) {
                CountingSocket s = new CountingSocket(counters, connections, tls == null ? readSpinNanos : 0);
                implAccept(s);
                HostConnections.Connection c = connections.admit(s.remote(), s);
                if (c == null) {
                    counters.refused.increment();
                    s.closeUncounted();
                    continue;
                }
                s.connection = c;
                counters.open.incrementAndGet();
                s.setTcpNoDelay(true);
                if (tls == null) {
                    return s;
                }
                try {
                    // closing the TLS socket closes the counted one (autoClose), which gives the slot back
                    javax.net.ssl.SSLSocket ssl = (javax.net.ssl.SSLSocket) tls.getSocketFactory()
                            .createSocket(s, s.realAddress().getHostAddress(), s.getPort(), true);
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

    /**
     * What an accepted connection tells RMI its client's address is: the wildcard address, which
     * RMI's registry takes as "origin unknown" (so it refuses changes from it), named so that
     * asking its host name looks nothing up.
     */
    static final InetAddress ORIGIN_UNKNOWN = originUnknown();

    private static InetAddress originUnknown() {
        try {
            return InetAddress.getByAddress("origin-unknown-to-rmi", new byte[4]);
        } catch (java.net.UnknownHostException e) {
            throw new AssertionError("four bytes are an IPv4 address", e);
        }
    }

    private static final class CountingSocket extends Socket {
        private final Counters counters;
        private final HostConnections connections;
        private final long readSpinNanos;
        private final java.util.concurrent.atomic.AtomicBoolean closed = new java.util.concurrent.atomic.AtomicBoolean();
        /** Its state among the endpoint's connections; set once admitted, before RMI sees it. */
        private volatile HostConnections.Connection connection;
        /** The read timeout RMI asked for, applied once the first byte came. */
        private volatile int timeoutMillis;
        private InputStream in;

        CountingSocket(Counters counters, HostConnections connections, long readSpinNanos) {
            this.counters = counters;
            this.connections = connections;
            this.readSpinNanos = readSpinNanos;
        }

        /**
         * The wildcard address {@code 0.0.0.0} ({@link #ORIGIN_UNKNOWN}), to RMI and everyone else
         * who asks: RMI then takes the client to be at {@code 0.0.0.0}, from where the JDK's
         * registry takes no {@code bind}, {@code rebind} or {@code unbind} ("origin unknown"), while
         * lookups go on. Not {@code null}: the JDK's own socket code takes a connected socket to
         * have an address (JDK 17's flight recorder reads it after every socket read and write
         * that took longer than its threshold, and a {@code null} killed the connection's thread
         * with a NullPointerException, so a host under a JFR recording dropped calls). The host
         * knows the real address from {@link #realAddress()}.
         */
        @Override
        public InetAddress getInetAddress() {
            return ORIGIN_UNKNOWN;
        }

        /** @return the client's address */
        InetAddress realAddress() {
            return super.getInetAddress();
        }

        /** @return the client's address and port, for the log */
        String remote() {
            InetAddress a = super.getInetAddress();
            return (a == null ? "?" : a.getHostAddress()) + ":" + getPort();
        }

        @Override
        public void setSoTimeout(int timeout) throws SocketException {
            timeoutMillis = timeout;
            if (in == null || ((ReadAhead) in).sawByte) {
                super.setSoTimeout(timeout);
            }
        }

        /** Reads with the first-byte deadline until a byte came, then with RMI's timeout. */
        void firstByteDeadline(boolean on) throws SocketException {
            int rmi = timeoutMillis;
            int first = (int) HostConnections.FIRST_BYTE.toMillis();
            super.setSoTimeout(on ? (rmi > 0 ? Math.min(rmi, first) : first) : rmi);
        }

        @Override
        public synchronized void close() throws IOException {
            if (closed.compareAndSet(false, true)) {
                counters.open.decrementAndGet();
                if (connection != null) {
                    connections.closed(connection);
                }
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
        public synchronized InputStream getInputStream() throws IOException {
            if (in == null) {
                in = new ReadAhead(this, super.getInputStream(), counters, readSpinNanos);
            }
            return in;
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

    /**
     * Spins (yielding the processor to any other runnable thread) until the stream has bytes to
     * read or {@code nanos} have passed: a call that comes within the spin is read without the
     * tens of microseconds a blocked thread takes to wake.
     */
    public static void spinUntilReadable(InputStream in, long nanos) throws IOException {
        if (in.available() > 0) {
            return;
        }
        long until = System.nanoTime() + nanos;
        while (in.available() == 0 && System.nanoTime() - until < 0) {
            Thread.yield();
        }
    }

    /** How much an accepted connection reads from its socket at once. */
    static final int READ_AHEAD_BYTES = 64 * 1024;

    /**
     * An accepted connection's input: reads from the socket up to {@value #READ_AHEAD_BYTES} bytes
     * at a time, where RMI's buffered stream asks for 8 KiB (a large call took a system call per
     * 8 KiB), counts the bytes, and, with a read spin, spins for the next call before it blocks.
     * One per connection; RMI reads it from one thread at a time.
     */
    private static final class ReadAhead extends InputStream {
        private final CountingSocket owner;
        private final InputStream socket;
        private final Counters counters;
        private final long readSpinNanos;
        private final byte[] ahead = new byte[READ_AHEAD_BYTES];
        private int pos;
        private int limit;
        private volatile boolean sawByte;

        ReadAhead(CountingSocket owner, InputStream socket, Counters counters, long readSpinNanos) {
            this.owner = owner;
            this.socket = socket;
            this.counters = counters;
            this.readSpinNanos = readSpinNanos;
        }

        /** @return whether there are bytes to serve (false: the end of the stream) */
        private boolean fill() throws IOException {
            if (pos < limit) {
                return true;
            }
            HostConnections.Connection c = owner.connection;
            if (c != null) {
                // RMI reads and serves a connection's calls on one thread: the filter and the endpoint ask it which connection
                owner.connections.reading(c);
            }
            if (!sawByte) {
                return fillFirst(c);
            }
            if (readSpinNanos > 0) {
                spinUntilReadable(socket, readSpinNanos);
            }
            int n = socket.read(ahead, 0, ahead.length);
            if (n <= 0) {
                return false;
            }
            counters.in.add(n);
            pos = 0;
            limit = n;
            return true;
        }

        /** The connection's first read: a connection that sends nothing within the first-byte deadline is closed. */
        private boolean fillFirst(HostConnections.Connection c) throws IOException {
            owner.firstByteDeadline(true);
            int n;
            try {
                n = socket.read(ahead, 0, ahead.length);
            } catch (java.net.SocketTimeoutException e) {
                if (c != null) {
                    owner.connections.silent(c);
                }
                owner.close();
                throw e;
            }
            if (n <= 0) {
                return false;
            }
            sawByte = true;
            owner.firstByteDeadline(false);
            counters.in.add(n);
            pos = 0;
            limit = n;
            return true;
        }

        @Override
        public int read() throws IOException {
            return fill() ? ahead[pos++] & 0xFF : -1;
        }

        @Override
        public int read(byte[] buf, int off, int len) throws IOException {
            java.util.Objects.checkFromIndexSize(off, len, buf.length);
            if (len == 0) {
                return 0;
            }
            if (!fill()) {
                return -1;
            }
            int n = Math.min(len, limit - pos);
            System.arraycopy(ahead, pos, buf, off, n);
            pos += n;
            return n;
        }

        /** The bytes read ahead, or if none, the socket's (a system call; RMI's buffered stream asks after every short read). */
        @Override
        public int available() throws IOException {
            return limit > pos ? limit - pos : socket.available();
        }

        @Override
        public void close() throws IOException {
            socket.close();
        }
    }

    /** RMI's transport: the byte a client sends to ask whether a reused connection is alive, and the answer. */
    public static final int RMI_PING = 0x52;
    public static final int RMI_PING_ACK = 0x53;
    /** A connection that carried an answer this recently is taken to be alive without asking. */
    static final long WARM_NANOS = 100_000_000L;
    /**
     * The most a client connection collects of a call before writing it to the socket: RMI writes
     * a call in 8 KiB pieces (its buffered stream's size), each a system call and a TCP segment of
     * its own on loopback; collected until RMI flushes, a call of up to this size goes out in one
     * write. Larger calls are written through in pieces of this size.
     */
    public static final int COALESCE_MAX_BYTES = 2 << 20;

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
    public static final class WarmSocket extends Socket {
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
        public long pingsAnswered() {
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
                    /** What RMI wrote since its last flush, up to {@link #COALESCE_MAX_BYTES}: sent in one write at the flush. */
                    private byte[] pending = new byte[8192];
                    private int n;

                    @Override
                    public void write(int b) throws IOException {
                        write(new byte[] {(byte) b}, 0, 1);
                    }

                    @Override
                    public void write(byte[] buf, int off, int len) throws IOException {
                        if (n == 0 && len == 1 && buf[off] == RMI_PING && answeredSinceWrite && System.nanoTime() - lastAnswer < WARM_NANOS) {
                            answeredSinceWrite = false;
                            ackPending = true;
                            pingsAnswered.increment();
                            return;
                        }
                        answeredSinceWrite = false;
                        if (n + len > pending.length) {
                            if (n + len > COALESCE_MAX_BYTES) {
                                sendPending();
                                out.write(buf, off, len);
                                return;
                            }
                            pending = java.util.Arrays.copyOf(pending, Math.min(COALESCE_MAX_BYTES, Math.max(n + len, 2 * pending.length)));
                        }
                        System.arraycopy(buf, off, pending, n, len);
                        n += len;
                    }

                    private void sendPending() throws IOException {
                        if (n > 0) {
                            out.write(pending, 0, n);
                            n = 0;
                        }
                    }

                    @Override
                    public void flush() throws IOException {
                        sendPending();
                        out.flush();
                    }
                };
            }
            return out;
        }
    }

    /** The connecting side, serializable because it travels in the host's stub. */
    public static final class Client implements RMIClientSocketFactory, Serializable {
        private static final long serialVersionUID = 1L;
        private final String host;
        private final boolean tls;
        private final int timeoutMillis;

        public Client(String host, boolean tls, int timeoutMillis) {
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
