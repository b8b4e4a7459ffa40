package io.robomw.platform.mavlink.wire;

/**
 * The layout of MAVLink frames (mavlink.io/en/guide/serialization.html and
 * .../message_signing.html), one named constant per offset. Every multi-byte value is
 * little-endian.
 *
 * <pre>
 * MAVLink 2 (start byte FD)
 *  0 STX 0xFD | 1 len (payload bytes as sent) | 2 incompat_flags (0x01 signed) | 3 compat_flags
 *  4 seq | 5 sysid | 6 compid | 7..9 msgid (24 bits)
 * 10 payload[len]: the message's fields in wire order, trailing zero bytes cut (never the first)
 * 10+len checksum u16: CRC-16/MCRF4XX of bytes 1..9+len, then the message's CRC_EXTRA
 * 12+len (signed frames only, 13 bytes) link_id u8 | timestamp u48 (10 µs since 2015-01-01 UTC)
 *        | signature: the first 6 bytes of SHA-256(key + bytes 0..12+len + link_id + timestamp)
 *
 * MAVLink 1 (start byte FE)
 *  0 STX 0xFE | 1 len | 2 seq | 3 sysid | 4 compid | 5 msgid (8 bits)
 *  6 payload[len] | 6+len checksum u16 of bytes 1..5+len, then CRC_EXTRA
 * </pre>
 *
 * A receiver zero-extends a cut payload back to the message's full length before it reads it, and
 * drops a frame with an incompatibility flag it does not know. The largest frame is
 * {@value #MAX_FRAME} bytes.
 */
public final class Framing {

    /** The start byte of a MAVLink 2 frame. */
    public static final int STX_V2 = 0xFD;
    /** The start byte of a MAVLink 1 frame. */
    public static final int STX_V1 = 0xFE;
    /** Header bytes of a MAVLink 2 frame, start byte included. */
    public static final int HEADER_V2 = 10;
    /** Header bytes of a MAVLink 1 frame, start byte included. */
    public static final int HEADER_V1 = 6;
    /** Checksum bytes. */
    public static final int CHECKSUM = 2;
    /** Signature block bytes: link id, timestamp, signature. */
    public static final int SIGNATURE_BLOCK = 13;
    /** Bytes of the signature itself (the first 48 bits of the SHA-256). */
    public static final int SIGNATURE = 6;
    /** Bytes of the signature's timestamp. */
    public static final int TIMESTAMP = 6;
    /** The most payload bytes of a frame. */
    public static final int MAX_PAYLOAD = 255;
    /** The largest MAVLink 2 frame: header, payload, checksum and signature. */
    public static final int MAX_FRAME = HEADER_V2 + MAX_PAYLOAD + CHECKSUM + SIGNATURE_BLOCK;

    /** Offset of the payload length (both versions). */
    public static final int LEN = 1;
    /** MAVLink 2: offset of the incompatibility flags. */
    public static final int INCOMPAT_FLAGS = 2;
    /** MAVLink 2: offset of the compatibility flags. */
    public static final int COMPAT_FLAGS = 3;
    /** MAVLink 2: offset of the sequence number. */
    public static final int SEQ = 4;
    /** MAVLink 2: offset of the sender's system id. */
    public static final int SYSID = 5;
    /** MAVLink 2: offset of the sender's component id. */
    public static final int COMPID = 6;
    /** MAVLink 2: offset of the message id's low byte (three bytes). */
    public static final int MSGID = 7;
    /** MAVLink 1: offset of the sequence number. */
    public static final int V1_SEQ = 2;
    /** MAVLink 1: offset of the sender's system id. */
    public static final int V1_SYSID = 3;
    /** MAVLink 1: offset of the sender's component id. */
    public static final int V1_COMPID = 4;
    /** MAVLink 1: offset of the message id (one byte). */
    public static final int V1_MSGID = 5;

    /** Incompatibility flag: the frame is signed (13 more bytes). The only flag MAVLink 2 defines. */
    public static final int INCOMPAT_SIGNED = 0x01;
    /** The incompatibility flags this codec understands. */
    public static final int KNOWN_INCOMPAT_FLAGS = INCOMPAT_SIGNED;

    private Framing() {
    }
}
