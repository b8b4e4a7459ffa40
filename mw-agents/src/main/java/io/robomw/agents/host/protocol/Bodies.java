package io.robomw.agents.host.protocol;

import io.robomw.agents.host.AgentInfo;
import io.robomw.agents.host.OwedDelivery;
import io.robomw.agents.host.OwedSelector;
import io.robomw.agents.net.WireCode;
import io.robomw.agents.net.WireCodes;

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
 * ARRIVALS body    [count 2, 1 to {@value #MAX_ARRIVALS}] then per arrival: [id 16][where: length 2, modified UTF-8]
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
public final class Bodies {

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

    /**
     * An agent's status as a LIST reply gives it: its {@link AgentStatus}, or an active agent whose
     * retract or dispose is pending. Each travels as its code, written once here.
     */
    enum Listed implements WireCode {
        CREATED(0, AgentStatus.CREATED, AgentInfo.Pending.NONE),
        ACTIVE(1, AgentStatus.ACTIVE, AgentInfo.Pending.NONE),
        IN_TRANSIT(2, AgentStatus.IN_TRANSIT, AgentInfo.Pending.NONE),
        COMPLETED(3, AgentStatus.COMPLETED, AgentInfo.Pending.NONE),
        DISPOSED(4, AgentStatus.DISPOSED, AgentInfo.Pending.NONE),
        RETRACTED(5, AgentStatus.RETRACTED, AgentInfo.Pending.NONE),
        FAILED(6, AgentStatus.FAILED, AgentInfo.Pending.NONE),
        /** Active, its retract pending. */
        RETRACT_PENDING(7, AgentStatus.ACTIVE, AgentInfo.Pending.RETRACT),
        /** Active, its dispose pending. */
        DISPOSE_PENDING(8, AgentStatus.ACTIVE, AgentInfo.Pending.DISPOSE);

        private static final WireCodes<Listed> CODES = WireCodes.of(Listed.class, "agent status");

        private final int code;
        final AgentStatus status;
        final AgentInfo.Pending pending;

        Listed(int code, AgentStatus status, AgentInfo.Pending pending) {
            this.code = code;
            this.status = status;
            this.pending = pending;
        }

        @Override
        public int code() {
            return code;
        }

        /** @return how a LIST reply gives an agent's status and what is pending */
        static Listed of(AgentStatus status, AgentInfo.Pending pending) {
            for (Listed l : values()) {
                if (l.status == status && l.pending == pending) {
                    return l;
                }
            }
            return of(status, AgentInfo.Pending.NONE);
        }

        /**
         * @param code a status code as read (unsigned)
         * @return its listed status
         * @throws IllegalArgumentException naming the code if none has it
         */
        static Listed fromCode(int code) {
            return CODES.get(code);
        }
    }

    // ---- LIST ----

    /** @param agents the agents at a host @return the LIST reply's body */
    public static byte[] listReply(List<AgentInfo> agents) {
        try {
            ByteArrayOutputStream bytes = new ByteArrayOutputStream();
            DataOutputStream out = new DataOutputStream(bytes);
            out.writeInt(agents.size());
            for (AgentInfo a : agents) {
                out.writeLong(a.id().getMostSignificantBits());
                out.writeLong(a.id().getLeastSignificantBits());
                out.writeUTF(a.className());
                out.writeByte(Listed.of(a.status(), a.pending()).code());
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
    public static List<AgentInfo> readListReply(byte[] body, String from) throws IOException {
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
                Listed listed;
                try {
                    listed = Listed.fromCode(in.readUnsignedByte());
                } catch (IllegalArgumentException e) {
                    throw new IOException("host " + from + " listed agent " + id + " with an " + e.getMessage(), e);
                }
                long hop = in.readLong();
                String home = in.readUTF();
                out.add(new AgentInfo(id, cls, listed.status, hop, home, listed.pending));
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
    public static byte[] owedReply(List<OwedDelivery> owed) {
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
    public static List<OwedDelivery> readOwedReply(byte[] body, String from) throws IOException {
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
    public static byte[] dropOwed(OwedSelector which) {
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
    public static OwedSelector readDropOwed(byte[] body) {
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
    public static byte[] visits(List<Itinerary.Visit> visits) {
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
    public static List<Itinerary.Visit> readVisits(byte[] payload) {
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
    public record Message(UUID id, boolean oneway, byte[] content) {
    }

    /** @return a MESSAGE body */
    public static byte[] message(UUID id, boolean oneway, byte[] content) {
        return ByteBuffer.allocate(ID_BYTES + 1 + content.length).putLong(id.getMostSignificantBits()).putLong(id.getLeastSignificantBits())
                .put((byte) (oneway ? ONE_WAY : TWO_WAY)).put(content).array();
    }

    /**
     * @param body a MESSAGE body
     * @return the message
     * @throws IllegalArgumentException if it is shorter than its header or its one-way flag is unknown
     */
    public static Message readMessage(byte[] body) {
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
    public static byte[] agentRequest(UUID id) {
        return ByteBuffer.allocate(16).putLong(id.getMostSignificantBits()).putLong(id.getLeastSignificantBits()).array();
    }

    /**
     * @param body a RETRACT or DISPOSE body
     * @return the agent it names
     * @throws IllegalArgumentException if it is not an id's 16 bytes
     */
    public static UUID readAgentRequest(byte[] body) {
        if (body.length != ID_BYTES) {
            throw new IllegalArgumentException("a RETRACT or DISPOSE body of " + body.length + " bytes; it is an agent id's " + ID_BYTES);
        }
        ByteBuffer b = ByteBuffer.wrap(body);
        return new UUID(b.getLong(), b.getLong());
    }

    // ---- ARRIVALS ----

    /** The most arrivals in one ARRIVALS body. */
    public static final int MAX_ARRIVALS = 1_024;

    /**
     * News that an agent arrived at a host.
     *
     * @param id    the agent
     * @param where the host it arrived at (its address)
     */
    public record Arrival(UUID id, String where) {
    }

    /**
     * @param arrivals 1 to {@value #MAX_ARRIVALS} arrivals
     * @return an ARRIVALS body
     * @throws IllegalArgumentException if there are none or more than {@value #MAX_ARRIVALS}
     */
    public static byte[] arrivals(List<Arrival> arrivals) {
        if (arrivals.isEmpty() || arrivals.size() > MAX_ARRIVALS) {
            throw new IllegalArgumentException("an ARRIVALS body holds 1 to " + MAX_ARRIVALS + " arrivals, not " + arrivals.size());
        }
        try {
            ByteArrayOutputStream bytes = new ByteArrayOutputStream(2 + arrivals.size() * (ID_BYTES + 2 + 32));
            DataOutputStream out = new DataOutputStream(bytes);
            out.writeShort(arrivals.size());
            for (Arrival a : arrivals) {
                out.writeLong(a.id().getMostSignificantBits());
                out.writeLong(a.id().getLeastSignificantBits());
                out.writeUTF(a.where());
            }
            return bytes.toByteArray();
        } catch (IOException e) {
            throw new UncheckedIOException(e);
        }
    }

    /**
     * @param body an ARRIVALS body
     * @return the arrivals it holds, in order
     * @throws IllegalArgumentException if it is cut short, has bytes left over, or claims none or more than {@value #MAX_ARRIVALS}
     */
    public static List<Arrival> readArrivals(byte[] body) {
        DataInputStream in = new DataInputStream(new ByteArrayInputStream(body));
        try {
            int n = in.readUnsignedShort();
            if (n == 0 || n > MAX_ARRIVALS) {
                throw new IllegalArgumentException("an ARRIVALS body claiming " + n + " arrivals; it holds 1 to " + MAX_ARRIVALS);
            }
            List<Arrival> out = new ArrayList<>(n);
            for (int i = 0; i < n; i++) {
                UUID id = new UUID(in.readLong(), in.readLong());
                out.add(new Arrival(id, in.readUTF()));
            }
            if (in.available() > 0) {
                throw new IllegalArgumentException("an ARRIVALS body with " + in.available() + " bytes after its " + n + " arrivals");
            }
            return out;
        } catch (IOException e) {
            throw new IllegalArgumentException("an ARRIVALS body cut short (" + body.length + " bytes)", e);
        }
    }

    // ---- PUT_ARCHIVE ----

    /**
     * An archive as a peer sends it.
     *
     * @param claimed the digest the peer claims for it
     * @param jar     its bytes
     */
    public record Archive(CodeArchive.Digest claimed, byte[] jar) {
    }

    /** @return a PUT_ARCHIVE body */
    public static byte[] archive(CodeArchive archive) {
        byte[] digest = archive.digest().bytes();
        return ByteBuffer.allocate(digest.length + archive.bytes().length).put(digest).put(archive.bytes()).array();
    }

    /**
     * @param body a PUT_ARCHIVE body
     * @return the archive it holds, not yet checked against its digest
     * @throws IllegalArgumentException if it is too short to hold a digest and a jar
     */
    public static Archive readArchive(byte[] body) {
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
    public record OwedEvent(String home, AgentEvent event) {
    }

    /** @return the stored form of an event owed to a home */
    public static byte[] owedEvent(String home, AgentEvent event) {
        byte[] homeBytes = home.getBytes(StandardCharsets.UTF_8);
        byte[] e = event.encode();
        return ByteBuffer.allocate(2 + homeBytes.length + e.length).putShort((short) homeBytes.length).put(homeBytes).put(e).array();
    }

    /**
     * @param record the stored form of an owed event
     * @return the event and its home
     * @throws IllegalArgumentException if it is cut short or its event is not one (the message says which)
     */
    public static OwedEvent readOwedEvent(byte[] record) {
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
