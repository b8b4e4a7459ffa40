package io.robomw.agents.host.protocol;

import io.robomw.agents.host.rmi.Session;
import java.io.ByteArrayOutputStream;
import java.util.Arrays;

/**
 * A call as {@link Session} sends it, laid out at the start of one array: room for the session
 * header, the body, room for the MAC. A transfer's body (the agent image, megabytes for a large
 * agent) is written into its frame where it will travel ({@link Buffer}), and {@link Session#seal}
 * fills the header and MAC in place: the state is not copied into an image and the image into a
 * request. The array may be longer than the frame (a reused one, {@link FrameBuffers}): only its
 * first {@link #length} bytes are the frame, and nothing after them is ever sent or stored.
 */
public final class Frame {

    public final byte[] bytes;
    /** The frame's length: header, body and MAC, from index 0 of {@link #bytes}. */
    public final int length;

    public Frame(byte[] bytes) {
        this(bytes, bytes.length);
    }

    public Frame(byte[] bytes, int length) {
        if (length < Session.HEADER + Session.MAC || length > bytes.length) {
            throw new IllegalArgumentException("a frame of " + length + " bytes in an array of " + bytes.length + " has no room for its header and MAC");
        }
        this.bytes = bytes;
        this.length = length;
    }

    /** @param body a call's body @return it in a frame of its own (copied) */
    public static Frame of(byte[] body) {
        byte[] b = new byte[Session.HEADER + body.length + Session.MAC];
        System.arraycopy(body, 0, b, Session.HEADER, body.length);
        return new Frame(b);
    }

    /** @return where the body starts */
    public int bodyOffset() {
        return Session.HEADER;
    }

    /** @return the body's length */
    public int bodyLength() {
        return length - Session.HEADER - Session.MAC;
    }

    /** @return the frame in an array of exactly its length (this one's when it is; else a copy): what an RMI call carries */
    public byte[] exact() {
        return bytes.length == length ? bytes : Arrays.copyOf(bytes, length);
    }

    /**
     * Collects a body behind room for the header, in an array sized for the body expected (an
     * agent's image when it last travelled), or in a reused one of {@link FrameBuffers}; it ends
     * as the frame's own array without a copy when the body fits.
     */
    public static final class Buffer extends ByteArrayOutputStream {

        /** @param expectedBody how long the body will probably be */
        Buffer(int expectedBody) {
            super(Session.HEADER + Math.max(64, expectedBody) + Session.MAC);
            count = Session.HEADER;
        }

        /**
         * @param expectedBody how long the body will probably be
         * @param reuse        an array to write into if it has room for that ({@code null}: a new one)
         */
        Buffer(int expectedBody, byte[] reuse) {
            super(0);
            int want = Session.HEADER + Math.max(64, expectedBody) + Session.MAC;
            buf = reuse != null && reuse.length >= want ? reuse : new byte[want];
            count = Session.HEADER;
        }

        /** @return the body written so far, with room for the MAC after it (the array grown if it has none) */
        Frame finish() {
            int length = count + Session.MAC;
            return new Frame(buf.length >= length ? buf : Arrays.copyOf(buf, length), length);
        }
    }
}
