package io.robomw.agents.messaging.tcp;

import io.robomw.agents.messaging.Address;
import io.robomw.agents.messaging.DropReason;
import io.robomw.agents.messaging.PeerLimits;
import io.robomw.agents.messaging.frame.FrameException;
import io.robomw.agents.messaging.io.FrameStreamReader;
import io.robomw.agents.messaging.io.OutboundBuffer;
import io.robomw.agents.messaging.spi.Link;
import io.robomw.agents.messaging.spi.TransportContext;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import javax.net.ssl.SSLSocket;
import java.io.IOException;
import java.io.InputStream;
import java.io.OutputStream;
import java.net.Socket;
import java.net.SocketException;
import java.net.SocketTimeoutException;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicBoolean;
import java.util.concurrent.atomic.AtomicLong;

/**
 * One TCP connection, accepted or opened: a reader thread that frames the stream and hands each
 * frame to the node (listeners run on it), and an {@link OutboundBuffer} with its writer thread.
 * Garbage, an oversized length, a cut-off frame, or no whole frame within the first-frame or
 * idle timeout ({@link PeerLimits}) end this connection only (counted and logged by the node); the
 * endpoint keeps accepting others. Its read buffer grows only with the bytes that arrive. The
 * timeouts of a plain connection are kept by its transport's {@link ConnectionTimeouts} (the
 * reader blocks in {@code read} without a socket timeout); a TLS connection's by its socket's read
 * timeout.
 */
final class TcpConnection implements Link, ConnectionTimeouts.Watched {

    private static final Logger LOG = LoggerFactory.getLogger(TcpConnection.class);
    private static final long DRAIN_NANOS = 1_000_000_000L;

    private final Socket socket;
    private final Address address;
    private final String peer;
    private final TransportContext context;
    private final OutboundBuffer outbound;
    private final InputStream in;
    private final OutputStream out;
    private final AtomicBoolean closed = new AtomicBoolean();
    private final java.util.List<AutoCloseable> registry;
    private final Runnable onClose;
    /** Enforces a plain connection's timeouts; {@code null} for TLS, whose reads time out themselves. */
    private final ConnectionTimeouts timeouts;
    /** Twice the whole frames read, plus one while the node handles the last; written by the reader only. */
    private final AtomicLong progress = new AtomicLong();
    /** Why the timer closed it, or {@code null}. */
    private volatile String timedOut;
    private volatile Thread reader;

    TcpConnection(Socket socket, Address address, String peer, TransportContext context, java.util.List<AutoCloseable> registry,
                  ConnectionTimeouts timeouts) throws IOException {
        this(socket, address, peer, context, registry, timeouts, () -> { });
    }

    /**
     * @param timeouts the transport's timer for plain connections' timeouts (not used for TLS)
     * @param onClose  run once when it closes (an acceptor counts its connections)
     */
    TcpConnection(Socket socket, Address address, String peer, TransportContext context, java.util.List<AutoCloseable> registry,
                  ConnectionTimeouts timeouts, Runnable onClose) throws IOException {
        this.onClose = onClose;
        this.timeouts = socket instanceof SSLSocket ? null : timeouts;
        this.registry = registry;
        this.socket = socket;
        this.address = address;
        this.peer = peer;
        this.context = context;
        socket.setTcpNoDelay(true);
        socket.setKeepAlive(true);
        this.in = socket.getInputStream();
        this.out = socket.getOutputStream();
        this.outbound = new OutboundBuffer(peer, context.settings().outboundBufferBytes(), context.settings().sendTimeout().toNanos());
    }

    void start() {
        registry.add(this);
        // Known to the node before any thread runs: a peer that connects and drops at once makes
        // the reader close this connection, and the node must already know it to forget it.
        context.opened(this);
        if (timeouts != null) {
            timeouts.watch(this);
        }
        String role = "tcp-" + (socket.getLocalPort()) + "-" + socket.getPort();
        outbound.startWriter((b, o, l) -> {
            out.write(b, o, l);
            out.flush();
        }, context.threads(role + "-write"), e -> fail("write failed: " + e.getMessage()));
        Thread t = context.threads(role + "-read").newThread(this::readLoop);
        reader = t;
        t.start();
    }

