package io.robomw.agents.messaging.frame;

import io.robomw.agents.messaging.DropReason;

import java.lang.invoke.MethodHandles;
import java.lang.invoke.VarHandle;
import java.nio.ByteOrder;
import java.nio.charset.StandardCharsets;
import java.util.UUID;

/**
 * The RoboMW frame: one message, request, reply or subscription on any transport. All integers
 * are big-endian; lengths are unsigned.
 *
 * <pre>
 *  0                   1                   2                   3
 *  0 1 2 3 4 5 6 7 8 9 0 1 2 3 4 5 6 7 8 9 0 1 2 3 4 5 6 7 8 9 0 1
 * +-------------------------------+---------------+---------------+
 * |         MAGIC 'R' 'M'         |   VERSION 1   |     KIND      |  0
 * +-------------------------------+---------------+---------------+
 * |                FRAME LENGTH (whole frame, with MAC)           |  4
 * +---------------------------------------------------------------+
 * |           STREAM SEQUENCE (per link; NOT covered by the MAC)  |  8
 * |                                                               |
 * +---------------+---------------+-------------------------------+
 * |     FLAGS     | PAYLOAD TYPE  |         SENDER LENGTH         | 16
 * +---------------+---------------+-------------------------------+
 * |        RECEIVER LENGTH        |          TOPIC LENGTH         | 20
 * +-------------------------------+-------------------------------+
 * |        FUNCTION LENGTH        |          RESERVED 0           | 24
 * +-------------------------------+-------------------------------+
 * |                        PAYLOAD LENGTH                         | 28
 * +---------------------------------------------------------------+
 * |                 SOURCE (random id of the sending node)        | 32
 * +---------------------------------------------------------------+
 * |                 MESSAGE NUMBER (per source)                   | 40
 * +---------------------------------------------------------------+
 * |                 CORRELATION ID (128 bits)                     | 48
 * +---------------------------------------------------------------+
 * |                 TIMESTAMP (microseconds since the epoch)      | 64
 * +---------------------------------------------------------------+
 * | SENDER | RECEIVER | TOPIC | FUNCTION (UTF-8) | PAYLOAD        | 72
 * +---------------------------------------------------------------+
 * | HMAC-SHA256 (32 bytes), present when FLAGS has {@link #FLAG_MAC} |
 * +---------------------------------------------------------------+
 * </pre>
 *
 * <table>
 * <caption>KIND codes ({@link FrameKind})</caption>
 * <tr><th>code</th><th>kind</th></tr>
 * <tr><td>1</td><td>MESSAGE</td></tr>
 * <tr><td>2</td><td>REPLY</td></tr>
 * <tr><td>3</td><td>ERROR</td></tr>
 * <tr><td>4</td><td>PUBLISH</td></tr>
 * <tr><td>5</td><td>SUBSCRIBE</td></tr>
 * <tr><td>6</td><td>UNSUBSCRIBE</td></tr>
 * <tr><td>7</td><td>KEEPALIVE (connections only; empty names and payload)</td></tr>
 * <tr><td>8</td><td>SHM_ASK (plain TCP to a loopback peer only; handled by the transport)</td></tr>
 * <tr><td>9</td><td>SHM_OFFER (in answer to SHM_ASK only; handled by the transport)</td></tr>
 * <tr><td>10</td><td>SHM_ACCEPT (in answer to SHM_OFFER only; handled by the transport)</td></tr>
 * <tr><td>11</td><td>PUBLISH_SHARED (a PUBLISH whose payload is in the sender's shared memory; after SHM_ACCEPT only)</td></tr>
 * </table>
 *
 * <p>An ERROR whose CORRELATION ID is all zeros answers no request: the node refuses the whole
 * connection (it serves its maximum number already); the payload says why, and the node closes
 * the connection after it.
 *
 * <p>VERSION: 1, or 2 for a frame whose payload is sealed (encrypted: {@link #FLAG_SEALED}); a
 * node writes 1 whenever it can, so builds that read only version 1 still read every frame of an
 * open topic, and refuse a sealed one clearly instead of taking its ciphertext for a payload.
 *
 * <p>FLAGS: bit 0 is {@link #FLAG_MAC}; bit 1 is {@link #FLAG_SEALED}: the PAYLOAD is AES-256-GCM
 * ciphertext and tag under the topic's password ({@link io.robomw.agents.messaging.security.PayloadSealer}),
 * only in version-2 frames, and only with {@link #FLAG_MAC}; the other bits are reserved, written 0
 * and ignored on reading. PAYLOAD TYPE codes are those of
 * {@link io.robomw.agents.messaging.security.PayloadCodec} (0 null, 1 bytes, 2 string, 3 int,
 * 4 long, 5 double, 6 float, 7 boolean, 127 serialized object); an unknown one is refused when the
 * payload is decoded. An unknown KIND code, MAGIC or VERSION drops the frame as
 * {@link DropReason#MALFORMED} with a message naming the value.
 *
 * <p>The MAC covers every byte before it except the stream sequence, which each link rewrites
 * when it sends the frame (so one authenticated frame can go to many subscribers). Replay
 * detection therefore uses SOURCE and MESSAGE NUMBER, which the MAC covers.
 *
 * <p>Stateless and thread-safe.
 */
