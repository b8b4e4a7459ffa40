package io.robomw.agents.host.protocol;

import io.robomw.agents.host.rmi.Session;
import io.robomw.agents.net.WireCode;
import io.robomw.agents.net.WireCodes;

import io.robomw.agents.host.code.CodeArchive;
import io.robomw.agents.host.code.StateCodec;

import java.io.IOException;

import java.nio.ByteBuffer;
import java.nio.charset.StandardCharsets;
import java.util.UUID;

/**
 * An agent as it travels and as a host stores it: who it is, which hop this is, where its home
 * is, which archive holds its code, and its serialized state. The header is compact (numbers as
 * varints, no class name: the state names its class), so a warm hop costs little more than the
 * state itself. Varints are unsigned LEB128 (7 bits a byte, least significant first); the id is
 * big-endian.
 *
 * <pre>
 * [kind|flags 1][id 16][hop varint][eventSeq varint][home length varint][home UTF-8][digest 32][state]
 *
 * kind|flags:  bit 7 0 | bit 6 FROM_HOME | bits 5-4 0 | bits 3-0 kind code
 * </pre>
 *
 * <table>
 * <caption>Image kind codes ({@link Kind})</caption>
 * <tr><th>code</th><th>kind</th></tr>
 * <tr><td>0</td><td>TRIP: to its next stop</td></tr>
 * <tr><td>1</td><td>HOMECOMING: home, retracted</td></tr>
 * </table>
 *
 * <p>A first byte with a bit set outside these fields, or a kind code that is not in the table,
 * is refused naming the byte.
 *
 * @param id       the agent's id
 * @param hop      counts the agent's hops, from 1; a host never accepts a hop it has seen, so a retried transfer is not run twice
 * @param kind     why it travels
 * @param fromHome whether the host sending it is its home, which then knows where it went without being told
 * @param home     its home's address
 * @param digest   the archive of its code
 * @param eventSeq the sequence number of its next event to its home
 * @param state       holds its serialized state (for a received image: the whole request it came in)
 * @param stateOffset where the state starts in {@code state}
 * @param stateLength the state's length
 */
public record AgentImage(UUID id, long hop, Kind kind, boolean fromHome, String home, CodeArchive.Digest digest, long eventSeq,
                  byte[] state, int stateOffset, int stateLength) {

    /** An image whose state is a whole array (an empty one for an image that is only a header). */
    public AgentImage(UUID id, long hop, Kind kind, boolean fromHome, String home, CodeArchive.Digest digest, long eventSeq, byte[] state) {
        this(id, hop, kind, fromHome, home, digest, eventSeq, state, 0, state.length);
    }

    private static final int FROM_HOME = 0x40;
    private static final int KIND_MASK = 0x0f;

    /** Why an agent travels. Each kind travels as its {@link #code()}, never as its position here. */
    public enum Kind implements WireCode {
        /** To its next stop. */
        TRIP(0),
        /** Home, retracted: its state completes the retract. */
        HOMECOMING(1);

        private static final WireCodes<Kind> CODES = WireCodes.of(Kind.class, "agent image kind");

        private final int code;

        Kind(int code) {
            this.code = code;
        }

        /** @return the kind's code in the image's first byte */
        @Override
        public int code() {
            return code;
        }

        /**
         * @param code the low four bits of an image's first byte
         * @return its kind
         * @throws IllegalArgumentException naming the code if no kind has it
         */
        static Kind fromCode(int code) {
            return CODES.get(code);
        }
    }

    public byte[] encode() {
        ByteBuffer b = header(stateLength);
        b.put(state, stateOffset, stateLength);
        return java.util.Arrays.copyOf(b.array(), b.position());
    }

    /** The header, in a buffer with room for {@code room} more bytes. */
    private ByteBuffer header(int room) {
        byte[] homeBytes = home.getBytes(StandardCharsets.UTF_8);
        ByteBuffer b = ByteBuffer.allocate(1 + 16 + 10 + 10 + 5 + homeBytes.length + CodeArchive.Digest.LENGTH + room);
        b.put((byte) (kind.code() | (fromHome ? FROM_HOME : 0)));
        b.putLong(id.getMostSignificantBits()).putLong(id.getLeastSignificantBits());
        putVarint(b, hop);
        putVarint(b, eventSeq);
        putVarint(b, homeBytes.length);
        b.put(homeBytes).put(digest.bytes());
        return b;
    }

    /**
     * This image's header followed by an agent's state, written straight into a call's frame.
     *
     * @param agent    the agent whose state travels (this image's own state is not used)
     * @param expected about how long the image will be (its length when it last travelled)
     * @param buffers  where a large frame's array is taken from if one fits (give it back once the transfer is over)
     * @param codec    the host's state codec
     * @param reads    the form of state the next host reads ({@link StateCodec#writeAgent})
     * @return the frame
     * @throws IOException if the agent is not serializable
     */
    public Frame frame(java.io.Serializable agent, int expected, FrameBuffers buffers, StateCodec codec, StateCodec.Form reads) throws IOException {
        Frame.Buffer out = new Frame.Buffer(expected, buffers.take(Session.HEADER + Math.max(64, expected) + Session.MAC));
        ByteBuffer h = header(0);
        out.write(h.array(), 0, h.position());
        codec.writeAgent(agent, out, reads);
        return out.finish();
    }

    public static AgentImage decode(byte[] bytes) {
        return decode(bytes, 0, bytes.length);
    }

    /** Decodes an image from part of an array; its state stays in that array (not copied). */
    public static AgentImage decode(byte[] bytes, int offset, int length) {
        ByteBuffer b = ByteBuffer.wrap(bytes, offset, length);
        try {
            int first = b.get() & 0xFF;
            if ((first & ~(KIND_MASK | FROM_HOME)) != 0) {
                throw new IllegalArgumentException(String.format("agent image's first byte 0x%02x sets bits outside its kind and flags", first));
            }
            Kind kind = Kind.fromCode(first & KIND_MASK);
            UUID id = new UUID(b.getLong(), b.getLong());
            long hop = varint(b);
            long eventSeq = varint(b);
            long homeLength = varint(b);
            if (homeLength > b.remaining()) {
                throw new IllegalArgumentException("agent image cut short (" + length + " bytes)");
            }
            byte[] home = new byte[(int) homeLength];
            b.get(home);
            byte[] digest = new byte[CodeArchive.Digest.LENGTH];
            b.get(digest);
            return new AgentImage(id, hop, kind, (first & FROM_HOME) != 0, new String(home, StandardCharsets.UTF_8),
                    new CodeArchive.Digest(digest), eventSeq, bytes, b.position(), b.remaining());
        } catch (java.nio.BufferUnderflowException e) {
            throw new IllegalArgumentException("agent image cut short (" + length + " bytes)", e);
        }
    }

    private static void putVarint(ByteBuffer b, long v) {
        if (v < 0) {
            throw new IllegalArgumentException("negative number " + v + " in an agent image");
        }
        while ((v & ~0x7fL) != 0) {
            b.put((byte) ((v & 0x7f) | 0x80));
            v >>>= 7;
        }
        b.put((byte) v);
    }

    private static long varint(ByteBuffer b) {
        long v = 0;
        for (int shift = 0; shift < 64; shift += 7) {
            int x = b.get();
            v |= (long) (x & 0x7f) << shift;
            if ((x & 0x80) == 0) {
                if (v < 0) {
                    throw new IllegalArgumentException("number out of range in an agent image");
                }
                return v;
            }
        }
        throw new IllegalArgumentException("malformed number in an agent image");
    }

    String shortId() {
        return id.toString().substring(0, 8);
    }
}
