package io.robomw.agents.messaging.shm;

import io.robomw.agents.messaging.DropReason;
import io.robomw.agents.messaging.frame.FrameCodec;
import io.robomw.agents.messaging.frame.FrameException;
import io.robomw.agents.messaging.frame.FrameKind;

import java.lang.invoke.MethodHandles;
import java.lang.invoke.VarHandle;
import java.nio.ByteOrder;

/**
 * Where a {@link FrameKind#PUBLISH_SHARED} frame's payload is: the PAYLOAD of that frame, 16 bytes,
 * big-endian like the rest of the frame.
 *
 * <pre>
 *  0  SEQUENCE  u64  the record's sequence in the sender's segment (increasing on each connection)
 *  8  OFFSET    u32  where the record starts in the segment's ring
 * 12  LENGTH    u32  the payload's length (the record's payload follows its 16-byte head)
 * </pre>
 *
 * @param sequence the record's sequence, from 1
 * @param offset   where its record starts in the ring
 * @param length   the payload's length
 */
public record SharedReference(long sequence, int offset, int length) {

    /** The reference's size: a {@link FrameKind#PUBLISH_SHARED} frame's PAYLOAD LENGTH. */
    public static final int BYTES = 16;

    private static final VarHandle INT = MethodHandles.byteArrayViewVarHandle(int[].class, ByteOrder.BIG_ENDIAN);
    private static final VarHandle LONG = MethodHandles.byteArrayViewVarHandle(long[].class, ByteOrder.BIG_ENDIAN);

    /**
     * Makes the reference frame that stands for a publication.
     *
     * @param publication an encoded {@link FrameKind#PUBLISH} frame without an HMAC
     * @param sequence    its record's sequence
     * @param offset      its record's offset in the ring
     * @return the frame's head and names with this reference as its payload, of kind {@link FrameKind#PUBLISH_SHARED}
     */
    public static byte[] frameFor(byte[] publication, long sequence, int offset) {
        int length = payloadLength(publication, 0);
        return frameFor(publication, publication.length - length, length, sequence, offset);
    }

    /**
     * Makes the reference frame that stands for a publication, from its head.
     *
     * @param head     the first {@code headLength} bytes of an encoded {@link FrameKind#PUBLISH} frame without an HMAC (its
     *                 header and names), or the head of a publication that travels apart ({@link io.robomw.agents.messaging.spi.Publication#head()})
     * @param headLength how many bytes of {@code head} are its header and names
     * @param length   the publication's payload length
     * @param sequence its record's sequence
     * @param offset   its record's offset in the ring
     * @return the head with this reference as its payload, of kind {@link FrameKind#PUBLISH_SHARED}
     */
    public static byte[] frameFor(byte[] head, int headLength, int length, long sequence, int offset) {
        byte[] out = new byte[headLength + BYTES];
        System.arraycopy(head, 0, out, 0, headLength);
        out[FrameCodec.KIND_OFFSET] = (byte) FrameKind.PUBLISH_SHARED.code();
        INT.set(out, FrameCodec.FRAME_LENGTH_OFFSET, out.length);
        INT.set(out, FrameCodec.PAYLOAD_LENGTH_OFFSET, BYTES);
        LONG.set(out, headLength, sequence);
        INT.set(out, headLength + 8, offset);
        INT.set(out, headLength + 12, length);
        return out;
    }

    /**
     * @param frame  an encoded frame
     * @param offset where it starts
     * @return its PAYLOAD LENGTH
     */
    public static int payloadLength(byte[] frame, int offset) {
        return (int) INT.get(frame, offset + FrameCodec.PAYLOAD_LENGTH_OFFSET);
    }

    /**
     * Reads the reference of a received {@link FrameKind#PUBLISH_SHARED} frame (framed, not yet decoded).
     *
     * @param buf    bytes
     * @param offset where the frame starts
     * @param length the frame's length
     * @return the reference
     * @throws FrameException ({@link DropReason#MALFORMED}) if the frame carries an HMAC or its payload is not a reference
     */
    public static SharedReference read(byte[] buf, int offset, int length) throws FrameException {
        if (length < FrameCodec.HEADER_LENGTH + BYTES || offset + length > buf.length) {
            throw new FrameException(DropReason.TRUNCATED, "a shared-memory publication of " + length + " bytes; it has a "
                    + FrameCodec.HEADER_LENGTH + "-byte header and a " + BYTES + "-byte reference");
        }
        if ((buf[offset + FrameCodec.FLAGS_OFFSET] & FrameCodec.FLAG_MAC) != 0) {
            throw new FrameException(DropReason.MALFORMED, "a shared-memory publication with an HMAC: frames with an HMAC never go through shared memory");
        }
        int payload = payloadLength(buf, offset);
        if (payload != BYTES) {
            throw new FrameException(DropReason.MALFORMED, "a shared-memory publication whose payload is " + payload + " bytes; a reference is " + BYTES);
        }
        int at = offset + length - BYTES;
        return new SharedReference((long) LONG.get(buf, at), (int) INT.get(buf, at + 8), (int) INT.get(buf, at + 12));
    }
}