public final class FrameCodec {

    /** The first two bytes of every frame, "RM". */
    public static final int MAGIC = 0x524D;
    /** The version of frames whose payload is in the clear. */
    public static final int VERSION = 1;
    /** The version of frames whose payload is sealed ({@link #FLAG_SEALED}). */
    public static final int SEALED_VERSION = 2;
    /** FLAGS bit: the frame ends with a 32-byte HMAC-SHA256. */
    public static final int FLAG_MAC = 1;
    /** FLAGS bit: the payload is sealed (AES-256-GCM under the topic's password); version 2 only, with {@link #FLAG_MAC}. */
    public static final int FLAG_SEALED = 2;

    public static final int MAGIC_OFFSET = 0;
    public static final int VERSION_OFFSET = 2;
    public static final int KIND_OFFSET = 3;
    public static final int FRAME_LENGTH_OFFSET = 4;
    public static final int STREAM_SEQUENCE_OFFSET = 8;
    public static final int FLAGS_OFFSET = 16;
    public static final int PAYLOAD_TYPE_OFFSET = 17;
    public static final int SENDER_LENGTH_OFFSET = 18;
    public static final int RECEIVER_LENGTH_OFFSET = 20;
    public static final int TOPIC_LENGTH_OFFSET = 22;
    public static final int FUNCTION_LENGTH_OFFSET = 24;
    public static final int PAYLOAD_LENGTH_OFFSET = 28;
    public static final int SOURCE_OFFSET = 32;
    public static final int MESSAGE_NUMBER_OFFSET = 40;
    public static final int CORRELATION_OFFSET = 48;
    public static final int TIMESTAMP_OFFSET = 64;
    /** Where the variable part (names, topic, function, payload) starts. */
    public static final int HEADER_LENGTH = 72;
    /** Bytes a stream reader needs to learn a frame's length: magic, version, kind, length. */
    public static final int PREFIX_LENGTH = 8;
    /** Length of the HMAC-SHA256 at the end of an authenticated frame. */
    public static final int MAC_LENGTH = 32;
    /** Longest sender, receiver, topic or function, in UTF-8 bytes. */
    public static final int MAX_NAME_BYTES = 0xFFFF;

    private static final VarHandle SHORT = MethodHandles.byteArrayViewVarHandle(short[].class, ByteOrder.BIG_ENDIAN);
    private static final VarHandle INT = MethodHandles.byteArrayViewVarHandle(int[].class, ByteOrder.BIG_ENDIAN);
    private static final VarHandle LONG = MethodHandles.byteArrayViewVarHandle(long[].class, ByteOrder.BIG_ENDIAN);

    private FrameCodec() {
    }

    /**
     * Encodes a frame, leaving room for its MAC when {@code withMac} (the caller fills it in with
     * {@link io.robomw.agents.messaging.security.FrameMac#sign}).
     *
     * @param frame   the frame; {@link Frame#streamSequence()} is written as given (links overwrite it)
     * @param withMac whether to reserve and flag a MAC
     * @return the encoded frame
     * @throws IllegalArgumentException if a name is longer than {@value #MAX_NAME_BYTES} bytes
     */
    public static byte[] encode(Frame frame, boolean withMac) {
        return encode(frame, withMac, null);
    }

