package io.robomw.agents.host;

import io.robomw.agents.host.code.CodeArchive;
import io.robomw.api.AgentStatus;
import io.robomw.api.Itinerary;

import java.io.ByteArrayInputStream;
import java.io.ByteArrayOutputStream;
import java.io.DataInputStream;
import java.io.DataOutputStream;
import java.io.EOFException;
import java.io.IOException;
import java.io.UncheckedIOException;
import java.nio.BufferUnderflowException;
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
 * OWED reply       [count 4] then per delivery: [agent id 16][event seq 8][event kind 1, {@link AgentEvent.Kind}'s code]
 *                  [home: length 2, modified UTF-8][owed since 8, ms since the epoch][failed tries 4][last error: length 2, modified UTF-8]
 * DROP_OWED body   [selector 1, {@link OwedSelector.Kind}'s code] then: ALL nothing; AGENT [id 16]; HOME [home: length 2, modified UTF-8]
 * VISITS payload   [count 4] then per visit: [round 4][host: length 2, modified UTF-8][outcome 1][detail: length 2, modified UTF-8]
 * </pre>
 *
 * <table>
 * <caption>Visit outcome codes in a VISITS payload ({@link Itinerary.Outcome}, an API type, so its codes are kept here;
 * they are those of the itinerary's serial form)</caption>
 * <tr><th>code</th><th>outcome</th></tr>
 * <tr><td>0</td><td>DONE</td></tr>
 * <tr><td>1</td><td>FAILED</td></tr>
 * <tr><td>2</td><td>UNREACHABLE</td></tr>
 * <tr><td>3</td><td>INTERRUPTED</td></tr>
 * </table>
 *
 * <table>
 * <caption>Agent status codes in a LIST reply ({@link AgentStatus}, an API type, so its codes are kept here)</caption>
 * <tr><th>code</th><th>status</th></tr>
 * <tr><td>0</td><td>CREATED</td></tr>
 * <tr><td>1</td><td>ACTIVE</td></tr>
 * <tr><td>2</td><td>IN_TRANSIT</td></tr>
 * <tr><td>3</td><td>COMPLETED</td></tr>
 * <tr><td>4</td><td>DISPOSED</td></tr>
 * <tr><td>5</td><td>RETRACTED</td></tr>
 * <tr><td>6</td><td>FAILED</td></tr>
 * <tr><td>7</td><td>ACTIVE, retract pending ({@link AgentInfo.Pending#RETRACT}: its callback was interrupted and has not returned)</td></tr>
 * <tr><td>8</td><td>ACTIVE, dispose pending ({@link AgentInfo.Pending#DISPOSE})</td></tr>
 * </table>
 *
 * <table>
 * <caption>One-way flag of a MESSAGE body</caption>
 * <tr><th>code</th><th>meaning</th></tr>
 * <tr><td>0</td><td>the sender waits for the agent's answer</td></tr>
 * <tr><td>1</td><td>one-way: nobody waits</td></tr>
 * </table>
 *
 * <p>Readers check what they read: a body cut short, a code not in these tables or bytes left
 * over fail with an error that says which, for the caller to refuse naming the peer.
 */
final class Bodies {

    /** The MESSAGE one-way flag of a message whose sender waits for the answer. */
    static final int TWO_WAY = 0;
    /** The MESSAGE one-way flag of a message nobody waits for. */
    static final int ONE_WAY = 1;
    private static final int ID_BYTES = 16;
    /** The shortest agent in a LIST reply: id, empty class name, status, hop, empty home. */
    private static final int MIN_LISTED_BYTES = ID_BYTES + 2 + 1 + 8 + 2;

    private Bodies() {
    }

    // ---- agent status codes ----

    /** A LIST reply's status code for an active agent whose retract is pending. */
    static final int RETRACT_PENDING = 7;
    /** A LIST reply's status code for an active agent whose dispose is pending. */
    static final int DISPOSE_PENDING = 8;

    /** @return the code of a status in a LIST reply */
    static int statusCode(AgentStatus status) {
        return switch (status) {
            case CREATED -> 0;
            case ACTIVE -> 1;
            case IN_TRANSIT -> 2;
            case COMPLETED -> 3;
            case DISPOSED -> 4;
            case RETRACTED -> 5;
            case FAILED -> 6;
        };
    }

    /**
     * @param code a status code as read (unsigned)
     * @return its status
     * @throws IllegalArgumentException naming the code if no status has it
     */
    static AgentStatus status(int code) {
        return switch (code) {
            case 0 -> AgentStatus.CREATED;
            case 1 -> AgentStatus.ACTIVE;
            case 2 -> AgentStatus.IN_TRANSIT;
            case 3 -> AgentStatus.COMPLETED;
            case 4 -> AgentStatus.DISPOSED;
            case 5 -> AgentStatus.RETRACTED;
            case 6 -> AgentStatus.FAILED;
            default -> throw new IllegalArgumentException("unknown agent status code " + code + " (known: 0-8)");
        };
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
                out.writeByte(a.pending() == AgentInfo.Pending.RETRACT ? RETRACT_PENDING : a.pending() == AgentInfo.Pending.DISPOSE ? DISPOSE_PENDING
                        : statusCode(a.status()));
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
     * @param from the host that sent it, for errors
     * @return the agents it lists
     * @throws IOException naming the host and what is wrong, if it is cut short, has bytes left over or holds an unknown status code
     */
    static List<AgentInfo> readListReply(byte[] body, String from) throws IOException {
        DataInputStream in = new DataInputStream(new ByteArrayInputStream(body));
        try {
            int n = in.readInt();
            if (n < 0 || n > (body.length - 4) / MIN_LISTED_BYTES) {
                throw new IOException("host " + from + " sent a LIST reply of " + body.length + " bytes claiming " + n + " agents");
            }
            List<AgentInfo> out = new ArrayList<>(n);
            for (int i = 0; i < n; i++) {
                UUID id = new UUID(in.readLong(), in.readLong());
                String cls = in.readUTF();
                int code = in.readUnsignedByte();
                AgentStatus status;
                AgentInfo.Pending pending = code == RETRACT_PENDING ? AgentInfo.Pending.RETRACT
                        : code == DISPOSE_PENDING ? AgentInfo.Pending.DISPOSE : AgentInfo.Pending.NONE;
                try {
                    status = pending != AgentInfo.Pending.NONE ? AgentStatus.ACTIVE : status(code);
                } catch (IllegalArgumentException e) {
                    throw new IOException("host " + from + " listed agent " + id + " with an " + e.getMessage(), e);
                }
                long hop = in.readLong();
                String home = in.readUTF();
                out.add(new AgentInfo(id, cls, status, hop, home, pending));
            }
            if (in.available() > 0) {
                throw new IOException("host " + from + " sent a LIST reply with " + in.available() + " bytes after its " + n + " agents");
            }
            return out;
        } catch (EOFException e) {
            throw new IOException("host " + from + " sent a LIST reply cut short (" + body.length + " bytes)", e);
        }
    }

    // ---- OWED, DROP_OWED ----

    /** The longest last-error text an OWED reply carries per delivery. */
    private static final int MAX_ERROR_CHARS = 500;
    /** The shortest delivery in an OWED reply: id, seq, kind, empty home, since, tries, empty error. */
    private static final int MIN_OWED_BYTES = ID_BYTES + 8 + 1 + 2 + 8 + 4 + 2;

    /** @param owed deliveries @return an OWED (or DROP_OWED) reply's body */
    static byte[] owedReply(List<OwedDelivery> owed) {
        try {
            ByteArrayOutputStream bytes = new ByteArrayOutputStream();
            DataOutputStream out = new DataOutputStream(bytes);
            out.writeInt(owed.size());
            for (OwedDelivery d : owed) {
                out.writeLong(d.agent().getMostSignificantBits());
                out.writeLong(d.agent().getLeastSignificantBits());
                out.writeLong(d.seq());
                out.writeByte(AgentEvent.Kind.valueOf(d.kind()).code());
                out.writeUTF(d.home());
                out.writeLong(d.owedSince().toEpochMilli());
                out.writeInt(d.attempts());
                String error = d.lastError();
                out.writeUTF(error.length() > MAX_ERROR_CHARS ? error.substring(0, MAX_ERROR_CHARS) + "..." : error);
            }
            return bytes.toByteArray();
        } catch (IOException e) {
            throw new UncheckedIOException(e);
        }
    }

    /**
     * @param body an OWED or DROP_OWED reply's body
     * @param from the host that sent it, for errors
     * @return the deliveries it lists
     * @throws IOException naming the host and what is wrong, if it is cut short, has bytes left over or holds an unknown kind code
     */
    static List<OwedDelivery> readOwedReply(byte[] body, String from) throws IOException {
        DataInputStream in = new DataInputStream(new ByteArrayInputStream(body));
        try {
            int n = in.readInt();
            if (n < 0 || n > (body.length - 4) / MIN_OWED_BYTES) {
                throw new IOException("host " + from + " sent an OWED reply of " + body.length + " bytes claiming " + n + " deliveries");
            }
            List<OwedDelivery> out = new ArrayList<>(n);
            for (int i = 0; i < n; i++) {
                UUID id = new UUID(in.readLong(), in.readLong());
                long seq = in.readLong();
                AgentEvent.Kind kind;
                try {
                    kind = AgentEvent.Kind.fromCode(in.readUnsignedByte());
                } catch (IllegalArgumentException e) {
                    throw new IOException("host " + from + " listed a delivery of agent " + id + " with an " + e.getMessage(), e);
                }
                String home = in.readUTF();
                java.time.Instant since = java.time.Instant.ofEpochMilli(in.readLong());
                int attempts = in.readInt();
                String error = in.readUTF();
                out.add(new OwedDelivery(id, seq, kind.name(), home, since, attempts, error));
            }
            if (in.available() > 0) {
                throw new IOException("host " + from + " sent an OWED reply with " + in.available() + " bytes after its " + n + " deliveries");
            }
            return out;
        } catch (EOFException e) {
            throw new IOException("host " + from + " sent an OWED reply cut short (" + body.length + " bytes)", e);
        } catch (java.time.DateTimeException e) {
            throw new IOException("host " + from + " sent an OWED reply with a time out of range: " + e.getMessage(), e);
        }
    }

    /** @param which the deliveries to drop @return a DROP_OWED body */
    static byte[] dropOwed(OwedSelector which) {
        try {
            ByteArrayOutputStream bytes = new ByteArrayOutputStream();
            DataOutputStream out = new DataOutputStream(bytes);
            out.writeByte(which.kind().code());
            switch (which.kind()) {
                case ALL -> {
                }
                case AGENT -> {
                    out.writeLong(which.agent().getMostSignificantBits());
                    out.writeLong(which.agent().getLeastSignificantBits());
                }
                case HOME -> out.writeUTF(which.home());
            }
            return bytes.toByteArray();
        } catch (IOException e) {
            throw new UncheckedIOException(e);
        }
    }

    /**
     * @param body a DROP_OWED body
     * @return the selector it holds
     * @throws IllegalArgumentException if it is empty, cut short, has bytes left over or names an unknown selector code
     */
    static OwedSelector readDropOwed(byte[] body) {
        DataInputStream in = new DataInputStream(new ByteArrayInputStream(body));
        try {
            OwedSelector.Kind kind = OwedSelector.Kind.fromCode(in.readUnsignedByte());
            OwedSelector which = switch (kind) {
                case ALL -> OwedSelector.all();
                case AGENT -> OwedSelector.agent(new UUID(in.readLong(), in.readLong()));
                case HOME -> OwedSelector.home(in.readUTF());
            };
            if (in.available() > 0) {
                throw new IllegalArgumentException("a DROP_OWED body with " + in.available() + " bytes after its selector");
            }
            return which;
        } catch (IOException e) {
            throw new IllegalArgumentException("a DROP_OWED body cut short (" + body.length + " bytes)", e);
        }
    }

    // ---- VISITS ----

    /** The longest detail a VISITS payload carries per visit (a stack trace is cut there). */
    static final int MAX_DETAIL_CHARS = 8_000;
    /** The shortest visit: round, empty host, outcome, empty detail. */
    private static final int MIN_VISIT_BYTES = 4 + 2 + 1 + 2;

    /** @return the code of a visit's outcome */
    static int outcomeCode(Itinerary.Outcome outcome) {
        return switch (outcome) {
            case DONE -> 0;
            case FAILED -> 1;
            case UNREACHABLE -> 2;
            case INTERRUPTED -> 3;
        };
    }

    /**
     * @param code an outcome code as read (unsigned)
     * @return its outcome
     * @throws IllegalArgumentException naming the code if no outcome has it
     */
    static Itinerary.Outcome outcome(int code) {
        return switch (code) {
            case 0 -> Itinerary.Outcome.DONE;
            case 1 -> Itinerary.Outcome.FAILED;
            case 2 -> Itinerary.Outcome.UNREACHABLE;
            case 3 -> Itinerary.Outcome.INTERRUPTED;
            default -> throw new IllegalArgumentException("unknown visit outcome code " + code + " (known: 0 DONE, 1 FAILED, 2 UNREACHABLE, 3 INTERRUPTED)");
        };
    }

    /** @param visits a trip's visits @return a VISITS event's payload (each detail cut to {@value #MAX_DETAIL_CHARS} characters) */
    static byte[] visits(List<Itinerary.Visit> visits) {
        try {
            ByteArrayOutputStream bytes = new ByteArrayOutputStream();
            DataOutputStream out = new DataOutputStream(bytes);
            out.writeInt(visits.size());
            for (Itinerary.Visit v : visits) {
                out.writeInt(v.round());
                out.writeUTF(v.host());
                out.writeByte(outcomeCode(v.outcome()));
                String detail = v.detail() == null ? "" : v.detail();
                out.writeUTF(detail.length() > MAX_DETAIL_CHARS ? detail.substring(0, MAX_DETAIL_CHARS) + "\n\t..." : detail);
            }
            return bytes.toByteArray();
        } catch (IOException e) {
            throw new UncheckedIOException(e);
        }
    }

    /**
     * @param payload a VISITS event's payload
     * @return the visits it holds
     * @throws IllegalArgumentException if it is cut short, has bytes left over or holds an unknown outcome code
     */
    static List<Itinerary.Visit> readVisits(byte[] payload) {
        DataInputStream in = new DataInputStream(new ByteArrayInputStream(payload));
        try {
            int n = in.readInt();
            if (n < 0 || n > (payload.length - 4) / MIN_VISIT_BYTES) {
                throw new IllegalArgumentException("a VISITS payload of " + payload.length + " bytes claiming " + n + " visits");
            }
            List<Itinerary.Visit> out = new ArrayList<>(n);
            for (int i = 0; i < n; i++) {
                int round = in.readInt();
                String host = in.readUTF();
                Itinerary.Outcome outcome = outcome(in.readUnsignedByte());
                out.add(new Itinerary.Visit(round, host, outcome, in.readUTF()));
            }
            if (in.available() > 0) {
                throw new IllegalArgumentException("a VISITS payload with " + in.available() + " bytes after its " + n + " visits");
            }
            return out;
        } catch (IOException e) {
            throw new IllegalArgumentException("a VISITS payload cut short (" + payload.length + " bytes)", e);
        }
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
        return ByteBuffer.allocate(ID_BYTES + 1 + content.length).putLong(id.getMostSignificantBits()).putLong(id.getLeastSignificantBits())
                .put((byte) (oneway ? ONE_WAY : TWO_WAY)).put(content).array();
    }

    /**
     * @param body a MESSAGE body
     * @return the message
     * @throws IllegalArgumentException if it is shorter than its header or its one-way flag is unknown
     */
    static Message readMessage(byte[] body) {
        if (body.length < ID_BYTES + 1) {
            throw new IllegalArgumentException("a MESSAGE body of " + body.length + " bytes is shorter than its " + (ID_BYTES + 1) + "-byte header");
        }
        ByteBuffer b = ByteBuffer.wrap(body);
        UUID id = new UUID(b.getLong(), b.getLong());
        int flag = b.get() & 0xFF;
        if (flag != ONE_WAY && flag != TWO_WAY) {
            throw new IllegalArgumentException("unknown one-way flag " + flag + " in a MESSAGE for agent " + id + " (known: 0 two-way, 1 one-way)");
        }
        byte[] content = new byte[b.remaining()];
        b.get(content);
        return new Message(id, flag == ONE_WAY, content);
    }

    // ---- RETRACT, DISPOSE ----

    /** @param id an agent @return a RETRACT or DISPOSE body */
    static byte[] agentRequest(UUID id) {
        return ByteBuffer.allocate(16).putLong(id.getMostSignificantBits()).putLong(id.getLeastSignificantBits()).array();
    }

    /**
     * @param body a RETRACT or DISPOSE body
     * @return the agent it names
     * @throws IllegalArgumentException if it is not an id's 16 bytes
     */
    static UUID readAgentRequest(byte[] body) {
        if (body.length != ID_BYTES) {
            throw new IllegalArgumentException("a RETRACT or DISPOSE body of " + body.length + " bytes; it is an agent id's " + ID_BYTES);
        }
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

    /**
     * @param record the stored form of an owed event
     * @return the event and its home
     * @throws IllegalArgumentException if it is cut short or its event is not one (the message says which)
     */
    static OwedEvent readOwedEvent(byte[] record) {
        ByteBuffer b = ByteBuffer.wrap(record);
        try {
            byte[] home = new byte[Short.toUnsignedInt(b.getShort())];
            b.get(home);
            byte[] e = new byte[b.remaining()];
            b.get(e);
            return new OwedEvent(new String(home, StandardCharsets.UTF_8), AgentEvent.decode(e));
        } catch (BufferUnderflowException e) {
            throw new IllegalArgumentException("owed-event record cut short (" + record.length + " bytes)", e);
        }
    }
}
