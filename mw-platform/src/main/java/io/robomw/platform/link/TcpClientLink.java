package io.robomw.platform.link;

import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.io.IOException;
import java.net.InetSocketAddress;
import java.net.Socket;
import java.time.Duration;
import java.util.Objects;

/**
 * A {@link Link} that connects to a brick listening on TCP (a fischertechnik TXT, an EV3 over WiFi,
 * an emulator). {@code TCP_NODELAY} is set, so each small command frame leaves at once instead of
 * waiting for Nagle's algorithm. Every {@link #open()} resolves the host and connects anew.
 *
 * <p>End of stream or a reset connection becomes {@link LinkLostException}. Threads: as
 * {@link Link} says; closing from another thread ends a blocked read with an {@link IOException}
 * saying the link is closed.
 */
public final class TcpClientLink implements Link {

    private static final Logger LOG = LoggerFactory.getLogger(TcpClientLink.class);

    private final String host;
    private final int port;
    private final Duration connectTimeout;
    private final Object lifecycle = new Object();
    private volatile Socket socket;

    /**
     * Creates a closed link.
     *
     * @param host           host name or address of the brick
     * @param port           its TCP port, 1 to 65535
     * @param connectTimeout how long {@link #open()} waits for the connection, positive
     */
    public TcpClientLink(String host, int port, Duration connectTimeout) {
        this.host = Objects.requireNonNull(host, "host");
        if (port < 1 || port > 65535) {
            throw new IllegalArgumentException("port must be 1 to 65535, port=" + port);
        }
        Objects.requireNonNull(connectTimeout, "connectTimeout");
        if (connectTimeout.isNegative() || connectTimeout.isZero()) {
            throw new IllegalArgumentException("connectTimeout must be positive, connectTimeout=" + connectTimeout);
        }
        this.port = port;
        this.connectTimeout = connectTimeout;
    }

    @Override
    public void open() throws IOException {
        synchronized (lifecycle) {
            if (socket != null) {
                return;
            }
            Socket s = new Socket();
            try {
                s.setTcpNoDelay(true);
                s.connect(new InetSocketAddress(host, port),
                        (int) Math.min(Integer.MAX_VALUE, Math.max(1, connectTimeout.toMillis())));
            } catch (IOException e) {
                s.close();
                throw new IOException("cannot connect " + describe() + " within "
                        + Deadline.format(connectTimeout) + ": " + e.getMessage(), e);
            }
            socket = s;
            LOG.debug("connected {} from local port {}", describe(), s.getLocalPort());
        }
    }

    @Override
    public boolean isOpen() {
        return socket != null;
    }

    @Override
    public void write(byte[] data, int off, int len) throws IOException {
        Objects.checkFromIndexSize(off, len, data.length);
        Socket s = connectedSocket();
        try {
            s.getOutputStream().write(data, off, len);
        } catch (IOException e) {
            throw failure(s, "write failed: " + e.getMessage(), e);
        }
    }

    @Override
    public int read(byte[] buf, int off, int len, Duration timeout) throws IOException {
        Objects.checkFromIndexSize(off, len, buf.length);
        Deadline deadline = Deadline.after(timeout);
        Socket s = connectedSocket();
        if (len == 0) {
            return 0;
        }
        int n;
        try {
            n = SocketReads.read(s, buf, off, len, deadline);
        } catch (IOException e) {
            throw failure(s, "read failed: " + e.getMessage(), e);
        }
        if (n < 0) {
            throw new LinkLostException(describe(), "the peer closed the connection");
        }
        return n;
    }

    private Socket connectedSocket() throws IOException {
        Socket s = socket;
        if (s == null) {
            throw new IOException(describe() + " is closed");
        }
        return s;
    }

    /** A failure on a socket we closed ourselves is "closed"; any other is a lost link. */
    private IOException failure(Socket s, String whatHappened, IOException cause) {
        if (socket != s) {
            return new IOException(describe() + " is closed", cause);
        }
        return new LinkLostException(describe(), whatHappened, cause);
    }

    @Override
    public String describe() {
        return "tcp " + host + ":" + port;
    }

    @Override
    public void close() {
        synchronized (lifecycle) {
            Socket s = socket;
            if (s == null) {
                return;
            }
            socket = null;
            try {
                s.close();
            } catch (IOException e) {
                LOG.debug("{}: closing the socket failed: {}", describe(), e.getMessage());
            }
            LOG.debug("closed {}", describe());
        }
    }

    @Override
    public String toString() {
        return describe();
    }
}
