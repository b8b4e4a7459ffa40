package io.robomw.agents.messaging.spi;

import io.robomw.agents.messaging.frame.Frame;
import io.robomw.agents.messaging.frame.FrameCodec;
import io.robomw.agents.messaging.frame.FrameKind;
import io.robomw.agents.messaging.frame.NameBytes;

/**
 * One publication on its way out, as the node hands it to each channel that takes it
 * ({@link Channel#sendPublication}): as one frame, or, where a transport carries a payload apart
 * from its frame, as a <em>head</em> and the payload itself, so that a sensor-sized payload is not
 * copied into a frame first.
 *
 * <p>The head is a {@link FrameKind#PUBLISH_SHARED} frame with an empty payload: the
 * {@link FrameKind#PUBLISH} it stands for, every field but the payload, which the receiving
 * transport hands to the node beside it ({@link TransportContext#onFrame(byte[], int, int, byte[], Channel)}).
 * Only a publication without an HMAC can travel apart (the HMAC covers the whole frame), and only
 * one of at least {@value #APART_FROM_BYTES} bytes of payload (below it a copy costs nothing worth
 * a second layout, and the frame is what older nodes read).
 *
 * <p>Made once per publication and used on the publishing thread: not thread-safe.
 */
public final class Publication {

    /** The smallest payload that travels apart from its frame: 64 KiB (a laser scan, a camera frame). */
    public static final int APART_FROM_BYTES = 64 * 1024;

    private static final byte[] EMPTY = new byte[0];

    private final Frame frame;
    private final NameBytes names;
    private byte[] whole;
    private byte[] head;

    private Publication(Frame frame, NameBytes names, byte[] whole) {
        this.frame = frame;
        this.names = names;
        this.whole = whole;
    }

    /**
     * @param frame an encoded publication (signed or small)
     * @return it, as a publication that travels whole
     */
    public static Publication whole(byte[] frame) {
        return new Publication(null, null, frame);
    }

    /**
     * @param frame a publication without an HMAC, its payload encoded, of at least {@value #APART_FROM_BYTES} bytes
     * @param names the sender's encoded names, or {@code null}
     * @return it, as a publication whose payload may travel apart
     * @throws IllegalArgumentException if it is not an unsigned {@code PUBLISH} of that size
     */
    public static Publication apart(Frame frame, NameBytes names) {
        if (frame.kind() != FrameKind.PUBLISH || frame.authenticated() || frame.payload().length < APART_FROM_BYTES) {
            throw new IllegalArgumentException("only an unsigned PUBLISH of at least " + APART_FROM_BYTES + " bytes travels apart, not a "
                    + (frame.authenticated() ? "signed " : "") + frame.kind() + " of " + frame.payload().length);
        }
        return new Publication(frame, names, null);
    }

    /** @return whether the payload may travel apart from its frame ({@link #head()}, {@link #payload()}) */
    public boolean travelsApart() {
        return frame != null;
    }

    /** @return the whole frame, encoded on the first call (the same array for every channel: do not change it) */
    public byte[] frame() {
        if (whole == null) {
            whole = FrameCodec.encode(frame, false, names);
        }
        return whole;
    }

    /** @return the length of the whole frame, without encoding it */
    public long length() {
        return whole != null ? whole.length : (long) head().length + frame.payload().length;
    }

    /**
     * @return the head: a {@code PUBLISH_SHARED} frame of every field but the payload, encoded on the first call
     * @throws IllegalStateException if the publication travels whole
     */
    public byte[] head() {
        if (frame == null) {
            throw new IllegalStateException("a signed or small publication travels whole");
        }
        if (head == null) {
            head = FrameCodec.encode(new Frame(FrameKind.PUBLISH_SHARED, frame.streamSequence(), frame.source(), frame.messageNumber(),
                    frame.correlationId(), frame.timestampMicros(), frame.sender(), frame.receiver(), frame.topic(), frame.function(),
                    frame.payloadType(), EMPTY, false), false, names);
        }
        return head;
    }

    /**
     * The payload as the caller gave it (a {@code byte[]} payload is its very array): read it only
     * during {@link Channel#sendPublication}, since the caller may change the array once
     * {@code publishMessage} returned; a transport that keeps it longer (an MQTT client, until the
     * broker's acknowledgement) copies it.
     *
     * @return the encoded payload, not copied (do not change it)
     * @throws IllegalStateException if the publication travels whole
     */
    public byte[] payload() {
        if (frame == null) {
            throw new IllegalStateException("a signed or small publication travels whole");
        }
        return frame.payload();
    }
}
