package io.robomw.agents.messaging.tcp;

import io.robomw.agents.messaging.DropReason;
import io.robomw.agents.messaging.frame.Frame;
import io.robomw.agents.messaging.frame.FrameCodec;
import io.robomw.agents.messaging.frame.FrameException;
import io.robomw.agents.messaging.frame.FrameKind;
import io.robomw.agents.messaging.io.OutboundBuffer;
import io.robomw.agents.messaging.shm.Handshake;
import io.robomw.agents.messaging.shm.SegmentView;
import io.robomw.agents.messaging.shm.SharedReference;
import io.robomw.agents.messaging.shm.SharedSegment;
import io.robomw.agents.messaging.spi.Publication;
import io.robomw.agents.messaging.spi.TransportContext;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.io.IOException;
import java.util.Optional;
import java.util.function.Supplier;

/**
 * One TCP connection's shared memory, both ways (docs/messaging.md, "Shared memory"):
 *
 * <ul>
 *   <li>as a <em>subscriber</em>: asks at the start ({@link FrameKind#SHM_ASK}) if the connection
 *   may use shared memory; maps the segment the peer offers and accepts it; takes the payloads of
 *   {@link FrameKind#PUBLISH_SHARED} frames out of it (on the reading thread);</li>
 *   <li>as a <em>publisher</em>: remembers that the peer asked from this host; before the first
 *   publication of at least the threshold, offers a cell of the transport's segment; once the peer
 *   accepted, writes such publications into the segment and sends their references instead.</li>
 * </ul>
 *
 * A connection may use shared memory when the node's setting and its address allow it
 * ({@code ?shm=off} does not), it is not TLS, and the peer's address is a loopback address. Frames
 * with an HMAC always go over the connection.
 *
 * <p>Thread-safe; the subscriber's view is used and closed by the connection's reader thread only.
 */
final class SharedMemoryLink {

    private static final Logger LOG = LoggerFactory.getLogger(SharedMemoryLink.class);

    private final String peer;
    private final TransportContext context;
    private final boolean usable;
    private final String hostId;
    private final int threshold;
    private final long sendTimeoutNanos;
    private final Supplier<SharedSegment> segments;
    private final Runnable lagging;
    /** The peer asked from this host: it may be offered the segment. */
    private volatile boolean peerAsked;
    /** This node asked: an offer is welcome. */
    private volatile boolean asked;
    /** Guarded by this: whether an offer was made. */
    private boolean offered;
    private volatile SharedSegment segment;
    private volatile SharedSegment.Subscriber outlet;
    /** The peer accepted: large publications go through the segment. */
    private volatile boolean accepted;
    /** The peer's segment as mapped here; reader thread only. */
    private SegmentView view;

    /**
     * @param peer     the peer, for messages
     * @param context  the node
     * @param usable   whether this connection may use shared memory (settings, address option, no TLS, loopback peer)
     * @param segments the transport's segment, made on first use; {@code null} if it cannot be made
     * @param lagging  closes the connection (the peer held a record past the send timeout)
     */
    SharedMemoryLink(String peer, TransportContext context, boolean usable, Supplier<SharedSegment> segments, Runnable lagging) {
        this.peer = peer;
        this.context = context;
        Optional<String> id = usable ? Handshake.hostId() : Optional.empty();
        this.usable = id.isPresent();
        this.hostId = id.orElse("");
        this.threshold = context.settings().sharedMemory().thresholdBytes();
        this.sendTimeoutNanos = context.settings().sendTimeout().toNanos();
        this.segments = segments;
        this.lagging = lagging;
    }

    /** @return the frame that asks the peer for shared memory, or {@code null} if this connection does not use it */
    byte[] ask() {
        if (!usable) {
            return null;
        }
        asked = true;
        return Handshake.ask(new Handshake.Ask(hostId));
    }

    /** @param kind a frame's KIND code @return whether this class handles frames of that kind */
    static boolean handles(int kind) {
        return kind == FrameKind.SHM_ASK.code() || kind == FrameKind.SHM_OFFER.code() || kind == FrameKind.SHM_ACCEPT.code()
                || kind == FrameKind.PUBLISH_SHARED.code();
    }

    /** @param kind a frame's KIND code @return whether only the reader thread may handle it (it touches the view) */
    static boolean forReader(int kind) {
        return kind == FrameKind.SHM_OFFER.code() || kind == FrameKind.PUBLISH_SHARED.code();
    }

    /**
     * Handles a handshake frame: a bad one is counted and dropped (the connection goes on over TCP).
     *
     * @param buf    bytes
     * @param offset where the frame starts
     * @param length its length
     * @param out    the connection's queue, for the acceptance
     */
    void onHandshake(byte[] buf, int offset, int length, OutboundBuffer out) {
        Frame f;
        try {
            f = FrameCodec.decode(buf, offset, length, context.settings().maxFrameSize());
            switch (f.kind()) {
                case SHM_ASK -> onAsk(Handshake.readAsk(f));
                case SHM_OFFER -> onOffer(Handshake.readOffer(f), out);
                case SHM_ACCEPT -> onAccept(Handshake.readAccept(f));
                default -> throw new IllegalArgumentException("not a handshake frame: " + f.kind());
            }
        } catch (FrameException e) {
            context.dropped(e.reason(), peer, e.getMessage());
        }
    }

    private void onAsk(Optional<Handshake.Ask> ask) {
        if (ask.isEmpty()) {
            LOG.debug("node '{}': {} asked for shared memory in a version this node does not speak", context.nodeName(), peer);
        } else if (!usable) {
            LOG.debug("node '{}': {} asked for shared memory; this connection does not use it", context.nodeName(), peer);
        } else if (!ask.get().hostId().equals(hostId)) {
            LOG.debug("node '{}': {} asked for shared memory from host {}, not this one ({})", context.nodeName(), peer, ask.get().hostId(), hostId);
        } else {
            peerAsked = true;
        }
    }

