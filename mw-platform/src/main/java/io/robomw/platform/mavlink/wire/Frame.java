package io.robomw.platform.mavlink.wire;

import java.util.Arrays;
import java.util.Optional;

/**
 * One MAVLink frame as it came off a link (or as an encoder made it): its header, its payload as
 * sent, its signature if it is signed, and the frame's bytes. A frame the {@link FrameDecoder}
 * hands on is of a message type its dialect knows, with a good checksum. Immutable.
 */
public final class Frame {

    /** The protocol version of a frame, by its start byte. */
    public enum Version {
        /** MAVLink 1: start byte {@code 0xFE}, 8-bit message ids, no flags, no signature. */
        V1(Framing.STX_V1),
        /** MAVLink 2: start byte {@code 0xFD}. */
        V2(Framing.STX_V2);

        private final int startByte;

        Version(int startByte) {
            this.startByte = startByte;
        }

        /** @return the start byte on the wire */
        public int startByte() {
            return startByte;
        }
    }

    /**
     * A signed frame's signature block.
     *
     * @param linkId    the sender's link id, 0-255
     * @param timestamp the signature's timestamp, 10 µs units since 2015-01-01 UTC (48 bits)
     * @param value     the signature, 6 bytes (a copy is kept)
     */
    public record Signature(int linkId, long timestamp, byte[] value) {
        /** Copies the value. */
        public Signature {
            value = value.clone();
        }

        @Override
        public byte[] value() {
            return value.clone();
        }

        @Override
        public boolean equals(Object o) {
            return o instanceof Signature s && s.linkId == linkId && s.timestamp == timestamp && Arrays.equals(s.value, value);
        }

        @Override
        public int hashCode() {
            return Long.hashCode(timestamp) * 31 + linkId;
        }

        @Override
        public String toString() {
            return "Signature[link " + linkId + ", timestamp " + timestamp + "]";
        }
    }

    private final byte[] bytes;
    private final Version version;
    private final MessageType type;

    /**
     * @param bytes   the whole frame, already checked for its length (kept, not copied)
     * @param version its version
     * @param type    its message type, or {@code null} when the dialect does not know its id
     */
    Frame(byte[] bytes, Version version, MessageType type) {
        this.bytes = bytes;
        this.version = version;
        this.type = type;
    }

    /** @return its protocol version */
    public Version version() {
        return version;
    }

    private int headerLength() {
        return version == Version.V2 ? Framing.HEADER_V2 : Framing.HEADER_V1;
    }

    /** @return payload bytes as sent (after truncation) */
    public int payloadLength() {
        return bytes[Framing.LEN] & 0xFF;
    }

    /** @return the incompatibility flags (0 for MAVLink 1) */
    public int incompatFlags() {
        return version == Version.V2 ? bytes[Framing.INCOMPAT_FLAGS] & 0xFF : 0;
    }

    /** @return the compatibility flags (0 for MAVLink 1) */
    public int compatFlags() {
        return version == Version.V2 ? bytes[Framing.COMPAT_FLAGS] & 0xFF : 0;
    }

    /** @return the sender's sequence number, 0-255 */
    public int sequence() {
        return bytes[version == Version.V2 ? Framing.SEQ : Framing.V1_SEQ] & 0xFF;
    }

    /** @return the sender's system id */
    public int systemId() {
        return bytes[version == Version.V2 ? Framing.SYSID : Framing.V1_SYSID] & 0xFF;
    }

    /** @return the sender's component id */
    public int componentId() {
        return bytes[version == Version.V2 ? Framing.COMPID : Framing.V1_COMPID] & 0xFF;
    }

    /** @return the message id */
    public int messageId() {
        if (version == Version.V1) {
            return bytes[Framing.V1_MSGID] & 0xFF;
        }
        return (bytes[Framing.MSGID] & 0xFF) | (bytes[Framing.MSGID + 1] & 0xFF) << 8 | (bytes[Framing.MSGID + 2] & 0xFF) << 16;
    }

    /** @return its message type, if the dialect knows the id */
    public Optional<MessageType> type() {
        return Optional.ofNullable(type);
    }

    /** @return whether it is a message of that type */
    public boolean is(MessageType t) {
        return type == t;
    }

    /**
     * @return its fields, zero-extended to the full payload
     * @throws IllegalStateException if the dialect does not know its message id
     */
    public Payload payload() {
        if (type == null) {
            throw new IllegalStateException("message id " + messageId() + " is not in the dialect; its fields cannot be read");
        }
        return Payload.fromWire(type, bytes, headerLength(), payloadLength());
    }

    /** @return the checksum as sent */
    public int checksum() {
        int o = headerLength() + payloadLength();
        return (bytes[o] & 0xFF) | (bytes[o + 1] & 0xFF) << 8;
    }

    /** @return whether it carries a signature block */
    public boolean signed() {
        return (incompatFlags() & Framing.INCOMPAT_SIGNED) != 0;
    }

    /** @return its signature block, if signed */
    public Optional<Signature> signature() {
        if (!signed()) {
            return Optional.empty();
        }
        int o = headerLength() + payloadLength() + Framing.CHECKSUM;
        long ts = 0;
        for (int i = Framing.TIMESTAMP; i >= 1; i--) {
            ts = ts << 8 | (bytes[o + i] & 0xFFL);
        }
        return Optional.of(new Signature(bytes[o] & 0xFF, ts,
                Arrays.copyOfRange(bytes, o + 1 + Framing.TIMESTAMP, o + Framing.SIGNATURE_BLOCK)));
    }

    /** @return the frame's bytes (a copy) */
    public byte[] bytes() {
        return bytes.clone();
    }

    /** @return the frame's length in bytes */
    public int length() {
        return bytes.length;
    }

    /** @return the bytes a signature covers, without the key: the frame up to and including link id and timestamp */
    byte[] signedBytes() {
        return Arrays.copyOf(bytes, bytes.length - Framing.SIGNATURE);
    }

    @Override
    public String toString() {
        return (type == null ? "message " + messageId() : type.name()) + " from " + systemId() + "/" + componentId()
                + " seq " + sequence() + (signed() ? " signed" : "") + (version == Version.V1 ? " (MAVLink 1)" : "");
    }
}
