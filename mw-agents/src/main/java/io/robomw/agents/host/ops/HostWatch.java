package io.robomw.agents.host.ops;

import io.robomw.agents.host.ClusterKey;
import io.robomw.agents.host.HostAddress;
import io.robomw.agents.host.HostDescription;
import io.robomw.agents.host.protocol.Op;
import io.robomw.agents.host.protocol.Reply;
import io.robomw.agents.host.rmi.HostSockets;
import io.robomw.agents.host.rmi.PeerException;
import io.robomw.agents.host.rmi.PeerLink;
import java.io.ByteArrayInputStream;
import java.io.DataInputStream;
import java.io.EOFException;
import java.io.IOException;
import java.io.UTFDataFormatException;
import java.security.SecureRandom;
import java.util.ArrayList;
import java.util.List;
import java.util.UUID;

/**
 * Watches one agent host for a console or a recorder: each {@link #poll()} asks the host
 * ({@code WATCH}, over the same authenticated link as every host-to-host call: the cluster key or
 * TLS) for its name, its robot, its agents with their itineraries, and the events since the last
 * poll. The link is kept between polls; a host that restarted is authenticated to again, a host
 * that is down fails the poll with an {@link IOException} and is asked again at the next one.
 * {@link #retract} and {@link #dispose} send those requests to the host an agent is at, and
 * {@link #describe} asks the host who it is, on the same link (so a console that asks often does
 * not open a session each time). One thread at a time polls; {@link #describe} may be called from
 * another. {@link #close()} closes the link.
 *
 * <p>The answer's layout (big-endian, strings as {@code DataOutput.writeUTF}):
 * <pre>
 * version:u8 (= {@value #FORMAT_VERSION})  then sections until the end:  tag:u8 length:u32 body[length]
 *   tag 1 host:    name:utf robot:utf ("" = none)
 *   tag 2 agents:  n:u32, n x { id:u64 u64, class:utf, status:utf (AgentStatus name), hop:u64, home:utf,
 *                  known:bool, [stops:u32 x { host:utf outcome:utf ("" = ahead) detail:utf round:u32 }, current:i32] }
 *   tag 3 events:  next:u64, n:u32, n x { seq:u64 timeMillis:u64 id:u64 u64 class:utf kind:utf host:utf detail:utf }
 *   tag 4 owed:    n:u32, n x { home:utf count:u32 oldestMillis:u64 } (deliveries owed to agents' homes, per home;
 *                  absent from hosts that do not report them)
 * </pre>
 * A watcher skips sections whose tag it does not know, so hosts can say more without breaking older
 * watchers; an unknown version, a section running past the end, or a malformed string is an
 * {@link IOException} naming the host.
 */
public final class HostWatch implements AutoCloseable {

    /** The answer's format version. */
    public static final int FORMAT_VERSION = 1;
    public static final int SECTION_HOST = 1;
    public static final int SECTION_AGENTS = 2;
    public static final int SECTION_EVENTS = 3;
    /** Deliveries owed to agents' homes, per home. */
    public static final int SECTION_OWED = 4;

    /**
     * What a host said.
     *
     * @param name    its name
     * @param robot   its robot's name, "" for none
     * @param agents  the agents there
     * @param events  what happened since the last poll, oldest first
     * @param missed  events that were dropped from the host's memory before this watcher saw them
     * @param owed    deliveries owed to homes, or {@code null} when the host does not report them
     */
    public record Snapshot(String name, String robot, List<Agent> agents, List<Event> events, long missed, List<Owed> owed) {
    }

    /**
     * An agent at the host.
     *
     * @param itinerary its stops (visited, then ahead), or {@code null} if the host could not say
     * @param current   the index in {@code itinerary} of the stop it is at, -1 if none
     */
    public record Agent(UUID id, String className, String status, long hop, String home, List<Stop> itinerary, int current) {
    }

    /** A stop: where, the outcome of the visit ("" for one ahead: DONE, FAILED, UNREACHABLE, INTERRUPTED), why, the round. */
    public record Stop(String host, String outcome, String detail, int round) {
    }

    /** Something that happened at the host: {@code kind} is arrived, stop-done, stop-failed, report, departed, result, failed, disposed or retracted. */
    public record Event(long seq, long timeMillis, UUID agent, String className, String kind, String host, String detail) {
    }

    /** Deliveries owed to a home. */
    public record Owed(String home, int count, long oldestMillis) {
    }

