package io.robomw.agents.host;

import java.nio.ByteBuffer;
import java.nio.charset.StandardCharsets;
import java.util.UUID;

/**
 * What a host tells an agent's home.
 *
 * @param id       the agent
 * @param seq      its order among the agent's reports and results (0 for arrivals, which are not ordered)
 * @param kind     what happened
 * @param location the host it happened at
 * @param payload  the serialized report or result, or the reason of a failure (UTF-8)
 */
record AgentEvent(UUID id, long seq, Kind kind, String location, byte[] payload) {

    /** What happened. */
    enum Kind {
        /** The agent arrived at {@code location}. */
        ARRIVED,
        /** The agent sent a value home. */
        REPORT,
        /** The trip ended; the payload is the result. */
        RESULT,
        /** The trip ended in failure; the payload says why. */
        FAILED,
        /** The agent was disposed of. */
        DISPOSED
    }

    byte[] encode() {
        byte[] loc = location.getBytes(StandardCharsets.UTF_8);
        ByteBuffer b = ByteBuffer.allocate(16 + 8 + 1 + 2 + loc.length + payload.length);
        b.putLong(id.getMostSignificantBits()).putLong(id.getLeastSignificantBits()).putLong(seq).put((byte) kind.ordinal());
        b.putShort((short) loc.length).put(loc).put(payload);
        return b.array();
    }

    static AgentEvent decode(byte[] bytes) {
        ByteBuffer b = ByteBuffer.wrap(bytes);
        try {
            UUID id = new UUID(b.getLong(), b.getLong());
            long seq = b.getLong();
            int kind = b.get();
            if (kind < 0 || kind >= Kind.values().length) {
                throw new IllegalArgumentException("unknown event kind " + kind);
            }
            byte[] loc = new byte[Short.toUnsignedInt(b.getShort())];
            b.get(loc);
            byte[] payload = new byte[b.remaining()];
            b.get(payload);
            return new AgentEvent(id, seq, Kind.values()[kind], new String(loc, StandardCharsets.UTF_8), payload);
        } catch (java.nio.BufferUnderflowException e) {
            throw new IllegalArgumentException("agent event cut short (" + bytes.length + " bytes)", e);
        }
    }
}
