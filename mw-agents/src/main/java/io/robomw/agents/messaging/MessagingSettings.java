package io.robomw.agents.messaging;

import io.robomw.agents.messaging.security.PayloadAllowList;
import io.robomw.agents.messaging.security.TlsSettings;
import io.robomw.agents.messaging.shm.SharedMemorySettings;

import java.time.Duration;
import java.util.Objects;
import java.util.Optional;

/**
 * How a messaging node behaves. Start from {@link #defaults()} and change what you need with the
 * {@code with...} methods; every instance is immutable.
 *
 * @param replyTimeout        how long {@code waitForReply(topic, host)} waits (the paper's form has no timeout argument)
 * @param connectTimeout      how long opening a connection may take
 * @param sendTimeout         how long a send may wait for a peer that does not read; then that link is closed
 * @param maxFrameSize        the largest frame sent or accepted, in bytes (UDP and multicast are further limited to one datagram)
 * @param outboundBufferBytes how many bytes may wait to be written to one peer
 * @param multicastInterface  the network interface multicast is sent and received on (name or address);
 *                            {@code null} means the loopback interface, so nothing leaves the host unless asked
 * @param multicastTtl        multicast time-to-live: 0 stays on this host, 1 on the local network
 * @param maxClockSkew        authenticated frames whose timestamp is further from this host's clock are dropped as stale
 * @param subscriptionRefresh how often subscriptions over UDP are repeated (they expire after 5 missed refreshes)
 * @param tls                 mutual TLS for TCP and RMI, or {@code null} for plain connections
 * @param allowList           the classes payload objects may contain
 * @param replySpin           how long a thread waiting for a reply spins before it parks (a reply on loopback or a LAN
 *                            often comes sooner, and waking a parked thread can cost tens of microseconds); zero never
 *                            spins: over plain TCP the waiting thread then reads the link itself while no other thread
 *                            does, so the reply wakes it directly (docs/messaging.md, "Performance")
 * @param limits              what peers may make the node hold: connections, subscriptions, topic length, and the
 *                            first-frame and idle timeouts of connections ({@link PeerLimits})
 * @param sharedMemory        whether large publications go to subscribers on the same host through shared memory
 *                            (on by default; never with TLS or for frames with an HMAC; docs/messaging.md, "Shared memory")
 */
