package io.robomw.agents.messaging;

import io.robomw.agents.messaging.frame.Frame;
import io.robomw.agents.messaging.frame.FrameCodec;
import io.robomw.agents.messaging.frame.FrameException;
import io.robomw.agents.messaging.frame.FrameKind;
import io.robomw.agents.messaging.frame.NameCache;
import io.robomw.agents.messaging.security.FrameMac;
import io.robomw.agents.messaging.security.PayloadCodec;
import io.robomw.agents.messaging.security.PayloadRejectedException;
import io.robomw.agents.messaging.security.ReplayGuard;
import io.robomw.agents.messaging.spi.Channel;
import io.robomw.agents.net.OwnerThreads;
import io.robomw.api.Message;
import io.robomw.api.MessageListener;
import io.robomw.api.spi.FailurePolicy;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import javax.crypto.SecretKey;
import java.io.Serializable;
import java.time.Instant;
import java.util.List;

/**
 * What a node does with each received frame, in this order: decode it; ignore its own frames
 * (multicast loops them back); count datagram losses; then by kind: record a (un)subscription;
 * or find the topic (or, for a reply, the request), check the receiver's name, authenticate
 * (HMAC, freshness, replay, also across restarts) if the topic has a password, open its sealed
 * payload (AES-256-GCM under the password; a sealed payload on a topic registered without one is
 * dropped as {@link DropReason#ENCRYPTED}), deserialize the payload through the allow-list, and
 * deliver it. Every refusal is counted and logged; refused requests get an
 * {@link FrameKind#ERROR} answer when it is safe to tell: a request with a missing or wrong
 * password is told so (nothing more), a stale or replayed frame is not answered.
 *
 * <p>Runs on the transports' receiving threads; listeners run there too.
 */
final class Inbound {

    private static final Logger LOG = LoggerFactory.getLogger(Inbound.class);

    private final MessagingNode node;
    private final NodeCounters counters;
    private final LossDetector losses;
    private final ReplayGuard replays = new ReplayGuard();
    private final io.robomw.agents.messaging.security.ReplayStore store;
    private final io.robomw.agents.messaging.security.PayloadSealer sealer;
    /** Per reading thread; a topic's name decoded from a frame is the very String the topic is registered under, when it is. */
    private final ThreadLocal<NameCache> names;
    private final FrameMac mac;
    private final PayloadCodec payloads;
    private final int maxFrameSize;
    private final int maxTopicBytes;
    private final long maxSkewMicros;
    private final FailurePolicy failures;

    Inbound(MessagingNode node, NodeCounters counters, FrameMac mac, PayloadCodec payloads, MessagingSettings settings, FailurePolicy failures,
            io.robomw.agents.messaging.security.PayloadSealer sealer, io.robomw.agents.messaging.security.ReplayStore store) {
        this.node = node;
        this.failures = failures;
        this.sealer = sealer;
        this.store = store;
        this.counters = counters;
        this.losses = new LossDetector(counters);
        this.mac = mac;
        this.payloads = payloads;
        this.maxFrameSize = settings.maxFrameSize();
        this.maxTopicBytes = settings.limits().maxTopicBytes();
        this.maxSkewMicros = settings.maxClockSkew().toNanos() / 1000;
        this.names = ThreadLocal.withInitial(() -> new NameCache(this::canonical));
    }

    /** @return the String a topic of that name is registered under here, else the name */
    private String canonical(String name) {
        LocalTopics.Topic t = node.topics().get(name);
        return t == null ? name : t.name;
    }