    /**
     * {@link #encode(Frame, boolean)}, taking the UTF-8 bytes of repeated names from a cache.
     *
     * @param frame   the frame
     * @param withMac whether to reserve and flag a MAC
     * @param names   the sender's encoded names, or {@code null}
     * @return the encoded frame
     */
    public static byte[] encode(Frame frame, boolean withMac, NameBytes names) {
        return encode(frame, withMac, false, names);
    }

    /**
     * {@link #encode(Frame, boolean, NameBytes)} of a frame whose payload may be sealed.
     *
     * @param frame   the frame (its payload already sealed when {@code sealed})
     * @param withMac whether to reserve and flag a MAC
     * @param sealed  whether its payload is sealed: a version-2 frame with {@link #FLAG_SEALED} (needs {@code withMac})
     * @param names   the sender's encoded names, or {@code null}
     * @return the encoded frame
     */
    public static byte[] encode(Frame frame, boolean withMac, boolean sealed, NameBytes names) {
        if (sealed && !withMac) {
            throw new IllegalArgumentException("a sealed frame is authenticated too");
        }
        byte[] sender = utf8("sender", frame.sender(), names);
        byte[] receiver = utf8("receiver", frame.receiver(), names);
        byte[] topic = utf8("topic", frame.topic(), names);
        byte[] function = utf8("function", frame.function(), names);
        byte[] payload = frame.payload();
        long length = (long) HEADER_LENGTH + sender.length + receiver.length + topic.length + function.length + payload.length
                + (withMac ? MAC_LENGTH : 0);
        if (length > Integer.MAX_VALUE - 16) {
            throw new IllegalArgumentException("frame of " + length + " bytes is too large to encode");
        }
        int payloadAt = HEADER_LENGTH + sender.length + receiver.length + topic.length + function.length;
        byte[] out = new byte[(int) length];
        // The payload first, right after the allocation: the compiler then zeroes only the bytes around it
        // (the header, the names, the MAC), not a sensor-sized payload it is about to overwrite (a third
        // of the encoding's time at 1 MiB, measured 2026-11-29).
        System.arraycopy(payload, 0, out, payloadAt, payload.length);
        SHORT.set(out, MAGIC_OFFSET, (short) MAGIC);
        out[VERSION_OFFSET] = (byte) (sealed ? SEALED_VERSION : VERSION);
        out[KIND_OFFSET] = (byte) frame.kind().code();
        INT.set(out, FRAME_LENGTH_OFFSET, (int) length);
        LONG.set(out, STREAM_SEQUENCE_OFFSET, frame.streamSequence());
        out[FLAGS_OFFSET] = (byte) ((withMac ? FLAG_MAC : 0) | (sealed ? FLAG_SEALED : 0));
        out[PAYLOAD_TYPE_OFFSET] = (byte) frame.payloadType();
        SHORT.set(out, SENDER_LENGTH_OFFSET, (short) sender.length);
        SHORT.set(out, RECEIVER_LENGTH_OFFSET, (short) receiver.length);
        SHORT.set(out, TOPIC_LENGTH_OFFSET, (short) topic.length);
        SHORT.set(out, FUNCTION_LENGTH_OFFSET, (short) function.length);
        INT.set(out, PAYLOAD_LENGTH_OFFSET, payload.length);
        LONG.set(out, SOURCE_OFFSET, frame.source());
        LONG.set(out, MESSAGE_NUMBER_OFFSET, frame.messageNumber());
        LONG.set(out, CORRELATION_OFFSET, frame.correlationId().getMostSignificantBits());
        LONG.set(out, CORRELATION_OFFSET + 8, frame.correlationId().getLeastSignificantBits());
        LONG.set(out, TIMESTAMP_OFFSET, frame.timestampMicros());
        int at = HEADER_LENGTH;
        System.arraycopy(sender, 0, out, at, sender.length);
        at += sender.length;
        System.arraycopy(receiver, 0, out, at, receiver.length);
        at += receiver.length;
        System.arraycopy(topic, 0, out, at, topic.length);
        at += topic.length;
        System.arraycopy(function, 0, out, at, function.length);
        return out;
    }

