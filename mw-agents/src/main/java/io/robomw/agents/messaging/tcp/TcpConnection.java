package io.robomw.agents.messaging.tcp;

import io.robomw.agents.messaging.Address;
import io.robomw.agents.messaging.DropReason;
import io.robomw.agents.messaging.PeerLimits;
import io.robomw.agents.messaging.frame.FrameCodec;
import io.robomw.agents.messaging.frame.FrameException;
import io.robomw.agents.messaging.frame.FrameKind;
import io.robomw.agents.messaging.io.FrameStreamReader;
import io.robomw.agents.messaging.io.OutboundBuffer;
import io.robomw.agents.messaging.spi.Link;
import io.robomw.agents.messaging.spi.Publication;
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
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicBoolean;
import java.util.concurrent.atomic.AtomicLong;
import java.util.concurrent.locks.LockSupport;

/**
 * One TCP connection, accepted or opened: a reader thread that frames the stream and hands each
 * frame to the node (listeners run on it), and an {@link OutboundBuffer} with its writer thread.
 * Garbage, an oversized length, a cut-off frame, or no whole frame within the first-frame or
 * idle timeout ({@link PeerLimits}) end this connection only (counted and logged by the node); the
 * endpoint keeps accepting others. Its read buffer grows only with the bytes that arrive. The
 * timeouts of a plain connection are kept by its transport's {@link ConnectionTimeouts} (the
 * reader blocks in {@code read} without a socket timeout); a TLS connection's by its socket's read
 * timeout.
 *
 * <p>A plain connection is read by one thread at a time, its <em>leader</em> ({@link ReadLeadership}):
 * the reader thread, or a thread waiting in {@code waitForReply} for a reply on it, which then reads
 * the socket itself (with a read timeout bounded by its deadline) and handles replies, keep-alives
 * and subscriptions as the reader thread would, so its reply reaches it without a thread hand-off.
 * A waiting thread never runs listeners: the first message or publication it reads it leaves, not
 * handled, to the reader thread, which handles it and everything after it in the order they came.
 * TLS connections are read by their reader thread only.
 *
 * <p>A plain connection to a peer on the loopback interface may carry large publications through
 * shared memory ({@link SharedMemoryLink}); publications through it, and the offer of it, are
 * handled by the reader thread only, in order with the connection's other frames.
 */
final class TcpConnection implements Link, ConnectionTimeouts.Watched {

    private static final Logger LOG = LoggerFactory.getLogger(TcpConnection.class);
    private static final long DRAIN_NANOS = 1_000_000_000L;
    /**
     * The longest one read of a waiting thread blocks: then it looks at its interrupt status (a
     * socket read does not end on {@code interrupt}) and reads again.
     */
    private static final int WAIT_SLICE_MILLIS = 20;
    /**
     * How often the reader thread looks whether leadership is free while it does not lead: the
     * longest a frame that arrives just after a waiting thread stopped reading waits to be read.
     */
    static final long READER_LOOKS_NANOS = 1_000_000;

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
    private final FrameStreamReader frames;
    private final SharedMemoryLink shared;
    /** Whether threads waiting for a reply may read it (plain TCP; TLS keeps its reader thread). */
    private final boolean leadable;
    private final ReadLeadership leadership = new ReadLeadership();
    // The leader's state (handed over with leadership):
    /** The length of the current frame if it was read and left to the reader thread, else -1. */
    private int undispatched = -1;
    /** The socket's read timeout as last set, in ms (0: none). */
    private int readTimeoutMillis;

    TcpConnection(Socket socket, Address address, String peer, TransportContext context, java.util.List<AutoCloseable> registry,
                  ConnectionTimeouts timeouts, java.util.function.Supplier<io.robomw.agents.messaging.shm.SharedSegment> segments) throws IOException {
        this(socket, address, peer, context, registry, timeouts, segments, () -> { });
    }

