package io.robomw.platform.link;

import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.io.IOException;
import java.time.Duration;
import java.util.Arrays;
import java.util.Objects;

/**
 * A brick driver's one door to its {@link Link}: sends frames, receives bytes with deadlines,
 * reads length-driven frames whole, reopens a dropped link, and optionally records every byte in a
 * {@link WireLog}.
 *
 * <h2>Frames over streams</h2>
 * A serial port or TCP stream does not keep frame boundaries: a pty read may return half a frame,
 * or one and a half. Codecs therefore read length-driven: {@link #receiveExactly(int, Duration)}
 * the fixed header, then {@code receiveExactly} the length the header gives. Bytes beyond the
 * requested count stay in the link for the next call.
 *
 * <h2>Lost and restored</h2>
 * A {@link LinkLostException} from the link is rethrown (and noted in the wire log); the
 * communicator keeps no state of the link's own: whether the link is up is its owner's to say
 * (a brick's link agent, which reopens it with {@link #reopen()}).
 *
 * <h2>Threads</h2>
 * One thread may {@link #send} while another {@link #receive}s; at most one thread sends and at
 * most one receives at a time (receiving uses a buffer owned by the receiver). {@link #open()},
 * {@link #reopen()} and {@link #close()} may be called from any thread; a send or receive that
 * overlaps them ends with an {@link IOException} saying the link is closed, or carries on over the
 * reopened link.
 */
public final class Communicator implements AutoCloseable {

    private static final Logger LOG = LoggerFactory.getLogger(Communicator.class);

    /** The most bytes one {@link #receive(Duration)} returns. */
    static final int RECEIVE_CHUNK_BYTES = 4096;

    private final Link link;
    private final WireLog wireLog;
    private final Object lifecycle = new Object();
    private final byte[] receiveBuffer = new byte[RECEIVE_CHUNK_BYTES];

    /**
     * Wraps a link without a wire log. The link is not opened; call {@link #open()}.
     *
     * @param link the link
     */
    public Communicator(Link link) {
        this.link = Objects.requireNonNull(link, "link");
        this.wireLog = null;
    }

    /**
     * Wraps a link and records its traffic. The link is not opened; call {@link #open()}.
     *
     * @param link    the link
     * @param wireLog where sent and received bytes are recorded; closed with this communicator
     */
    public Communicator(Link link, WireLog wireLog) {
        this.link = Objects.requireNonNull(link, "link");
        this.wireLog = Objects.requireNonNull(wireLog, "wireLog");
    }

    /** @return the link, as {@link Link#describe()} gives it */
    public String describe() {
        return link.describe();
    }

    /**
     * Opens the link if it is not open.
     *
     * @throws IOException if the link cannot be opened
     */
    public void open() throws IOException {
        synchronized (lifecycle) {
            link.open();
        }
    }

    /**
     * Closes and opens the link again, e.g. after a {@link LinkLostException}.
     *
     * @throws IOException if the link cannot be opened; it stays closed
     */
    public void reopen() throws IOException {
        synchronized (lifecycle) {
            link.close();
            link.open();
            LOG.debug("reopened {}", link.describe());
            if (wireLog != null) {
                wireLog.note("reopened " + link.describe());
            }
        }
    }

    /** @return whether the link is open ({@link Link#isOpen()}): a lost link stays open until it is closed or reopened */
    public boolean isOpen() {
        return link.isOpen();
    }

    /**
     * Sends all bytes.
     *
     * @param data the frame
     * @throws LinkLostException if the link was lost
     * @throws IOException       if the link is closed
     */
    public void send(byte[] data) throws IOException {
        Objects.requireNonNull(data, "data");
        try {
            link.write(data, 0, data.length);
        } catch (LinkLostException e) {
            noteLost(e);
            throw e;
        }
        if (wireLog != null) {
            wireLog.sent(data, 0, data.length);
        }
    }

    /**
     * Receives whatever bytes arrive first: at least one, at most {@value #RECEIVE_CHUNK_BYTES}.
     *
     * @param timeout how long to wait for the first byte
     * @return the bytes
     * @throws LinkTimeoutException if no byte arrived in time
     * @throws LinkLostException    if the link was lost
     * @throws IOException          if the link is closed
     */
    public byte[] receive(Duration timeout) throws IOException {
        int n = read(receiveBuffer, 0, receiveBuffer.length, Deadline.after(timeout));
        if (n == 0) {
            throw new LinkTimeoutException(link.describe(), "no bytes arrived", timeout);
        }
        return Arrays.copyOf(receiveBuffer, n);
    }

    /**
     * Receives exactly {@code n} bytes, however the link splits or merges them; the one deadline
     * covers all of them. On a timeout the bytes that did arrive are dropped (the wire log still
     * has them), so the caller should resynchronise, e.g. by reopening.
     *
     * @param n       how many bytes, at least 1
     * @param timeout how long all {@code n} bytes may take
     * @return the bytes
     * @throws LinkTimeoutException if fewer than {@code n} bytes arrived in time; the message says how many did
     * @throws LinkLostException    if the link was lost
     * @throws IOException          if the link is closed
     */
    public byte[] receiveExactly(int n, Duration timeout) throws IOException {
        if (n < 1) {
            throw new IllegalArgumentException("n must be at least 1, n=" + n);
        }
        Deadline deadline = Deadline.after(timeout);
        byte[] frame = new byte[n];
        int received = 0;
        while (received < n) {
            int got = read(frame, received, n - received, deadline);
            if (got == 0) {
                throw new LinkTimeoutException(link.describe(),
                        "received " + received + " of " + n + " bytes", timeout);
            }
            received += got;
        }
        return frame;
    }

    private int read(byte[] buf, int off, int len, Deadline deadline) throws IOException {
        int n;
        try {
            n = link.read(buf, off, len, Duration.ofNanos(deadline.remainingNanos()));
        } catch (LinkLostException e) {
            noteLost(e);
            throw e;
        }
        if (n > 0 && wireLog != null) {
            wireLog.received(buf, off, n);
        }
        return n;
    }

    /** Notes a loss in the wire log, where the bytes around it are. */
    private void noteLost(IOException cause) {
        if (wireLog != null) {
            wireLog.note("link lost: " + cause.getMessage());
        }
    }

    /** Closes the link and the wire log. Idempotent. */
    @Override
    public void close() {
        synchronized (lifecycle) {
            link.close();
            if (wireLog != null) {
                wireLog.close();
            }
        }
    }

    @Override
    public String toString() {
        return "Communicator[" + link.describe() + "]";
    }
}