    /**
     * Reads the length a frame declares, from its first {@value #PREFIX_LENGTH} bytes; stream
     * transports use it to know how much more to read.
     *
     * @param buf          bytes
     * @param offset       where the frame starts; at least {@value #PREFIX_LENGTH} bytes must follow
     * @param maxFrameSize the largest frame accepted
     * @return the declared frame length
     * @throws FrameException if the magic or version is wrong ({@link DropReason#MALFORMED}), or the length is impossible or above the maximum
     */
    public static int declaredLength(byte[] buf, int offset, int maxFrameSize) throws FrameException {
        int magic = (short) SHORT.get(buf, offset + MAGIC_OFFSET) & 0xFFFF;
        if (magic != MAGIC) {
            throw new FrameException(DropReason.MALFORMED, String.format("not a RoboMW frame: magic 0x%04x, expected 0x%04x", magic, MAGIC));
        }
        int version = buf[offset + VERSION_OFFSET] & 0xFF;
        if (version != VERSION && version != SEALED_VERSION) {
            throw new FrameException(DropReason.MALFORMED, "frame version " + version + ", this node reads versions " + VERSION + " and " + SEALED_VERSION);
        }
        long length = (int) INT.get(buf, offset + FRAME_LENGTH_OFFSET) & 0xFFFFFFFFL;
        if (length > maxFrameSize) {
            throw new FrameException(DropReason.OVERSIZED, "frame declares " + length + " bytes, above the maximum frame size of " + maxFrameSize);
        }
        if (length < HEADER_LENGTH) {
            throw new FrameException(DropReason.MALFORMED, "frame declares " + length + " bytes, less than its " + HEADER_LENGTH + "-byte header");
        }
        return (int) length;
    }

    /**
     * Decodes one complete frame.
     *
     * @param buf          bytes
     * @param offset       where the frame starts
     * @param length       how many bytes there are (a datagram's length, or what a stream reader framed)
     * @param maxFrameSize the largest frame accepted
     * @return the frame, with its payload still encoded
     * @throws FrameException naming what is wrong and the {@link DropReason}
     */
    public static Frame decode(byte[] buf, int offset, int length, int maxFrameSize) throws FrameException {
        return decode(buf, offset, length, maxFrameSize, null);
    }

