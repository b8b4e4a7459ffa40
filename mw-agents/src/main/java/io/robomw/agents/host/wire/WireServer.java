package io.robomw.agents.host.wire;

import io.robomw.agents.host.core.Calls;
import io.robomw.agents.host.protocol.Reply;
import io.robomw.agents.host.rmi.HostEndpoint;
import io.robomw.agents.host.rmi.HostSockets;
import io.robomw.agents.host.security.FrameTag;
import io.robomw.agents.host.visit.SpinHandoff;
import io.robomw.agents.net.OwnerThreads;
import io.robomw.api.spi.FailurePolicy;
import io.robomw.agents.net.ThrottledWarnings;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import javax.net.ssl.SSLContext;
import javax.net.ssl.SSLSocket;
import java.io.BufferedOutputStream;
import java.io.IOException;
import java.io.InputStream;
import java.net.InetAddress;
import java.net.InetSocketAddress;
import java.net.Socket;
import java.net.SocketTimeoutException;
import java.nio.channels.ClosedChannelException;
import java.nio.channels.ServerSocketChannel;
import java.nio.channels.SocketChannel;
import java.time.Duration;
import java.util.Set;
import java.util.concurrent.ConcurrentHashMap;
import java.util.concurrent.ThreadFactory;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicInteger;
import java.util.concurrent.atomic.LongAdder;

/**
 * A host's agent wire (protocol version 3, {@link WireFrames}): listens on a port of its own, on the
 * host's bind address, and serves each connection on a thread of its own, which reads a frame,
 * checks it, hands a transfer to the host as RMI's connection thread did ({@link Calls}: the agent
 * goes to a runner through {@link SpinHandoff}), and writes the reply on the same connection.
 *
 * <p><b>Limits.</b> At most {@link Limits#maxConnections} connections at once (one more is closed as
 * soon as it is accepted, before any TLS handshake); a connection's first frame must be a HELLO
 * that verifies, within {@link Limits#firstFrame} of the accept (the TLS handshake included), and
 * until a frame on it has verified, no frame may be larger than
 * {@link HostEndpoint#UNPROVEN_MAX_BYTES} (so nobody without the session key makes the host
 * allocate more); after that a frame's body may be as large as the largest agent state plus
 * 1 MiB. A connection idle for {@link Limits#idle} is closed, and a frame whose header has
 * arrived must be complete within {@link Limits#frame}. Every refused frame is logged (one line a
 * second at most) naming the peer and what was wrong, counted in the host's refusals, answered
 * with FRAME_REFUSED where the connection can still carry it, and its connection closed; the
 * server goes on serving the others.
 */
public final class WireServer implements AutoCloseable {

    private static final Logger LOG = LoggerFactory.getLogger(WireServer.class);
    /** How long a refused connection is read (and what it sends dropped) before it is closed, so the refusal reaches the peer. */
    static final int LINGER_MILLIS = 200;
    /** The most bytes read and dropped from a refused connection before it is closed. */
    static final int LINGER_MAX_BYTES = 64 * 1024;

    /**
     * The agent wire's limits.
     *
     * @param maxConnections the most connections open at once
     * @param firstFrame     how long after the accept the first frame (HELLO) must have arrived
     * @param idle           how long a connection may wait for its next frame
     * @param frame          how long a frame may take to arrive once its header began
     * @param maxBody        the largest body of a frame from a proved peer
     */
    public record Limits(int maxConnections, Duration firstFrame, Duration idle, Duration frame, long maxBody) {

        /** The most connections a host's agent wire keeps open, as its RMI endpoint ({@link HostSockets#MAX_CONNECTIONS}). */
        static final int MAX_CONNECTIONS = HostSockets.MAX_CONNECTIONS;