    private void onOffer(Optional<Handshake.Offer> offer, OutboundBuffer out) throws FrameException {
        if (offer.isEmpty()) {
            return;
        }
        if (!asked || view != null) {
            throw new FrameException(DropReason.MALFORMED, "SHM_OFFER " + (view != null ? "after an accepted one" : "that was not asked for"));
        }
        SegmentView v;
        try {
            v = SegmentView.open(SharedSegment.DIRECTORY, offer.get(), peer, context.settings().maxFrameSize());
        } catch (IOException | RuntimeException e) {
            LOG.warn("node '{}': cannot map the shared memory {} offered ({}); its publications keep coming over TCP", context.nodeName(), peer,
                    e.getMessage());
            return;
        }
        view = v;
        try {
            out.send(Handshake.accept(new Handshake.Accept(offer.get().cell(), offer.get().nonce())));
            LOG.debug("node '{}': {}'s large publications come through {}", context.nodeName(), peer, v.file());
        } catch (IOException e) {
            LOG.debug("node '{}': cannot accept {}'s shared memory: {}", context.nodeName(), peer, e.toString());
        }
    }

    private void onAccept(Optional<Handshake.Accept> accept) throws FrameException {
        if (accept.isEmpty()) {
            return;
        }
        SharedSegment.Subscriber s = outlet;
        SharedSegment seg = segment;
        if (s == null || seg == null || accept.get().cell() != s.cell() || accept.get().nonce() != seg.nonce()) {
            throw new FrameException(DropReason.MALFORMED, "SHM_ACCEPT of cell " + accept.get().cell() + ", which was not offered on this connection");
        }
        s.activate();
        accepted = s.active();
        LOG.info("node '{}': large publications go to {} through shared memory ({})", context.nodeName(), peer, seg.file());
    }

    /**
     * Takes a {@link FrameKind#PUBLISH_SHARED} frame's payload out of the peer's segment (reader thread).
     *
     * @return the payload
     * @throws FrameException if this connection accepted no segment, or the reference is bad: the connection ends
     */
    byte[] take(byte[] buf, int offset, int length) throws FrameException {
        SegmentView v = view;
        if (v == null) {
            throw new FrameException(DropReason.MALFORMED, "a shared-memory publication on a connection that accepted no shared memory");
        }
        return v.take(SharedReference.read(buf, offset, length));
    }

    /**
     * Sends a frame through the segment if it may go there: a publication of at least the
     * threshold, without an HMAC, to a peer that accepted. Before the first such frame to a peer
     * that asked, queues the offer (that frame still goes over TCP).
     *
     * @param frame an encoded frame
     * @param out   the connection's queue
     * @return whether it was sent (else the caller sends it over TCP)
     * @throws IOException as the queue's send, or if the segment stayed full
     */
    boolean trySend(byte[] frame, OutboundBuffer out) throws IOException {
        if (!peerAsked || frame.length < threshold || frame[FrameCodec.KIND_OFFSET] != FrameKind.PUBLISH.code()
                || (frame[FrameCodec.FLAGS_OFFSET] & FrameCodec.FLAG_MAC) != 0) {
            return false;
        }
        return throughSegment((seg, to, queue, timeout) -> seg.send(frame, to, queue, timeout), out);
    }

    /**
     * {@link #trySend} of a publication that travels apart from its frame: through the segment, its
     * payload is written into the ring from where it is, and its whole frame is never made.
     *
     * @param publication a publication that {@link Publication#travelsApart() travels apart} (unsigned, sensor-sized)
     * @param out         the connection's queue
     * @return whether it was sent (else the caller sends its frame over TCP)
     * @throws IOException as the queue's send, or if the segment stayed full
     */
    boolean trySend(Publication publication, OutboundBuffer out) throws IOException {
        if (!peerAsked || publication.length() < threshold) {
            return false;
        }
        return throughSegment((seg, to, queue, timeout) -> seg.send(publication, to, queue, timeout), out);
    }

    /** One way into the segment: a whole frame, or a publication that travels apart. */
    private interface SegmentWrite {
        void send(SharedSegment segment, SharedSegment.Subscriber to, SharedSegment.Queue queue, long sendTimeoutNanos) throws IOException;
    }

    /** Writes through the segment once the peer accepted; before, queues the offer (if not yet) and lets the caller use TCP. */
    private boolean throughSegment(SegmentWrite write, OutboundBuffer out) throws IOException {
        if (accepted) {
            write.send(segment, outlet, out::send, sendTimeoutNanos);
            return true;
        }
        offer(out);
        return false;
    }

    private synchronized void offer(OutboundBuffer out) throws IOException {
        if (offered) {
            return;
        }
        offered = true;
        SharedSegment seg = segments.get();
        if (seg == null) {
            return;
        }
        SharedSegment.Subscriber s = seg.attach(lagging);
        if (s == null) {
            LOG.debug("node '{}': every cell of {} is taken; {} gets its publications over TCP", context.nodeName(), seg.file(), peer);
            return;
        }
        segment = seg;
        outlet = s;
        out.send(Handshake.offer(new Handshake.Offer(s.cell(), seg.nonce(), seg.file())));
    }

    /** The connection closed: the peer stops counting in this node's segment. */
    void closePublisher() {
        accepted = false;
        SharedSegment.Subscriber s = outlet;
        if (s != null) {
            s.detach();
        }
    }

    /** The connection's reader ends: drops the mapping of the peer's segment. Reader thread only. */
    void closeView() {
        SegmentView v = view;
        view = null;
        if (v != null) {
            v.close();
        }
    }
}
