package io.robomw.agents.host;

import io.robomw.agents.host.code.CodeArchive;

import java.nio.ByteBuffer;
import java.nio.charset.StandardCharsets;
import java.util.UUID;

/**
 * An agent as it travels and as a host stores it: who it is, which hop this is, where its home
 * is, which archive holds its code, and its serialized state. The header is a few dozen bytes, so
 * a warm hop costs little more than the state itself.
 *
 * @param id        the agent's id
 * @param hop       counts the agent's hops, from 1; a host never accepts a hop it has seen, so a retried transfer is not run twice
 * @param kind      why it travels
 * @param home      its home's address
 * @param digest    the archive of its code
 * @param eventSeq  the sequence number of its next event to its home
 * @param className its class, for listings and logs
 * @param state     its serialized state
 */
record AgentImage(UUID id, long hop, Kind kind, String home, CodeArchive.Digest digest, long eventSeq, String className, byte[] state) {

    /** Why an agent travels. */
    enum Kind {
        /** To its next stop. */
        TRIP,
        /** Home, retracted: its state completes the retract. */
        HOMECOMING
    }

    byte[] encode() {
        byte[] homeBytes = home.getBytes(StandardCharsets.UTF_8);
        byte[] classBytes = className.getBytes(StandardCharsets.UTF_8);
        ByteBuffer b = ByteBuffer.allocate(16 + 8 + 1 + 2 + homeBytes.length + 32 + 8 + 2 + classBytes.length + state.length);
        b.putLong(id.getMostSignificantBits()).putLong(id.getLeastSignificantBits()).putLong(hop).put((byte) kind.ordinal());
        b.putShort((short) homeBytes.length).put(homeBytes).put(digest.bytes()).putLong(eventSeq);
        b.putShort((short) classBytes.length).put(classBytes).put(state);
        return b.array();
    }

    static AgentImage decode(byte[] bytes) {
        ByteBuffer b = ByteBuffer.wrap(bytes);
        try {
            UUID id = new UUID(b.getLong(), b.getLong());
            long hop = b.getLong();
            int kind = b.get();
            if (kind < 0 || kind >= Kind.values().length) {
                throw new IllegalArgumentException("unknown image kind " + kind);
            }
            String home = string(b);
            byte[] digest = new byte[CodeArchive.Digest.LENGTH];
            b.get(digest);
            long eventSeq = b.getLong();
            String className = string(b);
            byte[] state = new byte[b.remaining()];
            b.get(state);
            return new AgentImage(id, hop, Kind.values()[kind], home, new CodeArchive.Digest(digest), eventSeq, className, state);
        } catch (java.nio.BufferUnderflowException e) {
            throw new IllegalArgumentException("agent image cut short (" + bytes.length + " bytes)", e);
        }
    }

    private static String string(ByteBuffer b) {
        int n = Short.toUnsignedInt(b.getShort());
        byte[] s = new byte[n];
        b.get(s);
        return new String(s, StandardCharsets.UTF_8);
    }

    String shortId() {
        return id.toString().substring(0, 8);
    }
}
