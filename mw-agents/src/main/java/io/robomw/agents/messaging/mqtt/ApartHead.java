package io.robomw.agents.messaging.mqtt;

import io.robomw.agents.messaging.DropReason;
import io.robomw.agents.messaging.frame.FrameException;
import io.robomw.agents.messaging.frame.FrameKind;

import java.util.Base64;

/**
 * The MQTT 5 user property {@value #PROPERTY} of a publication whose payload travels apart from
 * its frame ({@link io.robomw.agents.messaging.spi.Publication}): the PUBLISH's payload is the
 * publication's payload as it is, and this property holds the rest of the frame, a
 * {@link FrameKind#PUBLISH_SHARED} head with an empty payload, in base64 (RFC 4648, with padding).
 */
public final class ApartHead {

    /** The property's name. */
    public static final String PROPERTY = "robomw-frame";

    private ApartHead() {
    }

    /**
     * @param head an encoded head
     * @return the property's value
     */
    public static String encode(byte[] head) {
        return Base64.getEncoder().encodeToString(head);
    }

    /**
     * @param value the property's value, as a broker delivered it
     * @return the head it holds, a {@code PUBLISH_SHARED} frame (not yet decoded past its kind)
     * @throws FrameException ({@link DropReason#MALFORMED}) if it is not base64, or not such a frame
     */
    public static byte[] decode(String value) throws FrameException {
        byte[] head;
        try {
            head = Base64.getDecoder().decode(value);
        } catch (IllegalArgumentException e) {
            throw new FrameException(DropReason.MALFORMED, "property " + PROPERTY + " is not base64: " + e.getMessage());
        }
        FrameKind kind = FramePeek.isFrame(head, 0, head.length) ? FramePeek.kind(head) : null;
        if (kind != FrameKind.PUBLISH_SHARED) {
            throw new FrameException(DropReason.MALFORMED, "property " + PROPERTY + " holds " + (kind == null ? "no frame" : "a " + kind)
                    + ", not the head of a publication (" + FrameKind.PUBLISH_SHARED + ")");
        }
        return head;
    }
}