    /**
     * @param shared the payload of a {@link FrameKind#PUBLISH_SHARED} frame, as the transport took it
     *               out of the peer's shared memory; {@code null} for any other frame
     */
    void onFrame(byte[] buf, int offset, int length, byte[] shared, Channel from) {
        try {
            Frame f = FrameCodec.decode(buf, offset, length, maxFrameSize, names.get());
            if (f.source() == node.id()) {
                return;
            }
            if (!from.isConnection()) {
                losses.observe(from.peer(), f.source(), f.streamSequence());
            }
            switch (f.kind()) {
                case SUBSCRIBE -> subscribe(f, from);
                case UNSUBSCRIBE -> node.remoteSubscribers().unsubscribe(f.topic(), from);
                case MESSAGE, PUBLISH -> onMessage(f, buf, offset, length, from);
                case PUBLISH_SHARED -> {
                    if (shared == null) {
                        throw new FrameException(DropReason.MALFORMED, "a shared-memory publication on a link that has no shared memory");
                    }
                    // the PUBLISH it stands for; never authenticated (frames with an HMAC do not go through shared memory)
                    onMessage(new Frame(FrameKind.PUBLISH, f.streamSequence(), f.source(), f.messageNumber(), f.correlationId(), f.timestampMicros(),
                            f.sender(), f.receiver(), f.topic(), f.function(), f.payloadType(), shared, false), buf, offset, length, from);
                }
                case SHM_ASK, SHM_OFFER, SHM_ACCEPT -> throw new FrameException(DropReason.MALFORMED, f.kind()
                        + " on a link that has no shared memory (only plain TCP connections have)");
                case REPLY, ERROR -> onReply(f, buf, offset, length, from);
                case KEEPALIVE -> {
                    // its arrival is all it says (the transport has seen a whole frame)
                }
                default -> throw new IllegalStateException("unhandled kind " + f.kind());
            }
        } catch (FrameException e) {
            counters.drop(e.reason(), from.peer(), e.getMessage());
        } catch (Throwable e) {
            // a failure of this frame's handling, not the link's: the frame is dropped, the thread goes on
            failures.surviveOrRethrow(OwnerThreads.current(), e);
            counters.drop(DropReason.MALFORMED, from.peer(), "frame could not be handled: " + e);
        }
    }

    private void subscribe(Frame f, Channel from) {
        int topicBytes = f.topic().getBytes(java.nio.charset.StandardCharsets.UTF_8).length;
        if (topicBytes > maxTopicBytes) {
            counters.drop(DropReason.LIMIT, from.peer(), "subscription to a topic of " + topicBytes + " bytes, above the "
                    + maxTopicBytes + " allowed (maxTopicBytes)");
            return;
        }
        String refused = node.remoteSubscribers().subscribe(f.topic(), from, System.nanoTime());
        if (refused != null) {
            counters.drop(DropReason.LIMIT, from.peer(), "subscription to '" + shorten(f.topic()) + "' refused: " + refused);
        }
    }

    private static String shorten(String topic) {
        return topic.length() <= 80 ? topic : topic.substring(0, 80) + "... (" + topic.length() + " characters)";
    }

