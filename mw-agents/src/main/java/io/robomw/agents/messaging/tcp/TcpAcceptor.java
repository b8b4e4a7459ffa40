package io.robomw.agents.messaging.tcp;

import io.robomw.agents.messaging.Address;
import io.robomw.agents.messaging.spi.Endpoint;
import io.robomw.agents.messaging.spi.TransportContext;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.io.IOException;
import java.net.ServerSocket;
import java.net.Socket;
import java.util.List;
import java.util.concurrent.atomic.AtomicInteger;
import javax.net.ssl.SSLSocket;
import io.robomw.agents.messaging.DropReason;

/**
 * A listening TCP socket: accepts connections on its own thread and starts a {@link TcpConnection}
 * for each, up to {@link io.robomw.agents.messaging.PeerLimits#maxConnections()} at once; a peer
 * beyond it gets a refusal frame naming the limit and is closed.
 */
final class TcpAcceptor implements Endpoint {

    private static final Logger LOG = LoggerFactory.getLogger(TcpAcceptor.class);

    private final ServerSocket server;
    private final Address address;
    private final TransportContext context;
    private final List<AutoCloseable> open;
    private final ConnectionTimeouts timeouts;
    private final AtomicInteger accepted = new AtomicInteger();
    /** Refused sockets waiting to be closed; touched by the accepting thread only (and by close, after it). */
    private final java.util.ArrayDeque<Refused> refused = new java.util.ArrayDeque<>();

    private static final int MAX_REFUSED_WAITING = 64;
    private static final long REFUSED_GRACE_NANOS = 1_000_000_000L;

    private record Refused(Socket socket, long sinceNanos) {
    }

    private final java.util.function.Supplier<io.robomw.agents.messaging.shm.SharedSegment> segments;

    TcpAcceptor(ServerSocket server, Address address, TransportContext context, List<AutoCloseable> open, ConnectionTimeouts timeouts,
                java.util.function.Supplier<io.robomw.agents.messaging.shm.SharedSegment> segments) {
        this.segments = segments;
        this.timeouts = timeouts;
        this.server = server;
        this.address = address;
        this.context = context;
        this.open = open;
    }

    void start() {
        context.threads("tcp-accept-" + address.port()).newThread(this::acceptLoop).start();
    }

    @Override
    public Address address() {
        return address;
    }

    @Override
    public void close() {
        try {
            server.close();
        } catch (IOException e) {
            LOG.debug("closing {}: {}", address, e.toString());
        }
    }

    private void acceptLoop() {
        try {
            serve();
        } finally {
            for (Refused r; (r = refused.pollFirst()) != null; ) {
                closeQuietly(r.socket());
            }
        }
    }

    private void serve() {
        while (!server.isClosed()) {
            Socket s;
            try {
                s = server.accept();
                closeRefused();
            } catch (IOException e) {
                if (!server.isClosed()) {
                    LOG.warn("node '{}': accepting on {} failed: {}", context.nodeName(), address, e.toString());
                }
                continue;
            }
            String peer = "tcp://" + s.getInetAddress().getHostAddress() + ":" + s.getPort();
            int max = context.settings().limits().maxConnections();
            if (accepted.incrementAndGet() > max) {
                accepted.decrementAndGet();
                refuse(s, peer, max);
                continue;
            }
            TcpConnection c;
            try {
                c = new TcpConnection(s, address, peer, context, open, timeouts, segments, accepted::decrementAndGet);
            } catch (Throwable e) {
                accepted.decrementAndGet();
                closeQuietly(s);
                if (!(e instanceof IOException)) {
                    context.failures().surviveOrRethrow(Thread.currentThread().getName(), e);
                }
                LOG.warn("node '{}': connection from {} failed: {}", context.nodeName(), peer, e.toString());
                continue;
            }
            c.start();
        }
    }

    /**
     * Tells a peer beyond the limit why it is refused (one small frame, which a fresh socket's
     * send buffer takes without blocking), then closes. The refusal is counted and logged as
     * {@link DropReason#LIMIT}, at most one line a second.
     */
    private void refuse(Socket s, String peer, int max) {
        String why = "node '" + context.nodeName() + "' at " + address + " serves at most " + max
                + " connections (maxConnections) and has that many; try again later";
        context.dropped(DropReason.LIMIT, peer, "connection refused: " + max + " connections are open (maxConnections)");
        try {
            if (!(s instanceof SSLSocket)) {
                // no TLS handshake for a peer that is refused anyway: a plain refusal frame, or nothing
                s.getOutputStream().write(context.refusal(why));
                s.shutdownOutput();
                // Closed a little later: closing a socket with unread input resets the connection,
                // and a reset can overtake the refusal at the peer (which sends its first frames
                // at once). The peer closes its side when it reads the refusal.
                refused.addLast(new Refused(s, System.nanoTime()));
                return;
            }
        } catch (IOException e) {
            LOG.debug("node '{}': refusing {}: {}", context.nodeName(), peer, e.toString());
        }
        closeQuietly(s);
    }

    /** Closes refused sockets after their grace, and the oldest beyond {@value #MAX_REFUSED_WAITING}. */
    private void closeRefused() {
        long now = System.nanoTime();
        for (Refused r; (r = refused.peekFirst()) != null; ) {
            if (refused.size() <= MAX_REFUSED_WAITING && now - r.sinceNanos() < REFUSED_GRACE_NANOS) {
                break;
            }
            refused.pollFirst();
            try {
                r.socket().getInputStream().skip(r.socket().getInputStream().available());
            } catch (IOException e) {
                // closing anyway
            }
            closeQuietly(r.socket());
        }
    }

    private static void closeQuietly(Socket s) {
        try {
            s.close();
        } catch (IOException ignored) {
            // nothing more to do
        }
    }
}