    private final HostAddress address;
    private final PeerLink link;
    private final ClusterKey key;
    private final boolean useTls;
    private long nextSeq;

    private HostWatch(HostAddress address, ClusterKey key, boolean useTls, String selfName) {
        this.address = address;
        this.key = key;
        this.useTls = useTls;
        this.link = new PeerLink(address, selfName, key, new HostSockets.Client(address.host(), useTls, 10_000), new SecureRandom());
    }

    /**
     * @param address  the host, {@code rmi://host:port/name}
     * @param key      the cluster key ({@link ClusterKey#tlsOnly()} with TLS)
     * @param useTls   whether the host uses TLS (the JVM's default TLS context must hold this peer's key)
     * @param selfName how this watcher introduces itself (in the host's log)
     * @return a watcher; nothing is sent until the first poll
     */
    public static HostWatch of(String address, ClusterKey key, boolean useTls, String selfName) {
        return new HostWatch(HostAddress.parse(address), key, useTls, selfName);
    }

    /** @return the host's address */
    public String address() {
        return address.toString();
    }

    /**
     * @return what the host says now, with the events since the last poll
     * @throws IOException if the host cannot be reached, refuses this watcher, or answers nonsense
     */
    public Snapshot poll() throws IOException {
        Reply r;
        try {
            r = link.call(Op.WATCH, java.nio.ByteBuffer.allocate(8).putLong(nextSeq).array());
        } catch (PeerException e) {
            throw new IOException(e.getMessage(), e);
        }
        if (r.status() != Reply.Status.OK) {
            throw new IOException(address + " answered " + r.status() + ": " + r.text());
        }
        Snapshot s = decode(address.toString(), r.body(), nextSeq);
        long last = s.events().isEmpty() ? nextSeq : s.events().get(s.events().size() - 1).seq();
        nextSeq = Math.max(nextSeq, last);
        return s;
    }

    /**
     * Asks the host who it is (its name, robot, messaging addresses and the hosts it knows), over
     * this watcher's link.
     *
     * @return what it says of itself
     * @throws IOException if the host cannot be reached, refuses this watcher, or answers nonsense
     */
    public HostDescription describe() throws IOException {
        Reply r;
        try {
            r = link.call(Op.DESCRIBE, new byte[0]);
        } catch (PeerException e) {
            throw new IOException(e.getMessage(), e);
        }
        if (r.status() != Reply.Status.OK) {
            throw new IOException(address + " answered " + r.status() + " to DESCRIBE: " + r.text());
        }
        try {
            return HostDescription.decode(r.body(), address.toString());
        } catch (IllegalArgumentException e) {
            throw new IOException(e.getMessage(), e);
        }
    }

    /** Closes the link to the host (its agent wire connections) and forgets its session. */
    @Override
    public void close() {
        link.drop();
    }

    /**
     * Reads a WATCH answer.
     *
     * @param host  who sent it, for messages
     * @param body  the answer
     * @param since the last event number the watcher had seen
     * @return what it says
     * @throws IOException if it is not a well-formed answer
     */
    public static Snapshot decode(String host, byte[] body, long since) throws IOException {
        try {
            DataInputStream in = new DataInputStream(new ByteArrayInputStream(body));
            int version = in.readUnsignedByte();
            if (version != FORMAT_VERSION) {
                throw new IOException(host + " answered WATCH in format version " + version + "; this watcher reads version " + FORMAT_VERSION);
            }
            String name = null;
            String robot = "";
            List<Agent> agents = List.of();
            List<Event> events = List.of();
            long missed = 0;
            List<Owed> owed = null;
            while (in.available() > 0) {
                int tag = in.readUnsignedByte();
                int length = in.readInt();
                if (length < 0 || length > in.available()) {
                    throw new IOException(host + " answered WATCH with a section (tag " + tag + ") of " + length + " bytes where " + in.available() + " are left");
                }
                byte[] section = in.readNBytes(length);
                DataInputStream s = new DataInputStream(new ByteArrayInputStream(section));
                switch (tag) {
                    case SECTION_HOST -> {
                        name = s.readUTF();
                        robot = s.readUTF();
                    }
                    case SECTION_AGENTS -> agents = readAgents(host, s);
                    case SECTION_EVENTS -> {
                        long next = s.readLong();
                        int n = count(host, s, "events");
                        List<Event> list = new ArrayList<>(n);
                        for (int i = 0; i < n; i++) {
                            list.add(new Event(s.readLong(), s.readLong(), new UUID(s.readLong(), s.readLong()), s.readUTF(), s.readUTF(), s.readUTF(),
                                    s.readUTF()));
                        }
                        events = list;
                        long first = list.isEmpty() ? next : list.get(0).seq();
                        missed = Math.max(0, first - since - 1);
                    }
                    case SECTION_OWED -> {
                        int n = count(host, s, "homes owed");
                        List<Owed> list = new ArrayList<>(n);
                        for (int i = 0; i < n; i++) {
                            String home = s.readUTF();
                            int c = s.readInt();
                            if (c < 0) {
                                throw new IOException(host + " answered WATCH with " + c + " deliveries owed to " + home);
                            }
                            list.add(new Owed(home, c, s.readLong()));
                        }
                        owed = list;
                    }
                    default -> {
                        // a section a newer host sends: skipped
                    }
                }
            }
            if (name == null) {
                throw new IOException(host + " answered WATCH without its host section");
            }
            return new Snapshot(name, robot, agents, events, missed, owed);
        } catch (EOFException | UTFDataFormatException e) {
            throw new IOException(host + " answered WATCH with a cut or malformed section: " + e, e);
        }
    }

