package io.robomw.agents.host;

import io.robomw.agents.host.rmi.Session;
import io.robomw.agents.host.security.FrameTag;
import io.robomw.agents.host.wire.WireFrames;
import java.io.ByteArrayOutputStream;
import java.io.IOException;
import java.io.OutputStream;
import java.nio.ByteBuffer;

/**
 * What the agent wire's fuzz target ({@link HostDecodersFuzzTest#wireFrames}) writes on a
 * connection, read from the fuzzer's bytes: a list of segments, each {@code [kind u8][length u16][payload]}.
 *
 * <pre>
 * kind 0  raw bytes: the payload as it is
 * kind 1  a frame: payload = [version u8][code u8][session u8][seq u16][tag u8][length u8][body...]
 *           session 0: the fuzzing peer's session, else a session id the host does not know
 *           seq: added to the input's own base, so inputs never reuse one another's numbers
 *           tag 0: right, 1: one bit wrong, 2: none written
 *           length 0: the body's, else the body's plus length × 4099 (a header that lies)
 * </pre>
 *
 * A payload cut short by the end of the input is written as raw bytes. Frames are sealed when the
 * input runs, with the session the target made: the fuzzer reaches what lies past the tag check.
 */
final class WireScript {

    static final int RAW = 0;
    static final int FRAME = 1;

    private WireScript() {
    }

    /**
     * Writes what the script says.
     *
     * @param script  the fuzzer's bytes
     * @param session the session frames are sealed with
     * @param seqBase added to every frame's sequence number
     * @param out     where the bytes go
     */
    static void play(byte[] script, Session session, long seqBase, OutputStream out) throws IOException {
        ByteBuffer in = ByteBuffer.wrap(script);
        while (in.remaining() >= 3) {
            int kind = in.get() & 0xFF;
            int length = in.getShort() & 0xFFFF;
            byte[] payload = new byte[Math.min(length, in.remaining())];
            in.get(payload);
            if (kind % 2 == FRAME && payload.length == length && length >= 7) {
                frame(ByteBuffer.wrap(payload), session, seqBase, out);
            } else {
                out.write(payload);
            }
        }
        out.write(script, in.position(), in.remaining());
        out.flush();
    }

    private static void frame(ByteBuffer p, Session session, long seqBase, OutputStream out) throws IOException {
        int version = p.get() & 0xFF;
        int code = p.get() & 0xFF;
        long id = p.get() == 0 ? session.id : session.id ^ 0x5A5A_5A5A_5A5A_5A5AL;
        long seq = seqBase + (p.getShort() & 0xFFFF);
        int tag = p.get() & 0xFF;
        int lie = p.get() & 0xFF;
        byte[] body = new byte[p.remaining()];
        p.get(body);
        long claimed = body.length + (long) lie * 4099;
        byte[] header = ByteBuffer.allocate(WireFrames.HEADER).put((byte) version).put((byte) code).putLong(id).putLong(seq).putInt((int) claimed).array();
        out.write(header);
        out.write(body);
        if (tag % 3 == 2) {
            return;
        }
        FrameTag t = new FrameTag();
        t.start(session.frameKey, WireFrames.DIRECTION_REQUEST, seq, false);
        t.update(header, 0, header.length);
        t.update(body, 0, body.length);
        byte[] sealed = t.finish().clone();
        if (tag % 3 == 1) {
            sealed[sealed.length - 1] ^= 1;
        }
        out.write(sealed);
    }

    /** Builds scripts (for the seeds). */
    static final class Builder {
        private final ByteArrayOutputStream bytes = new ByteArrayOutputStream();

        Builder raw(byte[] b) {
            segment(RAW, b);
            return this;
        }

        Builder frame(int version, int code, boolean ownSession, int seq, int tag, int lie, byte[] body) {
            ByteBuffer p = ByteBuffer.allocate(7 + body.length).put((byte) version).put((byte) code).put((byte) (ownSession ? 0 : 1))
                    .putShort((short) seq).put((byte) tag).put((byte) lie).put(body);
            segment(FRAME, p.array());
            return this;
        }

        private void segment(int kind, byte[] payload) {
            bytes.write(kind);
            bytes.write(payload.length >>> 8);
            bytes.write(payload.length);
            bytes.writeBytes(payload);
        }

        byte[] build() {
            return bytes.toByteArray();
        }
    }
}
