package io.robomw.agents.host;

import io.robomw.agents.host.code.CodeArchive;
import io.robomw.api.AgentStatus;

import java.io.ByteArrayInputStream;
import java.io.ByteArrayOutputStream;
import java.io.DataInputStream;
import java.io.DataOutputStream;
import java.io.IOException;
import java.io.UncheckedIOException;
import java.nio.ByteBuffer;
import java.nio.charset.StandardCharsets;
import java.util.ArrayList;
import java.util.Arrays;
import java.util.List;
import java.util.UUID;

/**
 * The layouts of the call bodies and replies hosts exchange, besides the agent image
 * ({@link AgentImage}) and the event ({@link AgentEvent}), and of the owed-event records a host
 * stores. All integers are big-endian; an id is its most and then its least significant 64 bits.
 *
 * <pre>
 * LIST reply       [count 4] then per agent: [id 16][class name: length 2, modified UTF-8][status 1][hop 8][home: length 2, modified UTF-8]
 * MESSAGE body     [id 16][one-way 1][content: the serialized value]
 * RETRACT, DISPOSE [id 16]
 * PUT_ARCHIVE body [claimed SHA-256 32][the jar]
 * owed event       [home length 2][home UTF-8][the encoded AgentEvent]
 * </pre>
 */
final class Bodies {

    private Bodies() {
    }

    // ---- LIST ----

    /** @param agents the agents at a host @return the LIST reply's body */
    static byte[] listReply(List<AgentInfo> agents) {
        try {
            ByteArrayOutputStream bytes = new ByteArrayOutputStream();
            DataOutputStream out = new DataOutputStream(bytes);
            out.writeInt(agents.size());
            for (AgentInfo a : agents) {
                out.writeLong(a.id().getMostSignificantBits());
                out.writeLong(a.id().getLeastSignificantBits());
                out.writeUTF(a.className());
                out.writeByte(a.status().ordinal());
                out.writeLong(a.hop());
                out.writeUTF(a.home());
            }
            return bytes.toByteArray();
        } catch (IOException e) {
            throw new UncheckedIOException(e);
        }
    }

    /**
     * @param body a LIST reply's body
     * @return the agents it lists
     * @throws IOException if it is cut short
     */
    static List<AgentInfo> readListReply(byte[] body) throws IOException {
        DataInputStream in = new DataInputStream(new ByteArrayInputStream(body));
        int n = in.readInt();
        List<AgentInfo> out = new ArrayList<>();
        for (int i = 0; i < n; i++) {
            UUID id = new UUID(in.readLong(), in.readLong());
            String cls = in.readUTF();
            AgentStatus status = AgentStatus.values()[in.readByte()];
            long hop = in.readLong();
            String home = in.readUTF();
            out.add(new AgentInfo(id, cls, status, hop, home));
        }
        return out;
    }

    // ---- MESSAGE ----

    /**
     * A message for an agent.
     *
     * @param id      the agent
     * @param oneway  whether the sender waits for no answer
     * @param content the serialized value
     */
    record Message(UUID id, boolean oneway, byte[] content) {
    }

    /** @return a MESSAGE body */
    static byte[] message(UUID id, boolean oneway, byte[] content) {
        return ByteBuffer.allocate(17 + content.length).putLong(id.getMostSignificantBits()).putLong(id.getLeastSignificantBits())
                .put((byte) (oneway ? 1 : 0)).put(content).array();
    }

    /** @param body a MESSAGE body @return the message */
    static Message readMessage(byte[] body) {
        ByteBuffer b = ByteBuffer.wrap(body);
        UUID id = new UUID(b.getLong(), b.getLong());
        boolean oneway = b.get() != 0;
        byte[] content = new byte[b.remaining()];
        b.get(content);
        return new Message(id, oneway, content);
    }

    // ---- RETRACT, DISPOSE ----

    /** @param id an agent @return a RETRACT or DISPOSE body */
    static byte[] agentRequest(UUID id) {
        return ByteBuffer.allocate(16).putLong(id.getMostSignificantBits()).putLong(id.getLeastSignificantBits()).array();
    }

    /** @param body a RETRACT or DISPOSE body @return the agent it names */
    static UUID readAgentRequest(byte[] body) {
        ByteBuffer b = ByteBuffer.wrap(body);
        return new UUID(b.getLong(), b.getLong());
    }

    // ---- PUT_ARCHIVE ----

    /**
     * An archive as a peer sends it.
     *
     * @param claimed the digest the peer claims for it
     * @param jar     its bytes
     */
    record Archive(CodeArchive.Digest claimed, byte[] jar) {
    }

    /** @return a PUT_ARCHIVE body */
    static byte[] archive(CodeArchive archive) {
        byte[] digest = archive.digest().bytes();
        return ByteBuffer.allocate(digest.length + archive.bytes().length).put(digest).put(archive.bytes()).array();
    }

    /**
     * @param body a PUT_ARCHIVE body
     * @return the archive it holds, not yet checked against its digest
     * @throws IllegalArgumentException if it is too short to hold a digest and a jar
     */
    static Archive readArchive(byte[] body) {
        if (body.length <= CodeArchive.Digest.LENGTH) {
            throw new IllegalArgumentException(body.length + " bytes is too short");
        }
        return new Archive(new CodeArchive.Digest(Arrays.copyOf(body, CodeArchive.Digest.LENGTH)),
                Arrays.copyOfRange(body, CodeArchive.Digest.LENGTH, body.length));
    }

    // ---- owed events ----

    /**
     * An event a host owes an agent's home, as the store keeps it.
     *
     * @param home  the home's address
     * @param event the event
     */
    record OwedEvent(String home, AgentEvent event) {
    }

    /** @return the stored form of an event owed to a home */
    static byte[] owedEvent(String home, AgentEvent event) {
        byte[] homeBytes = home.getBytes(StandardCharsets.UTF_8);
        byte[] e = event.encode();
        return ByteBuffer.allocate(2 + homeBytes.length + e.length).putShort((short) homeBytes.length).put(homeBytes).put(e).array();
    }

    /** @param record the stored form of an owed event @return the event and its home */
    static OwedEvent readOwedEvent(byte[] record) {
        ByteBuffer b = ByteBuffer.wrap(record);
        byte[] home = new byte[Short.toUnsignedInt(b.getShort())];
        b.get(home);
        byte[] e = new byte[b.remaining()];
        b.get(e);
        return new OwedEvent(new String(home, StandardCharsets.UTF_8), AgentEvent.decode(e));
    }
}