        /** @return the limits of a host whose agent state may be {@code maxStateBytes} long and whose calls may take {@code callTimeout} */
        public static Limits of(long maxStateBytes, Duration callTimeout) {
            long maxBody = Math.min(Integer.MAX_VALUE - 64, maxStateBytes + (1 << 20));
            return new Limits(MAX_CONNECTIONS, Duration.ofSeconds(10), Duration.ofMinutes(2), callTimeout, maxBody);
        }
    }

    private final HostEndpoint endpoint;
    private final String hostName;
    private final SSLContext tls;
    private final Limits limits;
    private final ServerSocketChannel server;
    private final Thread acceptor;
    private final Set<Connection> connections = ConcurrentHashMap.newKeySet();
    private final AtomicInteger threads = new AtomicInteger();
    private final LongAdder refusedConnections = new LongAdder();
    private final LongAdder served = new LongAdder();
    private volatile HostSockets.Counters counters = new HostSockets.Counters();
    private final ThrottledWarnings refusals = new ThrottledWarnings(LOG, Duration.ofSeconds(1));
    private volatile boolean closing;
    private volatile Throwable failure;
    private final FailurePolicy failures;
    private volatile ThreadFactory connectionThreads;
    /** How long a connection thread spins for the next frame before it blocks reading (0: never; plain connections only). */
    private volatile long readSpinNanos;
    private volatile java.util.concurrent.Executor tagger;

    /**
     * Binds and starts accepting.
     *
     * @param endpoint the host's endpoint: its sessions, and what it does with a verified call
     * @param bind     the address to listen on
     * @param port     the port, 0 for any free one
     * @param tls      the host's TLS context (client certificates required), or {@code null}
     * @param limits   the limits
     * @param failures where what its accept and connection threads catch goes
     * @throws IOException if the port cannot be bound
     */
    public WireServer(HostEndpoint endpoint, InetAddress bind, int port, SSLContext tls, Limits limits, FailurePolicy failures) throws IOException {
        this.endpoint = endpoint;
        this.failures = failures;
        this.connectionThreads = r -> OwnerThreads.thread("agent-wire-" + endpoint.hostName(), r, failures);
        this.hostName = endpoint.hostName();
        this.tls = tls;
        this.limits = limits;
        this.server = ServerSocketChannel.open();
        try {
            server.bind(new InetSocketAddress(bind, port), 128);
        } catch (IOException e) {
            server.close();
            throw new IOException("agent host " + hostName + " cannot listen for agent transfers on " + bind.getHostAddress() + ":" + port + ": "
                    + e.getMessage(), e);
        }
        this.acceptor = new Thread(this::accept, "agent-wire-accept-" + hostName);
        acceptor.setDaemon(true);
        acceptor.start(); // accept() catches whatever ends it, in one place
    }

    /** @param c where the frames' bytes are counted (the host's, with its RMI endpoint's) */
    public void countBytesIn(HostSockets.Counters c) {
        this.counters = c;
    }

    /** @param spin how long a connection thread spins (yielding) for the next frame before it blocks reading; zero never */
    public void readSpin(Duration spin) {
        this.readSpinNanos = spin.toNanos();
    }

    /** @param tagger computes the tags of large replies while they are written ({@link WireWriter}) */
    public void tagger(java.util.concurrent.Executor tagger) {
        this.tagger = tagger;
    }

    /** @return the port it listens on */
    public int port() {
        return server.socket().getLocalPort();
    }

    /** @return the connections open now */
    public int open() {
        return connections.size();
    }

    /** @return how many frames other than HELLO it served (counted as each is handed to the host) */
    public long served() {
        return served.sum();
    }

    /** @return how many connections were closed at once for being over the limit */
    long refusedConnections() {
        return refusedConnections.sum();
    }

    private void accept() {
        try {
            acceptUntilClosed();
        } catch (Throwable t) {
            failure = t;
            // Ends cleanly: new peers are offered no wire, and peers that have its port find it
            // refused at once and send their agents over RMI (docs/agents.md, "Versions").
            endpoint.wirePort(0);
            closeQuietly(server);
            LOG.warn("host {}: the agent wire's accept thread failed ({}); the wire stops listening and peers send their agents over RMI", hostName,
                    t.toString());
            failures.died(Thread.currentThread().getName(), t);
        }
    }

