package io.robomw.agents.messaging;

import java.time.Duration;
import java.util.Objects;

/**
 * What one messaging node lets its peers make it hold, and for how long. Every peer that can open
 * a connection can use these, without a password, so each is bounded; what passes a bound is
 * refused (a connection gets a refusal frame naming the limit, then is closed; a subscription is
 * dropped and counted as {@link DropReason#LIMIT}) and the node keeps serving the others.
 *
 * @param maxConnections          connections (TCP) and sessions (RMI) accepted at once, per endpoint; each
 *                                costs two threads and up to {@code outboundBufferBytes} of memory
 * @param maxSubscriptionsPerPeer topics one peer may subscribe to at once
 * @param maxSubscriptions        subscriptions of all peers together
 * @param maxTopicBytes           the longest topic a peer may subscribe to, in UTF-8 bytes
 * @param firstFrameTimeout       how long an accepted connection may take to deliver its first whole frame
 *                                (with TLS, the handshake included)
 * @param idleTimeout             how long a connection may go without delivering a whole frame; a peer that
 *                                stops in the middle of a frame, or trickles bytes, is closed after it. Healthy
 *                                quiet links are kept open by keep-alive frames sent after a third of it
 */
public record PeerLimits(int maxConnections, int maxSubscriptionsPerPeer, int maxSubscriptions, int maxTopicBytes,
                         Duration firstFrameTimeout, Duration idleTimeout) {

    /** Checks the values. */
    public PeerLimits {
        atLeast("maxConnections", maxConnections, 1);
        atLeast("maxSubscriptionsPerPeer", maxSubscriptionsPerPeer, 1);
        atLeast("maxSubscriptions", maxSubscriptions, maxSubscriptionsPerPeer);
        atLeast("maxTopicBytes", maxTopicBytes, 1);
        Objects.requireNonNull(firstFrameTimeout, "firstFrameTimeout");
        Objects.requireNonNull(idleTimeout, "idleTimeout");
        if (firstFrameTimeout.toMillis() < 100 || idleTimeout.toMillis() < 300) {
            throw new IllegalArgumentException("firstFrameTimeout must be >= 100 ms and idleTimeout >= 300 ms, got "
                    + firstFrameTimeout + " and " + idleTimeout);
        }
        if (idleTimeout.toMillis() > Integer.MAX_VALUE || firstFrameTimeout.toMillis() > Integer.MAX_VALUE) {
            throw new IllegalArgumentException("timeouts must be below 24 days, got " + firstFrameTimeout + " and " + idleTimeout);
        }
    }

    /**
     * @return 128 connections, 1,024 subscriptions per peer and 16,384 in all, topics up to 1,024
     *         bytes, the first frame within 10 s, a whole frame at least every 60 s (keep-alives
     *         after 20 s of silence)
     */
    public static PeerLimits defaults() {
        return new PeerLimits(128, 1024, 16_384, 1024, Duration.ofSeconds(10), Duration.ofSeconds(60));
    }

    /** @return how long a link may be silent before it sends a keep-alive: a third of the idle timeout */
    public Duration keepAliveInterval() {
        return idleTimeout.dividedBy(3);
    }

    /** @param v the maximum number of connections @return a copy with it */
    public PeerLimits withMaxConnections(int v) {
        return new PeerLimits(v, maxSubscriptionsPerPeer, maxSubscriptions, maxTopicBytes, firstFrameTimeout, idleTimeout);
    }

    /** @param perPeer subscriptions per peer @param total subscriptions in all @return a copy with them */
    public PeerLimits withMaxSubscriptions(int perPeer, int total) {
        return new PeerLimits(maxConnections, perPeer, total, maxTopicBytes, firstFrameTimeout, idleTimeout);
    }

    /** @param v the longest topic, in UTF-8 bytes @return a copy with it */
    public PeerLimits withMaxTopicBytes(int v) {
        return new PeerLimits(maxConnections, maxSubscriptionsPerPeer, maxSubscriptions, v, firstFrameTimeout, idleTimeout);
    }

    /** @param firstFrame the first-frame timeout @param idle the idle timeout @return a copy with them */
    public PeerLimits withTimeouts(Duration firstFrame, Duration idle) {
        return new PeerLimits(maxConnections, maxSubscriptionsPerPeer, maxSubscriptions, maxTopicBytes, firstFrame, idle);
    }

    private static void atLeast(String name, int value, int min) {
        if (value < min) {
            throw new IllegalArgumentException(name + " must be >= " + min + ", got " + value);
        }
    }
}
