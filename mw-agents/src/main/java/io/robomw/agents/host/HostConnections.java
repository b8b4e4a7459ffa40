package io.robomw.agents.host;

import io.robomw.agents.net.ThrottledWarnings;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.io.Closeable;
import java.io.IOException;
import java.time.Duration;
import java.util.Iterator;
import java.util.LinkedHashSet;
import java.util.Set;
import java.util.concurrent.atomic.LongAdder;

/**
 * The connections an agent host's RMI endpoint has accepted, as the host sees them: which of them
 * has proved the cluster key (a call on it verified under a session, or an authentication on it
 * succeeded), and how many bytes the calls being read on them may allocate. RMI reads each
 * connection's calls on a thread of its own; the connection's socket tells this class which
 * connection the current thread reads ({@link #reading}), so the deserialization filter and the
 * endpoint know the connection of the call in hand.
 *
 * <p>What it promises (docs/security.md):
 * <ul>
 * <li><b>Limits per connection until it has proved the key, not per client address.</b> A call on
 *     a connection that has not proved the key may carry at most {@value #UNPROVEN_MAX_BYTES}
 *     bytes (an authentication request is about a hundred); the filter refuses a larger array
 *     before RMI allocates it. Another connection from the same address having proved the key
 *     changes nothing.</li>
 * <li><b>A bound on what calls being read hold, across all connections.</b> A large array is read
 *     only if the arrays being read on all connections together stay within the budget (half the
 *     heap, and at least the largest call a host takes); one more is refused before it is allocated.</li>
 * <li><b>Idle connections cannot lock peers out.</b> At most {@value #MAX_CONNECTIONS} connections
 *     are open at once; one more makes the oldest connection that has proved nothing make way (it is
 *     closed), and is closed itself only when every open connection has proved the key. A
 *     connection that sends no byte within {@link #FIRST_BYTE} of its accept is closed.</li>
 * </ul>
 * Thread-safe.
 */
final class HostConnections {

    private static final Logger LOG = LoggerFactory.getLogger(HostConnections.class);

    /** Connections open at once. */
    static final int MAX_CONNECTIONS = 256;
    /** The largest byte array a call may carry on a connection that has not proved the cluster key. */
    static final int UNPROVEN_MAX_BYTES = 64 * 1024;
    /** How long an accepted connection may take to send its first byte (an RMI client sends its handshake at once; TLS its hello). */
    static final Duration FIRST_BYTE = Duration.ofSeconds(5);

    /** One accepted connection. */
    final class Connection {
        private final String remote;
        private final Closeable socket;
        private volatile boolean proven;
        /** Bytes the call being read on it may allocate; guarded by the outer lock. */
        private long reserved;

        private Connection(String remote, Closeable socket) {
            this.remote = remote;
            this.socket = socket;
        }

        /** @return the peer's address and port, for the log */
        String remote() {
            return remote;
        }

        /** @return whether a call on it proved the cluster key */
        boolean proven() {
            return proven;
        }

        @Override
        public String toString() {
            return remote + (proven ? " (proved the key)" : "");
        }
    }

    private final String hostName;
    private final long budget;
    private final Object lock = new Object();
    /** Every open connection, oldest first. */
    private final Set<Connection> open = new LinkedHashSet<>();
    /** The open connections that have not proved the key, oldest first. */
    private final Set<Connection> unproven = new LinkedHashSet<>();
    private long reading;
    private final ThreadLocal<Connection> current = new ThreadLocal<>();
    private final LongAdder refused = new LongAdder();
    private final LongAdder evicted = new LongAdder();
    private final LongAdder silent = new LongAdder();
    private final LongAdder arraysRefused = new LongAdder();
    private final ThrottledWarnings warnings = new ThrottledWarnings(LOG, Duration.ofSeconds(1));

    /**
     * @param hostName     the host's name, for the log
     * @param largestCall  the largest call the host takes, in bytes: the budget is at least this
     */
    HostConnections(String hostName, long largestCall) {
        this(hostName, largestCall, Runtime.getRuntime().maxMemory() / 2);
    }

    /**
     * @param hostName    the host's name, for the log
     * @param largestCall the largest call the host takes, in bytes
     * @param heapShare   the bytes the calls being read may hold together, if more than {@code largestCall}
     */
    HostConnections(String hostName, long largestCall, long heapShare) {
        this.hostName = hostName;
        this.budget = Math.max(largestCall, heapShare);
    }