    private void acceptUntilClosed() {
        while (!closing) {
            SocketChannel c;
            try {
                c = server.accept();
            } catch (ClosedChannelException e) {
                return;
            } catch (IOException | RuntimeException e) {
                if (!closing) {
                    refusals.warn("host {}: the agent wire failed to accept a connection: {}", hostName, e.toString());
                }
                continue;
            }
            if (connections.size() >= limits.maxConnections()) {
                refusedConnections.increment();
                endpoint.countRefused();
                refusals.warn("host {}: closed an agent wire connection from {}: {} are open already, the most it keeps", hostName, remote(c),
                        limits.maxConnections());
                closeQuietly(c);
                continue;
            }
            Connection conn = new Connection(c, System.nanoTime());
            connections.add(conn);
            try {
                Thread t = connectionThreads.newThread(conn::serve);
                t.setName("agent-wire-" + hostName + "-" + threads.incrementAndGet());
                t.setDaemon(true);
                conn.thread = t;
                t.start();
            } catch (Throwable t) {
                connections.remove(conn);
                closeQuietly(c);
                throw t;
            }
        }
    }

    /** @return what ended the accept thread other than {@link #close}, or {@code null} */
    public Throwable failure() {
        return failure;
    }

    /** @param factory makes the threads that serve connections (for tests: one that fails) */
    public void connectionThreads(ThreadFactory factory) {
        this.connectionThreads = factory;
    }

    private static String remote(SocketChannel c) {
        try {
            InetSocketAddress a = (InetSocketAddress) c.getRemoteAddress();
            return a == null ? "?" : a.getAddress().getHostAddress() + ":" + a.getPort();
        } catch (IOException e) {
            return "?";
        }
    }

    private static void closeQuietly(AutoCloseable c) {
        try {
            c.close();
        } catch (Exception ignored) {
            // closing anyway
        }
    }

    /**
     * Stops accepting, closes the connections that wait for a frame, lets those serving one finish
     * (their reply goes out) for up to {@code grace}, then closes the rest.
     */
    public void close(Duration grace) {
        closing = true;
        closeQuietly(server);
        for (Connection c : connections) {
            if (!c.busy) {
                closeQuietly(c.channel);
            }
        }
        long deadline = System.nanoTime() + grace.toNanos();
        for (Connection c : connections) {
            Thread t = c.thread;
            long left = deadline - System.nanoTime();
            try {
                if (t != null && left > 0) {
                    t.join(Math.max(1, TimeUnit.NANOSECONDS.toMillis(left)));
                }
            } catch (InterruptedException e) {
                Thread.currentThread().interrupt();
                break;
            }
            closeQuietly(c.channel);
        }
        try {
            acceptor.join(1000);
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
        }
    }

    @Override
    public void close() {
        close(Duration.ofSeconds(1));
    }

    /** One connection: its socket, its reader and writer, the session it carries. */
    private final class Connection {
        final SocketChannel channel;
        final long acceptedAt;
        final String address;
        final FrameTag checking = new FrameTag();
        volatile Thread thread;
        volatile boolean busy;
        HostEndpoint.Peer peer;
        long lastSeq = Long.MIN_VALUE;

        Connection(SocketChannel channel, long acceptedAt) {
            this.channel = channel;
            this.acceptedAt = acceptedAt;
            this.address = remote(channel);
        }

        /** @return the peer as the log names it */
        String who() {
            return peer == null ? address + " (no session proved yet)" : "peer '" + peer.name() + "' at " + address;
        }

