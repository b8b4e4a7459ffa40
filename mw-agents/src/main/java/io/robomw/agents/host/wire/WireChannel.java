package io.robomw.agents.host.wire;

import io.robomw.agents.host.protocol.Op;
import io.robomw.agents.host.protocol.Reply;
import io.robomw.agents.host.rmi.HostEndpoint;
import io.robomw.agents.host.rmi.HostSockets;
import io.robomw.agents.host.rmi.PeerLink;
import io.robomw.agents.host.rmi.Session;
import io.robomw.agents.host.security.FrameTag;
import io.robomw.agents.net.RmiSocketSetup;

import javax.net.ssl.SSLContext;
import javax.net.ssl.SSLSocket;
import java.io.BufferedOutputStream;
import java.io.IOException;
import java.io.InputStream;
import java.net.InetSocketAddress;
import java.net.Socket;
import java.nio.channels.SocketChannel;
import java.nio.charset.StandardCharsets;
import java.util.Arrays;

/**
 * A peer's connection to a host's agent wire ({@link WireServer}), for one session: connects (TLS
 * when the hosts use it), proves the session with HELLO, then carries one call at a time: writes
 * the request frame straight from the caller's array ({@link WireWriter}) and waits for the reply
 * on the same connection, optionally spinning a bounded time before it blocks. Not thread-safe:
 * a {@link PeerLink} lends each connection to one call at a time.
 */
public final class WireChannel implements AutoCloseable {

    /** What a call's answer was when it is not a verified reply. */
    public static final Reply UNKNOWN_SESSION = new Reply(Reply.Status.UNKNOWN_SESSION, new byte[0]);
    /**
     * The largest body after which a call spins for its reply. A larger frame's reply comes only after
     * the host has checked the frame's last piece and read the agent's state (about 0.13 ms a megabyte
     * on the project's machine), later than any spin: the spin would only take a processor from the
     * host that is reading the frame, on a machine that runs both.
     */
    public static final int SPIN_MAX_BODY = WireWriter.ONE_WRITE;

    private static final byte[] NO_BODY = new byte[0];

    public final Session session;
    private final String peer;
    private final Socket socket;
    private final InputStream in;
    private final WireReader reader;
    private final WireWriter writer;
    private final FrameTag checking = new FrameTag();
    private long lastUsed = System.nanoTime();

    private WireChannel(Session session, String peer, Socket socket, InputStream in, WireWriter writer) {
        this.session = session;
        this.peer = peer;
        this.socket = socket;
        this.in = in;
        this.reader = new WireReader(in, null, WireReader.Reuse.EVERY_FRAME); // a reply's body is copied out below
        this.writer = writer;
    }

    /**
     * Connects to a host's agent wire (nothing is sent yet).
     *
     * @param session       the session the connection will carry
     * @param host          the host's address
     * @param port          its wire port
     * @param tls           the TLS context to connect with, or {@code null} for a plain connection
     * @param timeoutMillis the connect timeout, and the longest a reply may take
     * @param tagger        computes the tags of large frames while they are written, or {@code null} (the calling thread does)
     * @return the connection
     * @throws IOException if it cannot connect, or the TLS handshake fails
     */
    public static WireChannel connect(Session session, String host, int port, SSLContext tls, int timeoutMillis, java.util.concurrent.Executor tagger)
            throws IOException {
        String peer = host + ":" + port;
        if (tls != null) {
            Socket raw = new Socket();
            raw.setSoTimeout(timeoutMillis);
            Socket s = RmiSocketSetup.connect(raw, host, port, timeoutMillis, false);
            try {
                SSLSocket ssl = (SSLSocket) tls.getSocketFactory().createSocket(s, host, port, true);
                ssl.setUseClientMode(true);
                ssl.startHandshake();
                return new WireChannel(session, peer, ssl, ssl.getInputStream(),
                        new WireWriter(WireWriter.of(new BufferedOutputStream(ssl.getOutputStream(), 32 * 1024)), tagger));
            } catch (IOException | RuntimeException e) {
                s.close();
                throw e;
            }
        }
        SocketChannel c = SocketChannel.open();
        try {
            c.socket().setTcpNoDelay(true);
            c.socket().setSoTimeout(timeoutMillis);
            c.socket().connect(new InetSocketAddress(host, port), timeoutMillis);
            return new WireChannel(session, peer, c.socket(), c.socket().getInputStream(), new WireWriter(WireWriter.of(c), tagger));
        } catch (IOException | RuntimeException e) {
            c.close();
            throw e;
        }
    }