    private void onMessage(Frame f, byte[] buf, int offset, int length, Channel from) throws FrameException {
        boolean request = f.kind() == FrameKind.MESSAGE;
        LocalTopics.Topic topic = node.topics().get(f.topic());
        if (topic == null || (!request && !topic.subscribed) || (request && topic.listeners.isEmpty())) {
            if (request && !from.isGroup()) {
                counters.drop(DropReason.NO_LISTENER, from.peer(), "message for topic '" + f.topic() + "', which nobody here listens to");
                refuse(f, from, "no listener for topic '" + f.topic() + "' at node '" + node.name() + "'" + siblings(f.topic()));
            } else {
                counters.dropQuietly(DropReason.NO_LISTENER);
            }
            return;
        }
        if (request && !node.answersTo(f.receiver())) {
            if (from.isGroup()) {
                counters.dropQuietly(DropReason.UNKNOWN_RECEIVER);
                return;
            }
            counters.drop(DropReason.UNKNOWN_RECEIVER, from.peer(), "message for '" + f.receiver() + "'; this node answers to " + node.names());
            refuse(f, from, "no receiver named '" + f.receiver() + "' here; this node answers to " + node.names());
            return;
        }
        try {
            authenticate(topic.key, f, buf, offset, length, from);
        } catch (FrameException e) {
            // counted before the sender is told: whoever reads the answer finds the drop counted
            counters.drop(e.reason(), from.peer(), e.getMessage());
            if (request && !from.isGroup() && (e.reason() == DropReason.MISSING_MAC || e.reason() == DropReason.BAD_MAC)) {
                // The sender is told its password was refused (as HTTP's 401 would), never why in more detail:
                // a wrong password learns nothing it could not learn from the missing reply.
                refuse(f, from, "refused by node '" + node.name() + "': topic '" + f.topic() + "' is password-protected and the message "
                        + (e.reason() == DropReason.MISSING_MAC ? "had no password" : "had a wrong password"));
            }
            return;
        }
        byte[] body;
        try {
            body = opened(topic.key, f, buf, offset);
        } catch (FrameException e) {
            counters.drop(e.reason(), from.peer(), e.getMessage());
            if (request && !from.isGroup() && e.reason() == DropReason.ENCRYPTED) {
                refuse(f, from, "refused by node '" + node.name() + "': topic '" + f.topic() + "' has no password here, and the message was"
                        + " encrypted under one");
            }
            return;
        }
        Serializable payload;
        try {
            payload = payloads.decode(f.payloadType(), body);
        } catch (PayloadRejectedException e) {
            counters.drop(DropReason.REJECTED_CLASS, from.peer(), "topic '" + f.topic() + "' from '" + f.sender() + "': " + e.getMessage());
            if (request) {
                refuse(f, from, e.getMessage());
            }
            return;
        }
        Message message = new Message(f.sender(), f.topic(), f.function(), payload, f.correlationId(), instant(f.timestampMicros()));
        if (request) {
            node.receivedRequests().put(f.correlationId(), new MessagingNode.Origin(from, topic.key));
        }
        counters.in();
        for (MessageListener listener : topic.listeners) {
            try {
                listener.onMessage(message);
            } catch (Throwable e) {
                // A listener's failure (an agent's code: an exception or an error it can cause) is its own, not the connection's.
                failures.surviveOrRethrow(OwnerThreads.current(), e);
                counters.listenerError();
                LOG.warn("node '{}': a listener of topic '{}' failed on a message from '{}': {}", node.name(), f.topic(), f.sender(), e.toString());
            }
        }
    }

    private void onReply(Frame f, byte[] buf, int offset, int length, Channel from) throws FrameException {
        if (f.kind() == FrameKind.ERROR && f.correlationId().getMostSignificantBits() == 0 && f.correlationId().getLeastSignificantBits() == 0
                && from.isConnection()) {
            Serializable why;
            try {
                why = payloads.decode(f.payloadType(), f.payload());
            } catch (PayloadRejectedException e) {
                why = "(an unreadable reason)";
            }
            node.refusedBy(from, String.valueOf(why));
            return;
        }
        MessagingNode.Sent sent = node.sentRequests().get(f.correlationId());
        if (sent == null) {
            counters.drop(DropReason.UNSOLICITED_REPLY, from.peer(), "reply " + f.correlationId() + " to no request sent from here");
            return;
        }
        if (f.kind() != FrameKind.ERROR || f.authenticated()) {
            // A refusal may come unsigned (the refusing node may not know the topic's password); it
            // can only fail the request, never deliver data, so it is accepted as it is.
            authenticate(sent.key(), f, buf, offset, length, from);
        }
        Serializable payload;
        try {
            payload = payloads.decode(f.payloadType(), opened(f.authenticated() ? sent.key() : null, f, buf, offset));
        } catch (PayloadRejectedException e) {
            counters.drop(DropReason.REJECTED_CLASS, from.peer(), "reply on topic '" + f.topic() + "' from '" + f.sender() + "': " + e.getMessage());
            return;
        }
        Message message = new Message(f.sender(), f.topic(), f.function(), payload, f.correlationId(), instant(f.timestampMicros()));
        counters.in();
        String error = f.kind() == FrameKind.ERROR ? String.valueOf(payload) : null;
        node.replies().arrived(new Replies.Reply(message, sent.host(), error));
    }