        void serve() {
            WireWriter writer = null;
            try {
                channel.socket().setTcpNoDelay(true);
                Socket socket;
                InputStream in;
                if (tls != null) {
                    SSLSocket ssl = (SSLSocket) tls.getSocketFactory().createSocket(channel.socket(), address, channel.socket().getPort(), true);
                    ssl.setUseClientMode(false);
                    ssl.setNeedClientAuth(true);
                    socket = ssl;
                    in = ssl.getInputStream();
                    writer = new WireWriter(WireWriter.of(new BufferedOutputStream(ssl.getOutputStream(), 32 * 1024)), tagger);
                } else {
                    socket = channel.socket();
                    in = socket.getInputStream();
                    writer = new WireWriter(WireWriter.of(channel), tagger);
                }
                WireReader reader = new WireReader(in, socket);
                loop(reader, writer, socket, in);
            } catch (WireFrames.FrameRefused e) {
                refuse(writer, e.getMessage());
            } catch (SocketTimeoutException e) {
                refuse(writer, e.getMessage());
            } catch (IOException e) {
                if (!closing) {
                    LOG.debug("host {}: agent wire connection of {} ended: {}", hostName, who(), e.toString());
                }
            } catch (Throwable t) {
                // this connection ends; the wire serves on (and an error no thread survives ends this thread too)
                LOG.warn("host {}: agent wire connection of {} failed ({}); closing it", hostName, who(), t.toString());
                failures.surviveOrRethrow(Thread.currentThread().getName(), t);
            } finally {
                busy = false;
                closeQuietly(channel);
                connections.remove(this);
            }
        }

        /** Logs and counts a refused frame, tells the peer why if it can, and leaves the connection to be closed. */
        private void refuse(WireWriter writer, String why) {
            endpoint.countRefused();
            String text = "host " + hostName + " refused an agent wire frame from " + who() + ": " + why;
            refusals.warn("{}; closing the connection", text);
            if (writer != null && channel.isOpen()) {
                try {
                    writer.writeUntagged(WireFrames.STATUS_FRAME_REFUSED, peer == null ? 0 : peer.session().id, 0, WireFrames.reason(text));
                    lingerForTheReason();
                } catch (IOException | RuntimeException ignored) {
                    // the connection is closed next either way
                }
            }
        }

        /**
         * Closes the host's side for writing and reads what the peer still sends, a bounded amount
         * for a short time: a socket closed with unread bytes sends a reset, which could destroy the
         * refusal before the peer reads it.
         */
        private void lingerForTheReason() throws IOException {
            if (tls != null) {
                return; // a TLS socket cannot half-close; its close_notify goes out with the close
            }
            Socket s = channel.socket();
            s.shutdownOutput();
            s.setSoTimeout(LINGER_MILLIS);
            InputStream in = s.getInputStream();
            byte[] discard = new byte[8192];
            long deadline = System.nanoTime() + LINGER_MILLIS * 1_000_000L;
            int total = 0;
            try {
                int n;
                while (total < LINGER_MAX_BYTES && System.nanoTime() - deadline < 0 && (n = in.read(discard)) >= 0) {
                    total += n;
                }
            } catch (SocketTimeoutException done) {
                // the peer sends nothing more
            }
        }

        private void loop(WireReader reader, WireWriter writer, Socket socket, InputStream in) throws IOException {
            long firstDeadline = acceptedAt + limits.firstFrame().toNanos();
            while (!closing) {
                if (peer == null) {
                    reader.deadline(firstDeadline, "no verified first frame within " + limits.firstFrame().toMillis() + " ms of connecting");
                } else {
                    reader.deadline(0, null);
                    if (!reader.buffered()) {
                        socket.setSoTimeout((int) Math.min(Integer.MAX_VALUE, limits.idle().toMillis()));
                        long spin = readSpinNanos;
                        if (spin > 0 && tls == null) {
                            HostSockets.spinUntilReadable(in, spin);
                        }
                    }
                }
                WireFrames.Header h;
                try {
                    h = reader.header();
                } catch (SocketTimeoutException e) {
                    if (peer != null) {
                        LOG.debug("host {}: closing the agent wire connection of {}: idle for {}", hostName, who(), limits.idle());
                        return;
                    }
                    throw e;
                }
                if (h == null) {
                    return;
                }
                busy = true;
                if (peer != null) {
                    reader.deadline(System.nanoTime() + limits.frame().toNanos(), "a frame took longer than " + limits.frame().toMillis() + " ms to arrive");
                }
                serveFrame(h, reader, writer);
                busy = false;
            }
        }