    /**
     * @param timeouts the transport's timer for plain connections' timeouts (not used for TLS)
     * @param segments the transport's shared-memory segment, made on first use ({@code null} if it cannot be)
     * @param onClose  run once when it closes (an acceptor counts its connections)
     */
    TcpConnection(Socket socket, Address address, String peer, TransportContext context, java.util.List<AutoCloseable> registry,
                  ConnectionTimeouts timeouts, java.util.function.Supplier<io.robomw.agents.messaging.shm.SharedSegment> segments,
                  Runnable onClose) throws IOException {
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
        this.leadable = this.timeouts != null;
        PeerLimits limits = context.settings().limits();
        this.frames = leadable ? new FrameStreamReader(in, context.settings().maxFrameSize())
                : new FrameStreamReader(in, context.settings().maxFrameSize(),
                new FrameStreamReader.Timeouts(socket::setSoTimeout, limits.firstFrameTimeout().toNanos(), limits.idleTimeout().toNanos()));
        boolean sharable = context.settings().sharedMemory().enabled() && !(socket instanceof SSLSocket) && context.settings().tls() == null
                && SharedMemoryOption.allows(address) && socket.getInetAddress().isLoopbackAddress();
        this.shared = new SharedMemoryLink(peer, context, sharable, segments,
                () -> fail("it has not copied a shared-memory payload within the send timeout; it is not reading"));
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
        leadership.reader(t);
        t.start();
        byte[] ask = shared.ask();
        if (ask != null) {
            try {
                outbound.send(ask);
            } catch (IOException e) {
                fail("cannot ask for shared memory: " + e.getMessage());
            }
        }
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
        if (!shared.trySend(frame, outbound)) {
            outbound.send(frame);
        }
    }

