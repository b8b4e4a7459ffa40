package io.robomw.agents.host.protocol;

import io.robomw.agents.net.WireCode;
import io.robomw.agents.net.WireCodes;

import java.nio.ByteBuffer;
import java.nio.charset.StandardCharsets;
import java.util.UUID;

/**
 * What a host tells an agent's home. All integers are big-endian.
 *
 * <pre>
 * [id 16][seq 8][kind 1][location length 2][location UTF-8][payload]
 * </pre>
 *
 * <table>
 * <caption>Event kind codes ({@link Kind})</caption>
 * <tr><th>code</th><th>kind</th><th>payload</th></tr>
 * <tr><td>0</td><td>ARRIVED</td><td>empty</td></tr>
 * <tr><td>1</td><td>REPORT</td><td>the serialized value</td></tr>
 * <tr><td>2</td><td>RESULT</td><td>the serialized result</td></tr>
 * <tr><td>3</td><td>FAILED</td><td>why, UTF-8</td></tr>
 * <tr><td>4</td><td>DISPOSED</td><td>where, UTF-8</td></tr>
 * <tr><td>5</td><td>VISITS</td><td>the trip's visits, {@link Bodies#visits}; owed just before the trip's last event</td></tr>
 * </table>
 *
 * @param id       the agent
 * @param seq      its order among the agent's reports and results (0 for arrivals, which are not ordered)
 * @param kind     what happened
 * @param location the host it happened at
 * @param payload  the serialized report or result, or the reason of a failure (UTF-8)
 */
public record AgentEvent(UUID id, long seq, Kind kind, String location, byte[] payload) {

    /** What happened. Each kind travels as its {@link #code()}, never as its position here. */
    public enum Kind implements WireCode {
        /** The agent arrived at {@code location}. */
        ARRIVED(0),
        /** The agent sent a value home. */
        REPORT(1),
        /** The trip ended; the payload is the result. */
        RESULT(2),
        /** The trip ended in failure; the payload says why. */
        FAILED(3),
        /** The agent was disposed of. */
        DISPOSED(4),
        /** The trip's visits, owed just before the event that ends it. */
        VISITS(5);

        private static final WireCodes<Kind> CODES = WireCodes.of(Kind.class, "event kind");

        private final int code;

        Kind(int code) {
            this.code = code;
        }

        /** @return the kind's code on the wire and in the store */
        @Override
        public int code() {
            return code;
        }

        /**
         * @param code a kind byte as read (unsigned)
         * @return its kind
         * @throws IllegalArgumentException naming the code if no kind has it
         */
        static Kind fromCode(int code) {
            return CODES.get(code);
        }
    }

    public byte[] encode() {
        byte[] loc = location.getBytes(StandardCharsets.UTF_8);
        ByteBuffer b = ByteBuffer.allocate(16 + 8 + 1 + 2 + loc.length + payload.length);
        b.putLong(id.getMostSignificantBits()).putLong(id.getLeastSignificantBits()).putLong(seq).put((byte) kind.code());
        b.putShort((short) loc.length).put(loc).put(payload);
        return b.array();
    }

    /**
     * @param bytes an encoded event
     * @return the event
     * @throws IllegalArgumentException if it is cut short or its kind is unknown (the message names the code)
     */
    public static AgentEvent decode(byte[] bytes) {
        ByteBuffer b = ByteBuffer.wrap(bytes);
        try {
            UUID id = new UUID(b.getLong(), b.getLong());
            long seq = b.getLong();
            Kind kind = Kind.fromCode(b.get() & 0xFF);
            byte[] loc = new byte[Short.toUnsignedInt(b.getShort())];
            b.get(loc);
            byte[] payload = new byte[b.remaining()];
            b.get(payload);
            return new AgentEvent(id, seq, kind, new String(loc, StandardCharsets.UTF_8), payload);
        } catch (java.nio.BufferUnderflowException e) {
            throw new IllegalArgumentException("agent event cut short (" + bytes.length + " bytes)", e);
        }
    }
}