    @Override
    public Address address() {
        return address;
    }

    @Override
    public String peer() {
        return peer;
    }

    @Override
    public void send(byte[] frame) throws IOException {
        outbound.send(frame);
    }

    @Override
    public boolean isOpen() {
        return !closed.get();
    }

    @Override
    public boolean isConnection() {
        return true;
    }

    @Override
    public boolean deliversOn(Thread thread) {
        return thread == reader;
    }

    @Override
    public boolean keepAlive(byte[] frame, long nowNanos, long silentNanos) {
        return outbound.sendIfSilent(frame, nowNanos, silentNanos);
    }

    @Override
    public boolean stuck(long nowNanos, long limitNanos) {
        return outbound.stuck(nowNanos, limitNanos);
    }

    /** Closes after writing what is waiting (for at most a second), unless called by the reader. */
    @Override
    public void close() {
        if (closed.compareAndSet(false, true)) {
            outbound.close();
            if (Thread.currentThread() != reader) {
                outbound.awaitDrained(DRAIN_NANOS);
            }
            try {
                socket.close();
            } catch (IOException e) {
                LOG.debug("closing {}: {}", peer, e.toString());
            }
            registry.remove(this);
            if (timeouts != null) {
                timeouts.forget(this);
            }
            onClose.run();
            context.closed(this);
        }
    }

    @Override
    public long progress() {
        return progress.get();
    }

    /** Called by the timer: records why and closes the socket, which ends the reader's blocked read. */
    @Override
    public void timedOut(boolean firstFrame, long limitNanos) {
        timedOut = "no whole frame within " + TimeUnit.NANOSECONDS.toMillis(limitNanos) + " ms "
                + (firstFrame ? "since it opened" : "since its last whole frame");
        try {
            socket.close();
        } catch (IOException e) {
            LOG.debug("closing {}: {}", peer, e.toString());
        }
    }

    @Override
    public String toString() {
        return "TcpConnection[" + peer + "]";
    }

    private void readLoop() {
        PeerLimits limits = context.settings().limits();
        FrameStreamReader frames = timeouts != null ? new FrameStreamReader(in, context.settings().maxFrameSize())
                : new FrameStreamReader(in, context.settings().maxFrameSize(),
                new FrameStreamReader.Timeouts(socket::setSoTimeout, limits.firstFrameTimeout().toNanos(), limits.idleTimeout().toNanos()));
        try {
            if (socket instanceof SSLSocket ssl) {
                socket.setSoTimeout((int) limits.firstFrameTimeout().toMillis());
                ssl.startHandshake();
            }
            int length;
            long p = 0;
            while ((length = frames.next()) >= 0) {
                progress.lazySet(++p); // odd: the node has the frame (plain stores: the timer reads them a few times per timeout)
                context.onFrame(frames.buffer(), frames.offset(), length, this);
                progress.lazySet(++p);
            }
        } catch (FrameException e) {
            context.dropped(e.reason(), peer, e.getMessage() + "; closing this connection");
        } catch (SocketTimeoutException e) {
            if (!closed.get()) {
                context.dropped(DropReason.TIMED_OUT, peer, "no TLS handshake within " + limits.firstFrameTimeout().toMillis()
                        + " ms; closing this connection");
            }
        } catch (SocketException e) {
            String why = timedOut;
            if (why != null) {
                context.dropped(DropReason.TIMED_OUT, peer, why + " (" + frames.arrived() + "); closing this connection");
            } else if (!closed.get()) {
                LOG.debug("node '{}': connection {} ended: {}", context.nodeName(), peer, e.toString());
            }
        } catch (IOException e) {
            if (!closed.get()) {
                LOG.warn("node '{}': connection {} failed: {}", context.nodeName(), peer, e.toString());
            }
        } catch (RuntimeException | LinkageError | AssertionError | StackOverflowError e) {
            LOG.error("node '{}': reading from {} failed ({}); closing this connection, the node goes on", context.nodeName(), peer, e.toString(), e);
        } finally {
            close();
        }
    }

    private void fail(String why) {
        if (!closed.get()) {
            LOG.warn("node '{}': connection {}: {}", context.nodeName(), peer, why);
        }
        close();
    }
}
