package io.robomw.agents.host;

import java.io.ByteArrayOutputStream;
import java.util.Arrays;

/**
 * A call as {@link Session} sends it, laid out in one array: room for the session header, the
 * body, room for the MAC. A transfer's body (the agent image, megabytes for a large agent) is
 * written into its frame where it will travel ({@link Buffer}), and {@link Session#seal} fills the
 * header and MAC in place: the state is not copied into an image and the image into a request.
 */
final class Frame {

    final byte[] bytes;

    Frame(byte[] bytes) {
        if (bytes.length < Session.HEADER + Session.MAC) {
            throw new IllegalArgumentException("a frame of " + bytes.length + " bytes has no room for its header and MAC");
        }
        this.bytes = bytes;
    }

    /** @param body a call's body @return it in a frame of its own (copied) */
    static Frame of(byte[] body) {
        byte[] b = new byte[Session.HEADER + body.length + Session.MAC];
        System.arraycopy(body, 0, b, Session.HEADER, body.length);
        return new Frame(b);
    }

    /** @return where the body starts */
    int bodyOffset() {
        return Session.HEADER;
    }

    /** @return the body's length */
    int bodyLength() {
        return bytes.length - Session.HEADER - Session.MAC;
    }

    /**
     * Collects a body behind room for the header. Sized for the body expected (an agent's image
     * when it last travelled), it ends as the frame's own array without a copy when the body is
     * as long as expected.
     */
    static final class Buffer extends ByteArrayOutputStream {

        /** @param expectedBody how long the body will probably be */
        Buffer(int expectedBody) {
            super(Session.HEADER + Math.max(64, expectedBody) + Session.MAC);
            count = Session.HEADER;
        }

        /** @return the body written so far, with room for the MAC after it */
        Frame finish() {
            int length = count + Session.MAC;
            return new Frame(buf.length == length ? buf : Arrays.copyOf(buf, length));
        }
    }
}