    /**
     * Decodes one complete frame, taking repeated names from a cache.
     *
     * @param buf          bytes
     * @param offset       where the frame starts
     * @param length       how many bytes there are
     * @param maxFrameSize the largest frame accepted
     * @param names        the reading thread's cache of names, or {@code null}
     * @return the frame, with its payload still encoded
     * @throws FrameException naming what is wrong and the {@link DropReason}
     */
    public static Frame decode(byte[] buf, int offset, int length, int maxFrameSize, NameCache names) throws FrameException {
        if (length < PREFIX_LENGTH) {
            throw new FrameException(DropReason.TRUNCATED, "frame of " + length + " bytes is shorter than the " + PREFIX_LENGTH + "-byte prefix");
        }
        int declared = declaredLength(buf, offset, maxFrameSize);
        if (length < declared) {
            throw new FrameException(DropReason.TRUNCATED, "frame declares " + declared + " bytes but only " + length + " arrived");
        }
        if (length > declared) {
            throw new FrameException(DropReason.MALFORMED, "frame declares " + declared + " bytes but " + length + " arrived");
        }
        FrameKind kind = FrameKind.fromCode(buf[offset + KIND_OFFSET] & 0xFF);
        int flags = buf[offset + FLAGS_OFFSET] & 0xFF;
        boolean mac = (flags & FLAG_MAC) != 0;
        boolean sealedFlag = (flags & FLAG_SEALED) != 0;
        if (sealedFlag != ((buf[offset + VERSION_OFFSET] & 0xFF) == SEALED_VERSION) || sealedFlag && !mac) {
            throw new FrameException(DropReason.MALFORMED, "frame version " + (buf[offset + VERSION_OFFSET] & 0xFF) + " with flags " + flags
                    + ": a sealed payload comes in a version-2 frame with an HMAC, and only there");
        }
        int senderLength = u16(buf, offset + SENDER_LENGTH_OFFSET);
        int receiverLength = u16(buf, offset + RECEIVER_LENGTH_OFFSET);
        int topicLength = u16(buf, offset + TOPIC_LENGTH_OFFSET);
        int functionLength = u16(buf, offset + FUNCTION_LENGTH_OFFSET);
        long payloadLength = (int) INT.get(buf, offset + PAYLOAD_LENGTH_OFFSET) & 0xFFFFFFFFL;
        long expected = (long) HEADER_LENGTH + senderLength + receiverLength + topicLength + functionLength + payloadLength + (mac ? MAC_LENGTH : 0);
        if (expected != declared) {
            throw new FrameException(DropReason.MALFORMED, "frame parts add up to " + expected + " bytes but the frame declares " + declared);
        }
        int at = offset + HEADER_LENGTH;
        int namesLength = senderLength + receiverLength + topicLength + functionLength;
        long lengths = (long) senderLength << 48 | (long) receiverLength << 32 | (long) topicLength << 16 | functionLength;
        String[] last = names == null ? null : names.lastBlock(buf, at, lengths, namesLength);
        String sender;
        String receiver;
        String topic;
        String function;
        if (last != null) {
            // the same four names as the frame before (a stream from one sender on one topic)
            sender = last[0];
            receiver = last[1];
            topic = last[2];
            function = last[3];
            at += namesLength;
        } else {
            int namesAt = at;
            sender = name(names, buf, at, senderLength);
            at += senderLength;
            receiver = name(names, buf, at, receiverLength);
            at += receiverLength;
            topic = name(names, buf, at, topicLength);
            at += topicLength;
            function = name(names, buf, at, functionLength);
            at += functionLength;
            if (names != null) {
                names.rememberBlock(buf, namesAt, lengths, namesLength, sender, receiver, topic, function);
            }
        }
        byte[] payload = new byte[(int) payloadLength];
        System.arraycopy(buf, at, payload, 0, payload.length);
        return new Frame(kind, (long) LONG.get(buf, offset + STREAM_SEQUENCE_OFFSET), (long) LONG.get(buf, offset + SOURCE_OFFSET),
                (long) LONG.get(buf, offset + MESSAGE_NUMBER_OFFSET),
                new UUID((long) LONG.get(buf, offset + CORRELATION_OFFSET), (long) LONG.get(buf, offset + CORRELATION_OFFSET + 8)),
                (long) LONG.get(buf, offset + TIMESTAMP_OFFSET), sender, receiver, topic, function,
                buf[offset + PAYLOAD_TYPE_OFFSET] & 0xFF, payload, mac);
    }

    /**
     * @param buf    a decoded frame's bytes
     * @param offset where it starts
     * @return whether its payload is sealed ({@link #FLAG_SEALED})
     */
    public static boolean sealed(byte[] buf, int offset) {
        return (buf[offset + FLAGS_OFFSET] & FLAG_SEALED) != 0;
    }

    /**
     * Overwrites the stream sequence of an encoded frame (links do this as they send it).
     *
     * @param buf      the frame's bytes
     * @param offset   where the frame starts
     * @param sequence the link's sequence number for it
     */
    public static void writeStreamSequence(byte[] buf, int offset, long sequence) {
        LONG.set(buf, offset + STREAM_SEQUENCE_OFFSET, sequence);
    }

    /**
     * @param buf    the frame's bytes
     * @param offset where the frame starts
     * @return its stream sequence
     */
    public static long streamSequence(byte[] buf, int offset) {
        return (long) LONG.get(buf, offset + STREAM_SEQUENCE_OFFSET);
    }

    private static String name(NameCache names, byte[] buf, int at, int length) {
        return names == null ? new String(buf, at, length, StandardCharsets.UTF_8) : names.decode(buf, at, length);
    }

    private static int u16(byte[] buf, int at) {
        return (short) SHORT.get(buf, at) & 0xFFFF;
    }

    private static byte[] utf8(String what, String value, NameBytes names) {
        if (names != null) {
            return names.of(what, value);
        }
        byte[] bytes = value.getBytes(StandardCharsets.UTF_8);
        if (bytes.length > MAX_NAME_BYTES) {
            throw new IllegalArgumentException(what + " is " + bytes.length + " bytes in UTF-8; the limit is " + MAX_NAME_BYTES);
        }
        return bytes;
    }
}