    private static List<Agent> readAgents(String host, DataInputStream s) throws IOException {
        int n = count(host, s, "agents");
        List<Agent> list = new ArrayList<>(n);
        for (int i = 0; i < n; i++) {
            UUID id = new UUID(s.readLong(), s.readLong());
            String cls = s.readUTF();
            String status = s.readUTF();
            long hop = s.readLong();
            String home = s.readUTF();
            List<Stop> stops = null;
            int current = -1;
            if (s.readBoolean()) {
                int m = count(host, s, "stops");
                stops = new ArrayList<>(m);
                for (int j = 0; j < m; j++) {
                    stops.add(new Stop(s.readUTF(), s.readUTF(), s.readUTF(), s.readInt()));
                }
                current = s.readInt();
            }
            list.add(new Agent(id, cls, status, hop, home, stops, current));
        }
        return list;
    }

    private static int count(String host, DataInputStream s, String what) throws IOException {
        int n = s.readInt();
        if (n < 0 || n > s.available()) {
            throw new IOException(host + " answered WATCH with " + n + " " + what + " in " + s.available() + " bytes");
        }
        return n;
    }

    /**
     * Asks the host an agent is at to send it home (to the home it was launched from).
     *
     * @param host  the host the agent is at
     * @param agent the agent
     * @return where the request went (the host, or where the agent had moved on to)
     * @throws IOException if no host took the request
     */
    public String retract(String host, UUID agent) throws IOException {
        return request(Op.RETRACT, host, agent);
    }

    /**
     * Asks the host an agent is at to end its trip there.
     *
     * @param host  the host the agent is at
     * @param agent the agent
     * @return where the request went
     * @throws IOException if no host took the request
     */
    public String dispose(String host, UUID agent) throws IOException {
        return request(Op.DISPOSE, host, agent);
    }

    private String request(Op op, String host, UUID agent) throws IOException {
        byte[] body = java.nio.ByteBuffer.allocate(16).putLong(agent.getMostSignificantBits()).putLong(agent.getLeastSignificantBits()).array();
        String at = host;
        for (int i = 0; i < 16; i++) {
            PeerLink l = at.equals(address.toString()) ? link
                    : new PeerLink(HostAddress.parse(at), "watch-" + address.name(), key, new HostSockets.Client(HostAddress.parse(at).host(), useTls, 10_000),
                    new SecureRandom());
            Reply r;
            try {
                r = l.call(op, body);
            } catch (PeerException e) {
                throw new IOException(e.getMessage(), e);
            } finally {
                if (l != link) {
                    l.drop(); // a link to a host the agent moved to, made for this request alone
                }
            }
            switch (r.status()) {
                case OK -> {
                    return at;
                }
                case MOVED -> at = r.text();
                case GONE -> throw new IOException("agent " + agent + " is not at " + at + " any more (its trip has ended, or it went home)");
                default -> throw new IOException(at + " answered " + r.status() + ": " + r.text());
            }
        }
        throw new IOException("agent " + agent + " moved more than 16 times while the " + op + " chased it");
    }
}