    @Override
    public void sendPublication(Publication publication) throws IOException {
        if (!publication.travelsApart()) {
            send(publication.frame());
        } else if (!shared.trySend(publication, outbound)) {
            // over TCP, and not through trySend(frame): were the peer's acceptance to arrive in between, the same
            // publication would go into the segment under a second identity, written twice for its subscribers
            outbound.send(publication.frame());
        }
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
            outbound.close(); // first: a publisher waiting for room in it gives up, and with it the segment's lock
            shared.closePublisher();
            Thread me = Thread.currentThread();
            if (me != reader && !leadership.leads(me)) {
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
            leadership.close();
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
        Thread me = Thread.currentThread();
        try {
            if (socket instanceof SSLSocket ssl) {
                socket.setSoTimeout((int) limits.firstFrameTimeout().toMillis());
                ssl.startHandshake();
            }
            while (!closed.get()) {
                if (!leadership.tryLead(me)) {
                    LockSupport.parkNanos(this, READER_LOOKS_NANOS);
                    continue;
                }
                if (!leadAsReader()) {
                    return;
                }
            }
        } catch (SocketTimeoutException e) {
            if (!closed.get()) {
                context.dropped(DropReason.TIMED_OUT, peer, "no TLS handshake within " + limits.firstFrameTimeout().toMillis()
                        + " ms; closing this connection");
            }
        } catch (Throwable e) {
            ended(e);
        } finally {
            close();
            shared.closeView();
        }
    }

    /**
     * Reads and handles frames as the leader on the reader thread, until the stream ends or a
     * waiting thread asks to lead at a moment this one would block.
     *
     * @return {@code false} at the end of the stream
     */
    private boolean leadAsReader() throws IOException, FrameException {
        if (leadable) {
            readTimeout(0);
        }
        long p = progress.get();
        if (undispatched >= 0) {
            int length = undispatched;
            undispatched = -1;
            deliver(frames.buffer(), frames.offset(), length);
            progress.lazySet(++p);
        }
        int length;
        while (true) {
            if (leadable && leadership.followersWaiting() && !frames.hasWholeFrame()) {
                leadership.release(false);
                return true;
            }
            if ((length = frames.next()) < 0) {
                return false;
            }
            progress.lazySet(++p); // odd: the node has the frame (plain stores: the timer reads them a few times per timeout)
            deliver(frames.buffer(), frames.offset(), length);
            progress.lazySet(++p);
        }
    }

    @Override
    public void receiveUntil(CompletableFuture<?> reply, long deadlineNanos) {
        if (!leadable) {
            return;
        }
        Thread me = Thread.currentThread();
        boolean following = false;
        boolean told = false;
        try {
            while (!reply.isDone() && !closed.get() && !me.isInterrupted()) {
                long left = deadlineNanos - System.nanoTime();
                if (left <= 0) {
                    return;
                }
                if (leadership.tryLead(me)) {
                    following = false;
                    if (!leadAsCaller(reply, deadlineNanos)) {
                        return;
                    }
                } else if (!following) {
                    // asks to lead next, then looks again (the leader may have released meanwhile)
                    leadership.follow(me);
                    following = true;
                    if (!told) {
                        reply.whenComplete((r, e) -> LockSupport.unpark(me));
                        told = true;
                    }
                } else {
                    LockSupport.parkNanos(this, left);
                }
            }
        } finally {
            if (following) {
                leadership.unfollow(me);
            }
        }
    }

    /**
     * Reads and handles frames as the leader on a thread waiting for {@code reply}, until it is
     * done, the deadline passes or the thread is interrupted; then hands leadership on.
     *
     * @return {@code false} if the thread must stop reading for this wait (a frame for a listener
     *         came, or the connection ended), {@code true} to look at the reply and the deadline
     */
    private boolean leadAsCaller(CompletableFuture<?> reply, long deadlineNanos) {
        boolean toReader = false;
        long p = progress.get();
        try {
            while (!reply.isDone()) {
                long left = deadlineNanos - System.nanoTime();
                if (left <= 0 || closed.get() || Thread.currentThread().isInterrupted()) {
                    return true;
                }
                readTimeout((int) Math.min(WAIT_SLICE_MILLIS, TimeUnit.NANOSECONDS.toMillis(left) + 1));
                int length;
                try {
                    length = frames.next();
                } catch (SocketTimeoutException e) {
                    continue; // no whole frame within the slice; what arrived of one stays buffered
                }
                if (length < 0) {
                    close();
                    return false;
                }
                progress.lazySet(++p);
                byte kind = frames.buffer()[frames.offset() + FrameCodec.KIND_OFFSET];
                if (kind == FrameKind.MESSAGE.code() || kind == FrameKind.PUBLISH.code() || SharedMemoryLink.forReader(kind)) {
                    // listeners run on the reader thread, this frame first, in order (and shared memory is read there only)
                    undispatched = length;
                    toReader = true;
                    return false;
                }
                deliver(frames.buffer(), frames.offset(), length);
                progress.lazySet(++p);
            }
            return true;
        } catch (Throwable e) {
            try {
                ended(e);
            } finally {
                close();
            }
            return false;
        } finally {
            if ((p & 1) == 1 && !toReader) {
                progress.lazySet(++p); // a frame whose handling failed still counts as handled
            }
            if (toReader) {
                leadership.releaseToReader();
            } else {
                leadership.release(framesWait());
            }
        }
    }

    /**
     * Hands a frame to the node, or to the connection's shared memory: the handshake, and a
     * publication whose payload is taken out of the peer's segment first (on the reader thread).
     *
     * @throws FrameException if a shared-memory reference is bad (the connection ends)
     */
    private void deliver(byte[] buf, int offset, int length) throws FrameException {
        int kind = buf[offset + FrameCodec.KIND_OFFSET];
        if (!SharedMemoryLink.handles(kind)) {
            context.onFrame(buf, offset, length, this);
        } else if (kind == FrameKind.PUBLISH_SHARED.code()) {
            context.onFrame(buf, offset, length, shared.take(buf, offset, length), this);
        } else {
            shared.onHandshake(buf, offset, length, outbound);
        }
    }

    /** @return whether bytes of the stream wait to be read (buffered, or in the socket); on the leader */
    private boolean framesWait() {
        if (closed.get() || frames.buffered() > 0) {
            return true;
        }
        try {
            return in.available() > 0;
        } catch (IOException e) {
            return true;
        }
    }

    /** Sets the socket's read timeout if it changed (plain sockets: a field of the socket, no system call). */
    private void readTimeout(int millis) throws SocketException {
        if (millis != readTimeoutMillis) {
            socket.setSoTimeout(millis);
            readTimeoutMillis = millis;
        }
    }

    /** Counts and logs why reading this connection ended (the caller closes it). */
    /**
     * Says why the connection ends: what the peer sent or the socket did, counted and logged; any
     * other failure is reported to the node's failure policy (the node goes on without this
     * connection), and one no thread survives is re-thrown.
     */
    private void ended(Throwable e) {
        if (e instanceof FrameException f) {
            context.dropped(f.reason(), peer, f.getMessage() + "; closing this connection");
        } else if (e instanceof SocketException) {
            String why = timedOut;
            if (why != null) {
                context.dropped(DropReason.TIMED_OUT, peer, why + " (" + frames.arrived() + "); closing this connection");
            } else if (!closed.get()) {
                LOG.debug("node '{}': connection {} ended: {}", context.nodeName(), peer, e.toString());
            }
        } else if (e instanceof IOException) {
            if (!closed.get()) {
                LOG.warn("node '{}': connection {} failed: {}", context.nodeName(), peer, e.toString());
            }
        } else {
            context.failures().surviveOrRethrow(Thread.currentThread().getName(), e);
            LOG.warn("node '{}': reading from {} failed ({}); closing this connection, the node goes on", context.nodeName(), peer, e.toString());
        }
    }

    private void fail(String why) {
        if (!closed.get()) {
            LOG.warn("node '{}': connection {}: {}", context.nodeName(), peer, why);
        }
        close();
    }
}
