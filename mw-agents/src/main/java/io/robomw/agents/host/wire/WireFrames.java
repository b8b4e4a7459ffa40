package io.robomw.agents.host.wire;

import io.robomw.agents.host.protocol.Op;
import io.robomw.agents.host.protocol.Reply;
import io.robomw.agents.host.rmi.HostEndpoint;
import io.robomw.agents.host.rmi.Session;
import java.io.IOException;
import java.lang.invoke.MethodHandles;
import java.lang.invoke.VarHandle;
import java.nio.ByteOrder;
import java.nio.charset.StandardCharsets;
import java.util.Objects;

/**
 * The frames of agent wire protocol version {@value #VERSION}: a host's transfers (an agent hopping
 * to it) and their replies, on a TCP connection of their own (TLS when the hosts use TLS) instead of
 * an RMI call. The connection belongs to one session, made by the authentication of
 * {@link Session} over RMI; a host that speaks version 3 says in its authentication answer on which
 * port it takes them ({@link HostEndpoint}). All integers are big-endian.
 *
 * <pre>
 * frame  = header body tag
 * header = [version 1 = 3][code 1][session id 8][seq 8][body length 4]          22 bytes
 * body   = body length bytes: the call's body (a transfer: its AgentImage) or the reply's
 * tag    = 16 bytes: AES-256-GCM's tag under the session key over header and body as the plaintext,
 *          nonce [0 0 0 2][seq 8] in a request, [0 0 0 3][seq 8] in its reply (seq = the request's);
 *          16 zero bytes in the two untagged replies below
 * </pre>
 *
 * <p>A request's code is an operation: those of the table in {@link Session} ({@link Op}, 0-10),
 * and {@value #OP_HELLO} HELLO (empty body), the first frame on every connection, which proves the
 * peer's session before the host reads a frame larger than {@link HostEndpoint#UNPROVEN_MAX_BYTES}.
 * A reply's code is a status: those of {@link Reply.Status} (0-7) and {@value #STATUS_FRAME_REFUSED}
 * FRAME_REFUSED. A reply carries the session id and sequence number of the request it answers.
 *
 * <table>
 * <caption>What a host answers, and whether it keeps the connection</caption>
 * <tr><th>frame</th><th>answer</th><th>connection</th></tr>
 * <tr><td>verified, a known operation</td><td>the call's reply, tagged</td><td>kept</td></tr>
 * <tr><td>verified, an unknown operation code</td><td>REFUSED (3), tagged, naming the code</td><td>kept</td></tr>
 * <tr><td>a session the host does not know</td><td>UNKNOWN_SESSION (7), untagged, empty: authenticate again</td><td>closed</td></tr>
 * <tr><td>another version, a body over the limit, a number not above the connection's last one or one the
 *     session served, another session than the connection's first, a wrong tag, a frame cut short</td>
 *     <td>FRAME_REFUSED ({@value #STATUS_FRAME_REFUSED}), untagged, the reason in UTF-8 (at most
 *     {@value #MAX_REASON_BYTES} bytes), when the connection can still carry it</td><td>closed</td></tr>
 * </table>
 *
 * <p>An untagged reply is information, not proof: a peer treats FRAME_REFUSED as a broken connection
 * (the call may have been served: a transfer is asked of the same host again, which takes a hop at
 * most once), and UNKNOWN_SESSION as v2 does (authenticate again, repeat the call to the same host).
 */
public final class WireFrames {

    /** The version byte of every frame: agent protocol version 3. */
    public static final int VERSION = Session.WIRE_VERSION;
    /** Bytes of a header. */
    public static final int HEADER = 1 + 1 + 8 + 8 + 4;
    /** Bytes of a tag. */
    public static final int TAG = 16;
    /** Operation code of HELLO, the first frame on a connection (empty body; the reply: OK, empty). */
    public static final int OP_HELLO = 64;
    /** Status code of an untagged reply refusing a malformed frame; the host closes the connection after it. */
    public static final int STATUS_FRAME_REFUSED = 8;
    /** The nonce's direction byte of a request's tag. */
    public static final int DIRECTION_REQUEST = 2;
    /** The nonce's direction byte of a reply's tag. */
    public static final int DIRECTION_REPLY = 3;
    /** The longest reason a FRAME_REFUSED carries, and the longest body an untagged reply may have. */
    public static final int MAX_REASON_BYTES = 1024;

    private WireFrames() {
    }

    /**
     * A frame's header as read.
     *
     * @param version the version byte
     * @param code    the operation (a request) or status (a reply)
     * @param session the session id
     * @param seq     the request's sequence number
     * @param length  the body's length (an unsigned 32-bit field)
     */
    public record Header(int version, int code, long session, long seq, long length) {

        /** @return the header at {@code off} in {@code b} ({@value #HEADER} bytes there) */
        public static Header read(byte[] b, int off) {
            Objects.checkFromIndexSize(off, HEADER, b.length);
            return new Header(b[off] & 0xFF, b[off + 1] & 0xFF, (long) LONGS.get(b, off + 2), (long) LONGS.get(b, off + 10),
                    (int) INTS.get(b, off + 18) & 0xFFFF_FFFFL);
        }

        /** @return the whole frame's length: header, body and tag */
        public long frameLength() {
            return HEADER + length + TAG;
        }
    }

    /** @return a header's bytes */
    static byte[] header(int code, long session, long seq, int length) {
        byte[] h = new byte[HEADER];
        header(h, code, session, seq, length);
        return h;
    }

    /** Puts a header's bytes at the start of {@code into} (a writer's own array, reused frame after frame). */
    static void header(byte[] into, int code, long session, long seq, int length) {
        into[0] = (byte) VERSION;
        into[1] = (byte) code;
        LONGS.set(into, 2, session);
        LONGS.set(into, 10, seq);
        INTS.set(into, 18, length);
    }

    private static final VarHandle LONGS = MethodHandles.byteArrayViewVarHandle(long[].class, ByteOrder.BIG_ENDIAN);
    private static final VarHandle INTS = MethodHandles.byteArrayViewVarHandle(int[].class, ByteOrder.BIG_ENDIAN);

    /** @return the body of a FRAME_REFUSED reply: the reason, cut to {@value #MAX_REASON_BYTES} bytes */
    static byte[] reason(String why) {
        byte[] b = why.getBytes(StandardCharsets.UTF_8);
        if (b.length <= MAX_REASON_BYTES) {
            return b;
        }
        return new String(b, 0, MAX_REASON_BYTES - 3, StandardCharsets.UTF_8).replace("\uFFFD", "").concat("...").getBytes(StandardCharsets.UTF_8);
    }

    /** A frame that breaks the rules of this format or its limits; the connection that carried it is closed. */
    public static final class FrameRefused extends IOException {
        private static final long serialVersionUID = 1L;

        FrameRefused(String message) {
            super(message);
        }
    }
}