public record MessagingSettings(Duration replyTimeout, Duration connectTimeout, Duration sendTimeout, int maxFrameSize,
                                int outboundBufferBytes, String multicastInterface, int multicastTtl, Duration maxClockSkew,
                                Duration subscriptionRefresh, TlsSettings tls, PayloadAllowList allowList, Duration replySpin,
                                PeerLimits limits, SharedMemorySettings sharedMemory) {

    /** Largest payload of one UDP datagram over IPv4. */
    public static final int MAX_DATAGRAM = 65_507;

    /** Checks the values. */
    public MessagingSettings {
        positive("replyTimeout", replyTimeout);
        positive("connectTimeout", connectTimeout);
        positive("sendTimeout", sendTimeout);
        positive("maxClockSkew", maxClockSkew);
        positive("subscriptionRefresh", subscriptionRefresh);
        Objects.requireNonNull(allowList, "allowList");
        Objects.requireNonNull(replySpin, "replySpin");
        Objects.requireNonNull(limits, "limits");
        Objects.requireNonNull(sharedMemory, "sharedMemory");
        if (replySpin.isNegative()) {
            throw new IllegalArgumentException("replySpin must be >= 0, got " + replySpin);
        }
        if (maxFrameSize < 1024) {
            throw new IllegalArgumentException("maxFrameSize must be >= 1024 bytes, got " + maxFrameSize);
        }
        if (outboundBufferBytes < maxFrameSize) {
            throw new IllegalArgumentException("outboundBufferBytes (" + outboundBufferBytes + ") must be >= maxFrameSize (" + maxFrameSize + ")");
        }
        if (multicastTtl < 0 || multicastTtl > 255) {
            throw new IllegalArgumentException("multicastTtl must be 0..255, got " + multicastTtl);
        }
    }

    /**
     * @return reply timeout 5 s, connect timeout 5 s, send timeout 10 s, frames up to 1 MiB, 4 MiB
     *         buffered per peer, multicast on loopback with TTL 0, clock skew 5 min, UDP
     *         subscriptions refreshed every second, no TLS, JDK value types only, replies awaited
     *         with a 50 µs spin, the peer limits of {@link PeerLimits#defaults()}, and shared memory
     *         for large publications to subscribers on the same host ({@link SharedMemorySettings#defaults()})
     */
    public static MessagingSettings defaults() {
        return new MessagingSettings(Duration.ofSeconds(5), Duration.ofSeconds(5), Duration.ofSeconds(10), 1 << 20, 4 << 20,
                null, 0, Duration.ofMinutes(5), Duration.ofSeconds(1), null, PayloadAllowList.jdkDefaults(), Duration.ofNanos(50_000),
                PeerLimits.defaults(), SharedMemorySettings.defaults());
    }

    /** @return the TLS settings, if TLS is on */
    public Optional<TlsSettings> tlsSettings() {
        return Optional.ofNullable(tls);
    }

    /** @param v the reply timeout @return a copy with it */
    public MessagingSettings withReplyTimeout(Duration v) {
        return new MessagingSettings(v, connectTimeout, sendTimeout, maxFrameSize, outboundBufferBytes, multicastInterface, multicastTtl, maxClockSkew, subscriptionRefresh, tls, allowList, replySpin, limits, sharedMemory);
    }

    /** @param v the connect timeout @return a copy with it */
    public MessagingSettings withConnectTimeout(Duration v) {
        return new MessagingSettings(replyTimeout, v, sendTimeout, maxFrameSize, outboundBufferBytes, multicastInterface, multicastTtl, maxClockSkew, subscriptionRefresh, tls, allowList, replySpin, limits, sharedMemory);
    }

    /** @param v the send timeout @return a copy with it */
    public MessagingSettings withSendTimeout(Duration v) {
        return new MessagingSettings(replyTimeout, connectTimeout, v, maxFrameSize, outboundBufferBytes, multicastInterface, multicastTtl, maxClockSkew, subscriptionRefresh, tls, allowList, replySpin, limits, sharedMemory);
    }

    /** @param v the maximum frame size in bytes @return a copy with it (and a buffer of at least that) */
    public MessagingSettings withMaxFrameSize(int v) {
        return new MessagingSettings(replyTimeout, connectTimeout, sendTimeout, v, Math.max(v, outboundBufferBytes), multicastInterface, multicastTtl, maxClockSkew, subscriptionRefresh, tls, allowList, replySpin, limits, sharedMemory);
    }

    /** @param name the multicast interface's name or address @param ttl the multicast TTL @return a copy with them */
    public MessagingSettings withMulticast(String name, int ttl) {
        return new MessagingSettings(replyTimeout, connectTimeout, sendTimeout, maxFrameSize, outboundBufferBytes, name, ttl, maxClockSkew, subscriptionRefresh, tls, allowList, replySpin, limits, sharedMemory);
    }

    /** @param v the maximum clock skew @return a copy with it */
    public MessagingSettings withMaxClockSkew(Duration v) {
        return new MessagingSettings(replyTimeout, connectTimeout, sendTimeout, maxFrameSize, outboundBufferBytes, multicastInterface, multicastTtl, v, subscriptionRefresh, tls, allowList, replySpin, limits, sharedMemory);
    }

    /** @param v how often UDP subscriptions are refreshed @return a copy with it */
    public MessagingSettings withSubscriptionRefresh(Duration v) {
        return new MessagingSettings(replyTimeout, connectTimeout, sendTimeout, maxFrameSize, outboundBufferBytes, multicastInterface, multicastTtl, maxClockSkew, v, tls, allowList, replySpin, limits, sharedMemory);
    }

    /** @param v TLS settings, or {@code null} for none @return a copy with them */
    public MessagingSettings withTls(TlsSettings v) {
        return new MessagingSettings(replyTimeout, connectTimeout, sendTimeout, maxFrameSize, outboundBufferBytes, multicastInterface, multicastTtl, maxClockSkew, subscriptionRefresh, v, allowList, replySpin, limits, sharedMemory);
    }

    /** @param v the allow-list @return a copy with it */
    public MessagingSettings withAllowList(PayloadAllowList v) {
        return new MessagingSettings(replyTimeout, connectTimeout, sendTimeout, maxFrameSize, outboundBufferBytes, multicastInterface, multicastTtl, maxClockSkew, subscriptionRefresh, tls, v, replySpin, limits, sharedMemory);
    }

    /** @param v how long a waiting thread spins before parking; zero never spins @return a copy with it */
    public MessagingSettings withReplySpin(Duration v) {
        return new MessagingSettings(replyTimeout, connectTimeout, sendTimeout, maxFrameSize, outboundBufferBytes, multicastInterface, multicastTtl, maxClockSkew, subscriptionRefresh, tls, allowList, v, limits, sharedMemory);
    }

    /** @param v what peers may make the node hold @return a copy with it */
    public MessagingSettings withLimits(PeerLimits v) {
        return new MessagingSettings(replyTimeout, connectTimeout, sendTimeout, maxFrameSize, outboundBufferBytes, multicastInterface, multicastTtl, maxClockSkew, subscriptionRefresh, tls, allowList, replySpin, v, sharedMemory);
    }

    /** @param v whether and how large publications go through shared memory @return a copy with it */
    public MessagingSettings withSharedMemory(SharedMemorySettings v) {
        return new MessagingSettings(replyTimeout, connectTimeout, sendTimeout, maxFrameSize, outboundBufferBytes, multicastInterface, multicastTtl, maxClockSkew, subscriptionRefresh, tls, allowList, replySpin, limits, v);
    }

    /**
     * @param on whether large publications go to subscribers on the same host through shared memory (default on)
     * @return a copy with it
     */
    public MessagingSettings withSharedMemory(boolean on) {
        return withSharedMemory(sharedMemory.withEnabled(on));
    }

    /** @param types application payload types to allow @return a copy whose allow-list has them too */
    public MessagingSettings allowPayloadTypes(Class<?>... types) {
        return withAllowList(allowList.with(types));
    }

    private static void positive(String name, Duration d) {
        Objects.requireNonNull(d, name);
        if (d.isNegative() || d.isZero()) {
            throw new IllegalArgumentException(name + " must be > 0, got " + d);
        }
    }
}