    /**
     * Takes an accepted connection, making the oldest one that has proved nothing make way if the
     * endpoint has {@value #MAX_CONNECTIONS} open.
     *
     * @param remote the peer's address and port
     * @param socket closes the connection
     * @return the connection, or {@code null} if every open connection has proved the key (the caller closes this one)
     */
    Connection admit(String remote, Closeable socket) {
        Connection c = new Connection(remote, socket);
        Connection makingWay = null;
        synchronized (lock) {
            if (open.size() >= MAX_CONNECTIONS) {
                Iterator<Connection> oldest = unproven.iterator();
                if (!oldest.hasNext()) {
                    refused.increment();
                    return null;
                }
                makingWay = oldest.next();
                oldest.remove();
                open.remove(makingWay);
                release(makingWay);
            }
            open.add(c);
            unproven.add(c);
        }
        if (makingWay != null) {
            evicted.increment();
            warnings.warn("host {}: {} connections open, closed the oldest that proved nothing ({}) for a new one from {}", hostName, MAX_CONNECTIONS,
                    makingWay.remote, remote);
            closeQuietly(makingWay);
        }
        return c;
    }

    /** The connection closed (by either side). */
    void closed(Connection c) {
        synchronized (lock) {
            open.remove(c);
            unproven.remove(c);
            release(c);
        }
    }

    /** The connection sent no byte within {@link #FIRST_BYTE}: it is closed. */
    void silent(Connection c) {
        silent.increment();
        warnings.warn("host {}: closed a connection from {} that sent nothing within {} s", hostName, c.remote, FIRST_BYTE.toSeconds());
        closeQuietly(c);
    }

    /** The current thread reads this connection (RMI reads and serves a connection's calls on one thread). */
    void reading(Connection c) {
        current.set(c);
    }

    /** @return the connection the current thread reads, or {@code null} outside a connection's thread */
    Connection current() {
        return current.get();
    }

    /** @return the address and port of the current call's peer, or "this process" outside a connection's thread */
    String currentRemote() {
        Connection c = current.get();
        return c == null ? "this process" : c.remote;
    }

    /** A call on the current connection proved the cluster key: its calls may be large from now on. */
    void proven() {
        Connection c = current.get();
        if (c != null && !c.proven) {
            synchronized (lock) {
                c.proven = true;
                unproven.remove(c);
            }
        }
    }

    /**
     * The deserialization filter's question for a byte array a call on the current connection
     * announces: may it be read? Reserves its length from the budget until {@link #callDone()}
     * (or the connection closes, or its next call).
     *
     * @param length the array's length
     * @return whether to read it
     */
    boolean mayRead(long length) {
        if (length <= UNPROVEN_MAX_BYTES) {
            return true;
        }
        Connection c = current.get();
        if (c == null || !c.proven) {
            arraysRefused.increment();
            warnings.warn("host {}: refused a call of {} bytes from {}: its connection has not proved the cluster key (until it has, at most {} bytes)",
                    hostName, length, c == null ? "an unknown connection" : c.remote, UNPROVEN_MAX_BYTES);
            return false;
        }
        synchronized (lock) {
            release(c);
            if (reading + length > budget) {
                arraysRefused.increment();
                warnings.warn("host {}: refused a call of {} bytes from {}: calls being read hold {} bytes already, of the {} they may hold together",
                        hostName, length, c.remote, reading, budget);
                return false;
            }
            reading += length;
            c.reserved = length;
        }
        return true;
    }

    /** The current call is done: what it reserved is free again. */
    void callDone() {
        Connection c = current.get();
        if (c != null) {
            synchronized (lock) {
                release(c);
            }
        }
    }

    private void release(Connection c) {
        reading -= c.reserved;
        c.reserved = 0;
    }

    /** @return connections open now */
    int open() {
        synchronized (lock) {
            return open.size();
        }
    }

    /** @return bytes the calls being read may hold now */
    long reading() {
        synchronized (lock) {
            return reading;
        }
    }

    /** @return the bytes the calls being read may hold together */
    long budget() {
        return budget;
    }

    /** @return connections closed at once because every open one had proved the key */
    long refused() {
        return refused.sum();
    }

    /** @return connections closed to make way for a new one */
    long evicted() {
        return evicted.sum();
    }

    /** @return connections closed for sending nothing in time */
    long silent() {
        return silent.sum();
    }

    /** @return large arrays refused (unproven connection, or over the budget) */
    long arraysRefused() {
        return arraysRefused.sum();
    }

    private static void closeQuietly(Connection c) {
        try {
            c.socket.close();
        } catch (IOException e) {
            // closing anyway
        }
    }
}