        private void serveFrame(WireFrames.Header h, WireReader reader, WireWriter writer) throws IOException {
            if (h.version() != WireFrames.VERSION) {
                throw new WireFrames.FrameRefused("unknown agent wire protocol version " + h.version() + " (this host speaks " + WireFrames.VERSION + ")");
            }
            HostEndpoint.Peer p = endpoint.peer(h.session());
            if (p == null) {
                // Not secret: the host forgot the session (it restarted, or keeps a bounded number); the peer authenticates again.
                writer.writeUntagged(Reply.Status.UNKNOWN_SESSION.code(), h.session(), h.seq(), new byte[0]);
                throw new java.io.EOFException("unknown session");
            }
            if (peer != null && peer.session() != p.session()) {
                throw new WireFrames.FrameRefused("a frame of session " + Long.toHexString(h.session()) + " on a connection of another session");
            }
            if (p.session().frameKey == null) {
                throw new WireFrames.FrameRefused("its session's authenticator is not AES-256-GCM, which the agent wire needs");
            }
            long max = peer == null ? HostEndpoint.UNPROVEN_MAX_BYTES - WireFrames.HEADER - WireFrames.TAG : limits.maxBody();
            if (h.length() > max) {
                throw new WireFrames.FrameRefused("a frame announces a body of " + h.length() + " bytes; at most " + max + " are read"
                        + (peer == null ? " before a frame on the connection has verified" : ""));
            }
            if (peer == null && h.code() != WireFrames.OP_HELLO) {
                throw new WireFrames.FrameRefused("the first frame on a connection must be HELLO (" + WireFrames.OP_HELLO + "), not code " + h.code());
            }
            if (h.seq() <= lastSeq) {
                throw new WireFrames.FrameRefused("sequence number " + h.seq() + " is not above the connection's last, " + lastSeq + " (replayed or reordered)");
            }
            if (p.session().servedBefore(h.seq())) {
                throw new WireFrames.FrameRefused("sequence number " + h.seq() + " was served before on its session (replayed)");
            }
            checking.start(p.session().frameKey, WireFrames.DIRECTION_REQUEST, h.seq(), true);
            byte[] f = reader.frame(h, checking);
            int frameLength = (int) h.frameLength();
            if (!checking.check(f, frameLength - WireFrames.TAG)) {
                throw new WireFrames.FrameRefused("wrong tag: not sealed with the key of session " + Long.toHexString(h.session())
                        + " (a changed byte, another key, or a forged session id)");
            }
            if (!p.session().firstTime(h.seq())) {
                throw new WireFrames.FrameRefused("sequence number " + h.seq() + " was served before on its session (replayed)");
            }
            boolean first = peer == null;
            peer = p;
            lastSeq = h.seq();
            Reply r;
            if (h.code() == WireFrames.OP_HELLO) {
                if (first) {
                    LOG.debug("host {}: agent wire connection from {}", hostName, who());
                }
                r = Reply.ok();
            } else {
                served.increment();
                r = endpoint.serve(p, h.code(), f, WireFrames.HEADER, (int) h.length(), address);
            }
            writer.write(p.session().frameKey, WireFrames.DIRECTION_REPLY, r.status().code(), h.session(), h.seq(), r.body(), 0, r.body().length);
            HostSockets.Counters c = counters;
            c.in.add(frameLength);
            c.out.add(WireFrames.HEADER + r.body().length + WireFrames.TAG);
        }
    }
}