    /** @return how long ago the connection last carried a call, ns */
    public long idleNanos() {
        return System.nanoTime() - lastUsed;
    }

    /**
     * Makes one call and waits for its reply.
     *
     * @param seq       the call's sequence number (above every number this connection carried)
     * @param opCode    the operation ({@link Op#code()} or {@link WireFrames#OP_HELLO})
     * @param body      holds the body
     * @param off       where it starts
     * @param len       its length
     * @param spinNanos how long to spin for the reply before blocking (0: block at once); not for a body of more than
     *                  {@value #SPIN_MAX_BODY} bytes, whose reply cannot come that soon
     * @return the verified reply, or {@link #UNKNOWN_SESSION}
     * @throws WireFrames.FrameRefused if the host refused the frame (it closes the connection) or sent a bad reply
     * @throws IOException             if the connection fails: the call may have been served
     */
    public Reply call(long seq, int opCode, byte[] body, int off, int len, long spinNanos) throws IOException {
        writer.write(session.frameKey, WireFrames.DIRECTION_REQUEST, opCode, session.id, seq, body, off, len);
        if (spinNanos > 0 && len <= SPIN_MAX_BODY && !reader.buffered() && !(socket instanceof SSLSocket)) {
            // (a TLS stream cannot tell whether bytes wait on the socket: it blocks at once)
            HostSockets.spinUntilReadable(in, spinNanos);
        }
        WireFrames.Header h = reader.header();
        if (h == null) {
            throw new java.io.EOFException("host " + peer + " closed the agent wire connection without answering");
        }
        if (h.version() != WireFrames.VERSION) {
            throw new WireFrames.FrameRefused("host " + peer + " answered in agent wire version " + h.version() + " (this peer speaks " + WireFrames.VERSION + ")");
        }
        boolean untagged = h.code() == Reply.Status.UNKNOWN_SESSION.code() || h.code() == WireFrames.STATUS_FRAME_REFUSED;
        long max = untagged ? WireFrames.MAX_REASON_BYTES : HostEndpoint.UNPROVEN_MAX_BYTES * 16L;
        if (h.length() > max) {
            throw new WireFrames.FrameRefused("host " + peer + " answered with a body of " + h.length() + " bytes; at most " + max + " are read");
        }
        if (untagged) {
            byte[] f = reader.frame(h, null);
            if (h.code() == Reply.Status.UNKNOWN_SESSION.code()) {
                return UNKNOWN_SESSION;
            }
            throw new WireFrames.FrameRefused("host " + peer + " refused the frame (unauthenticated answer): "
                    + new String(f, WireFrames.HEADER, (int) h.length(), StandardCharsets.UTF_8));
        }
        if (h.session() != session.id || h.seq() != seq) {
            throw new WireFrames.FrameRefused("host " + peer + " answered call " + h.seq() + " of session " + Long.toHexString(h.session())
                    + " to call " + seq + " of session " + Long.toHexString(session.id));
        }
        checking.start(session.frameKey, WireFrames.DIRECTION_REPLY, seq, true);
        byte[] f = reader.frame(h, checking);
        if (!checking.check(f, (int) h.frameLength() - WireFrames.TAG)) {
            throw new WireFrames.FrameRefused("host " + peer + " sent a reply with a wrong tag: not from the host the session was made with");
        }
        Reply.Status status;
        try {
            status = Reply.Status.fromCode(h.code());
        } catch (IllegalArgumentException e) {
            throw new WireFrames.FrameRefused("host " + peer + " answered with " + e.getMessage());
        }
        lastUsed = System.nanoTime();
        return new Reply(status, h.length() == 0 ? NO_BODY : Arrays.copyOfRange(f, WireFrames.HEADER, WireFrames.HEADER + (int) h.length()));
    }

    @Override
    public void close() {
        try {
            socket.close();
        } catch (IOException ignored) {
            // closing anyway
        }
    }

    @Override
    public String toString() {
        return "WireChannel[" + peer + ", session " + Long.toHexString(session.id) + "]";
    }
}
