package io.robomw.agents.messaging;

import io.robomw.agents.messaging.frame.Frame;
import io.robomw.agents.messaging.frame.FrameCodec;
import io.robomw.agents.messaging.frame.FrameKind;
import io.robomw.agents.messaging.frame.NameBytes;
import io.robomw.agents.messaging.security.FrameMac;
import io.robomw.agents.messaging.security.PayloadCodec;
import io.robomw.agents.messaging.spi.Publication;
import io.robomw.api.MessagingException;

import javax.crypto.SecretKey;
import java.io.Serializable;
import java.time.Instant;
import java.util.UUID;
import java.util.concurrent.atomic.AtomicLong;

/**
 * Makes a node's outgoing frames: numbers them (the node's random source id and a message
 * number, which together are also the correlation id of a new request), stamps the time,
 * encodes the payload, checks the frame size, and for password-protected topics seals the payload
 * (AES-256-GCM, {@link io.robomw.agents.messaging.security.PayloadSealer}) and signs the frame.
 * Thread-safe.
 */
final class FrameFactory {

    /** A frame and the number it was given. @param number its message number @param bytes the encoded frame */
    record Made(long number, byte[] bytes) {
    }

    private final String node;
    private final long source;
    private final AtomicLong numbers = new AtomicLong();
    private final PayloadCodec payloads;
    private final FrameMac mac;
    private final io.robomw.agents.messaging.security.PayloadSealer sealer;
    private final int maxFrameSize;
    /** UTF-8 of the names this node sends (its own, topics, functions, receivers): the same few, over and over. */
    private final NameBytes names = new NameBytes();

    FrameFactory(String node, long source, PayloadCodec payloads, FrameMac mac, io.robomw.agents.messaging.security.PayloadSealer sealer,
            int maxFrameSize) {
        this.node = node;
        this.source = source;
        this.payloads = payloads;
        this.mac = mac;
        this.sealer = sealer;
        this.maxFrameSize = maxFrameSize;
    }

    /**
     * A new message (a request or a publication): its correlation id is its own id.
     *
     * @return the frame and its number ({@link #correlationId} gives the id)
     */
    Made message(FrameKind kind, String receiver, String topic, Serializable object, String function, SecretKey key) {
        long n = numbers.incrementAndGet();
        return new Made(n, encode(kind, n, correlationId(n), receiver, topic, object, function, key));
    }

    /** An answer (reply or error) to the request with {@code correlationId}. */
    byte[] answer(FrameKind kind, UUID correlationId, String receiver, String topic, Serializable object, String function, SecretKey key) {
        return encode(kind, numbers.incrementAndGet(), correlationId, receiver, topic, object, function, key);
    }

    /**
     * A new publication: as {@link #message} of a {@code PUBLISH}, but one without a password whose
     * payload is sensor-sized is not encoded into a frame yet: it may travel apart ({@link Publication}).
     */
    Publication publication(String topic, Serializable object, String function, SecretKey key) {
        if (key != null) {
            return Publication.whole(message(FrameKind.PUBLISH, "", topic, object, function, key).bytes());
        }
        long n = numbers.incrementAndGet();
        Frame f = frame(FrameKind.PUBLISH, n, correlationId(n), "", topic, object, function, null);
        if (f.payload().length < Publication.APART_FROM_BYTES) {
            return Publication.whole(checked(FrameCodec.encode(f, false, false, names), topic));
        }
        Publication p = Publication.apart(f, names);
        checked(p.length(), topic);
        return p;
    }

    /** A subscription or unsubscription for {@code topic}. */
    byte[] control(FrameKind kind, String topic) {
        return message(kind, "", topic, null, "", null).bytes();
    }

    /** @return the correlation id of the message numbered {@code number} */
    UUID correlationId(long number) {
        return new UUID(source, number);
    }

    /** @return now, in microseconds since the epoch, as frames carry it */
    static long nowMicros() {
        Instant now = Instant.now();
        return now.getEpochSecond() * 1_000_000L + now.getNano() / 1000;
    }

    private byte[] encode(FrameKind kind, long number, UUID correlationId, String receiver, String topic, Serializable object,
                          String function, SecretKey key) {
        Frame f = frame(kind, number, correlationId, receiver, topic, object, function, key);
        byte[] bytes = checked(FrameCodec.encode(f, key != null, key != null, names), topic);
        if (key != null) {
            mac.sign(key, bytes);
        }
        return bytes;
    }

    /** @return the frame, its payload encoded (and sealed with a key), not yet encoded itself */
    private Frame frame(FrameKind kind, long number, UUID correlationId, String receiver, String topic, Serializable object,
                        String function, SecretKey key) {
        PayloadCodec.Encoded payload;
        try {
            payload = payloads.encode(object);
        } catch (IllegalArgumentException e) {
            throw new MessagingException("node '" + node + "' cannot send on topic '" + topic + "': " + e.getMessage(), e);
        }
        byte[] body = key == null ? payload.bytes() : sealer.seal(key, source, number, payload.bytes());
        return new Frame(kind, 0, source, number, correlationId, nowMicros(), node, receiver, topic,
                function == null ? "" : function, payload.type(), body, key != null);
    }

    /** @return the frame, if it is within the maximum frame size */
    private byte[] checked(byte[] frame, String topic) {
        checked(frame.length, topic);
        return frame;
    }

    private void checked(long length, String topic) {
        if (length > maxFrameSize) {
            throw new MessagingException("node '" + node + "': a frame on topic '" + topic + "' would be " + length
                    + " bytes, above the maximum frame size of " + maxFrameSize + "; send less, or raise maxFrameSize on both sides");
        }
    }
}
