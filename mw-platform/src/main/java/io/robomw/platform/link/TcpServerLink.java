package io.robomw.platform.link;

import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.io.IOException;
import java.net.InetSocketAddress;
import java.net.ServerSocket;
import java.net.Socket;
import java.net.SocketTimeoutException;
import java.time.Duration;
import java.util.Objects;
import java.util.concurrent.atomic.AtomicReference;

/**
 * A {@link Link} that listens on TCP and serves one peer at a time: for a brick (or an emulator's
 * client) that connects to us.
 *
 * <p>{@link #open()} binds. A {@link #read} with no current peer accepts one first, within the
 * read's timeout. When the peer disconnects, the read or write that notices throws
 * {@link LinkLostException} and the peer is dropped; the next read accepts the next peer, which
 * may already be waiting in the listen backlog. A {@link #write} needs a current peer and throws
 * {@link LinkLostException} ("no peer is connected") without one, since writes have no timeout
 * to wait with.
 *
 * <p>Reopening after {@link #close()} binds the port that was bound before, so clients can
 * reconnect to the same port even when the link was created with port 0.
 *
 * <p>Threads: as {@link Link} says. Only the reader accepts.
 */
public final class TcpServerLink implements Link {

    private static final Logger LOG = LoggerFactory.getLogger(TcpServerLink.class);

    /** Connections the operating system queues while the current peer is served. */
    private static final int BACKLOG = 4;

    private final String bindAddress;
    private final Object lifecycle = new Object();
    private final AtomicReference<Socket> peer = new AtomicReference<>();
    private volatile ServerSocket server;
    private volatile int port;

    /**
     * Creates a closed link.
     *
     * @param bindAddress the local address to listen on, e.g. {@code "127.0.0.1"} or {@code "0.0.0.0"}
     * @param port        the TCP port, or 0 for any free port (see {@link #localPort()})
     */
    public TcpServerLink(String bindAddress, int port) {
        this.bindAddress = Objects.requireNonNull(bindAddress, "bindAddress");
        if (port < 0 || port > 65535) {
            throw new IllegalArgumentException("port must be 0 to 65535, port=" + port);
        }
        this.port = port;
    }

    @Override
    public void open() throws IOException {
        synchronized (lifecycle) {
            if (server != null) {
                return;
            }
            ServerSocket s = new ServerSocket();
            try {
                s.setReuseAddress(true);
                s.bind(new InetSocketAddress(bindAddress, port), BACKLOG);
            } catch (IOException e) {
                s.close();
                throw new IOException("cannot listen on " + describe() + ": " + e.getMessage(), e);
            }
            port = s.getLocalPort();
            server = s;
            LOG.debug("listening {}", describe());
        }
    }

    /**
     * @return the bound port, useful after binding port 0
     * @throws IllegalStateException if the link is not open
     */
    public int localPort() {
        if (server == null) {
            throw new IllegalStateException(describe() + " is not open; open() binds the port");
        }
        return port;
    }

    @Override
    public boolean isOpen() {
        return server != null;
    }

    @Override
    public void write(byte[] data, int off, int len) throws IOException {
        Objects.checkFromIndexSize(off, len, data.length);
        openServer();
        Socket p = peer.get();
        if (p == null) {
            throw new LinkLostException(describe(), "no peer is connected; the next read accepts one");
        }
        try {
            p.getOutputStream().write(data, off, len);
        } catch (IOException e) {
            throw dropPeer(p, "write to peer " + p.getRemoteSocketAddress() + " failed: " + e.getMessage(), e);
        }
    }

    @Override
    public int read(byte[] buf, int off, int len, Duration timeout) throws IOException {
        Objects.checkFromIndexSize(off, len, buf.length);
        Deadline deadline = Deadline.after(timeout);
        ServerSocket s = openServer();
        if (len == 0) {
            return 0;
        }
        Socket p = peer.get();
        if (p == null) {
            p = accept(s, deadline);
            if (p == null) {
                return 0;
            }
        }
        int n;
        try {
            n = SocketReads.read(p, buf, off, len, deadline);
        } catch (IOException e) {
            throw dropPeer(p, "read from peer " + p.getRemoteSocketAddress() + " failed: " + e.getMessage(), e);
        }
        if (n < 0) {
            throw dropPeer(p, "peer " + p.getRemoteSocketAddress() + " closed the connection", null);
        }
        return n;
    }

    /** @return the accepted peer, or {@code null} if none connected before the deadline */
    private Socket accept(ServerSocket s, Deadline deadline) throws IOException {
        Socket accepted;
        try {
            s.setSoTimeout(Math.max(1, deadline.remainingMillisRoundedUp()));
            accepted = s.accept();
        } catch (SocketTimeoutException e) {
            return null;
        } catch (IOException e) {
            if (server != s) {
                throw new IOException(describe() + " is closed", e);
            }
            throw e;
        }
        accepted.setTcpNoDelay(true);
        if (server != s || !peer.compareAndSet(null, accepted)) {
            accepted.close();
            throw new IOException(describe() + " is closed");
        }
        LOG.debug("{}: accepted peer {}", describe(), accepted.getRemoteSocketAddress());
        return accepted;
    }

    /** Forgets and closes the peer; the exception says whether we closed it or it went away. */
    private IOException dropPeer(Socket p, String whatHappened, IOException cause) {
        boolean wasCurrent = peer.compareAndSet(p, null);
        closeQuietly(p);
        if (!wasCurrent || server == null) {
            return new IOException(describe() + " is closed", cause);
        }
        LOG.debug("{}: {}", describe(), whatHappened);
        return new LinkLostException(describe(), whatHappened, cause);
    }

    private ServerSocket openServer() throws IOException {
        ServerSocket s = server;
        if (s == null) {
            throw new IOException(describe() + " is closed");
        }
        return s;
    }

    @Override
    public String describe() {
        return "tcp server " + bindAddress + ":" + port;
    }

    @Override
    public void close() {
        synchronized (lifecycle) {
            ServerSocket s = server;
            if (s == null) {
                return;
            }
            server = null;
            closeQuietly(s);
            Socket p = peer.getAndSet(null);
            if (p != null) {
                closeQuietly(p);
            }
            LOG.debug("closed {}", describe());
        }
    }

    private void closeQuietly(AutoCloseable c) {
        try {
            c.close();
        } catch (Exception e) {
            LOG.debug("{}: closing {} failed: {}", describe(), c, e.getMessage());
        }
    }

    @Override
    public String toString() {
        return describe();
    }
}