    private void authenticate(SecretKey key, Frame f, byte[] buf, int offset, int length, Channel from) throws FrameException {
        if (key == null) {
            return;
        }
        if (!f.authenticated()) {
            throw new FrameException(DropReason.MISSING_MAC, "topic '" + f.topic() + "' is password-protected and the frame from '"
                    + f.sender() + "' has no HMAC");
        }
        if (!mac.verify(key, buf, offset, length)) {
            throw new FrameException(DropReason.BAD_MAC, "HMAC check failed on topic '" + f.topic() + "' from '" + f.sender()
                    + "' (wrong password, or the frame was altered)");
        }
        if (!ReplayGuard.fresh(f.timestampMicros(), MessagingNode.nowMicros(), maxSkewMicros)) {
            throw new FrameException(DropReason.STALE, "frame from '" + f.sender() + "' is timestamped " + instant(f.timestampMicros())
                    + ", further than " + maxSkewMicros / 1_000_000 + " s from this host's clock");
        }
        // Only requests and publications are kept across restarts: a reply is taken only for a request sent from here, so a
        // replayed one finds none (UNSOLICITED_REPLY), restart or not.
        boolean kept = f.kind() == FrameKind.MESSAGE || f.kind() == FrameKind.PUBLISH;
        if (kept && f.messageNumber() <= store.floor(f.source())) {
            throw new FrameException(DropReason.REPLAYED, "frame " + f.messageNumber() + " of source " + Long.toHexString(f.source())
                    + " from '" + f.sender() + "' was already received, before this node restarted");
        }
        if (!replays.accept(f.source(), f.messageNumber())) {
            throw new FrameException(DropReason.REPLAYED, "frame " + f.messageNumber() + " of source " + Long.toHexString(f.source())
                    + " from '" + f.sender() + "' was already received");
        }
        if (kept) {
            store.record(f.source(), f.messageNumber(), System.currentTimeMillis());
        }
    }

    /**
     * @param key the topic's key, or {@code null} if this node has none for it
     * @return the frame's payload, opened if it is sealed
     * @throws FrameException if it is sealed and this node has no key for it, or it does not open under the key
     */
    private byte[] opened(SecretKey key, Frame f, byte[] buf, int offset) throws FrameException {
        if (!FrameCodec.sealed(buf, offset)) {
            return f.payload();
        }
        if (key == null) {
            throw new FrameException(DropReason.ENCRYPTED, "topic '" + f.topic() + "' from '" + f.sender() + "' is encrypted under a password;"
                    + " this node registered it without one (give the password to addMessageListener/subscribeMessage)");
        }
        byte[] plain = sealer.open(key, f.source(), f.messageNumber(), f.payload());
        if (plain == null) {
            throw new FrameException(DropReason.BAD_MAC, "the payload on topic '" + f.topic() + "' from '" + f.sender() + "' does not decrypt");
        }
        return plain;
    }

    /**
     * @return the topics here under the same first level as a topic nobody listens to ("; topics
     *         under 'robot/' here: robot/sim-1"), so that a sender who misspelled a robot's or
     *         agent's name learns the right ones; empty for a topic without levels
     */
    private String siblings(String topic) {
        int slash = topic.indexOf('/');
        if (slash <= 0) {
            return "";
        }
        String level = topic.substring(0, slash + 1);
        List<String> near = node.topics().names().stream().filter(t -> t.startsWith(level) && t.length() > level.length()).limit(20).toList();
        return near.isEmpty() ? "; no topic under '" + level + "' here" : "; topics under '" + level + "' here: " + String.join(", ", near);
    }

    private void refuse(Frame f, Channel from, String why) {
        node.sendError(f, from, why);
    }

    static Instant instant(long micros) {
        return Instant.ofEpochSecond(Math.floorDiv(micros, 1_000_000L), Math.floorMod(micros, 1_000_000L) * 1000);
    }
}
