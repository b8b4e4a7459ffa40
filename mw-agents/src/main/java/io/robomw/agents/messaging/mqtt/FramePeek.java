package io.robomw.agents.messaging.mqtt;

import io.robomw.agents.messaging.frame.FrameCodec;
import io.robomw.agents.messaging.frame.FrameKind;

import java.nio.charset.StandardCharsets;
import java.util.Arrays;

/**
 * Reads the few header fields a broker session routes by (kind, receiver, topic, correlation id)
 * from an encoded frame this node made, without decoding the rest (see {@link FrameCodec} for the
 * layout). Frames from outside are decoded in full by the node, never here.
 */
final class FramePeek {

    private FramePeek() {
    }

    /** @return whether the {@code length} bytes at {@code offset} start like a RoboMW frame (magic and version) */
    static boolean isFrame(byte[] b, int offset, int length) {
        if (length < FrameCodec.HEADER_LENGTH) {
            return false;
        }
        int version = b[offset + FrameCodec.VERSION_OFFSET] & 0xFF;
        return u16(b, offset + FrameCodec.MAGIC_OFFSET) == FrameCodec.MAGIC && (version == FrameCodec.VERSION || version == FrameCodec.SEALED_VERSION);
    }

    /** @return the frame's kind, or {@code null} for a code no kind has (this node's own frames always have one) */
    static FrameKind kind(byte[] frame) {
        try {
            return FrameKind.fromCode(frame[FrameCodec.KIND_OFFSET] & 0xFF);
        } catch (io.robomw.agents.messaging.frame.FrameException e) {
            return null;
        }
    }

    static String receiver(byte[] frame) {
        int at = FrameCodec.HEADER_LENGTH + u16(frame, FrameCodec.SENDER_LENGTH_OFFSET);
        return new String(frame, at, u16(frame, FrameCodec.RECEIVER_LENGTH_OFFSET), StandardCharsets.UTF_8);
    }

    static String topic(byte[] frame) {
        int at = FrameCodec.HEADER_LENGTH + u16(frame, FrameCodec.SENDER_LENGTH_OFFSET) + u16(frame, FrameCodec.RECEIVER_LENGTH_OFFSET);
        return new String(frame, at, u16(frame, FrameCodec.TOPIC_LENGTH_OFFSET), StandardCharsets.UTF_8);
    }

    /** @return the 16 bytes of the correlation id, as MQTT 5 correlation data */
    static byte[] correlation(byte[] frame) {
        return Arrays.copyOfRange(frame, FrameCodec.CORRELATION_OFFSET, FrameCodec.CORRELATION_OFFSET + 16);
    }

    private static int u16(byte[] b, int at) {
        return ((b[at] & 0xFF) << 8) | (b[at + 1] & 0xFF);
    }
}
