package io.robomw.agents.host.ops;

import io.robomw.agents.host.AgentInfo;
import io.robomw.agents.host.ClusterKey;
import io.robomw.agents.host.HostAddress;
import io.robomw.agents.host.HostDescription;
import io.robomw.agents.host.OwedDelivery;
import io.robomw.agents.host.OwedSelector;
import io.robomw.agents.host.protocol.Bodies;
import io.robomw.agents.host.protocol.Op;
import io.robomw.agents.host.protocol.Reply;
import io.robomw.agents.host.rmi.HostSockets;
import io.robomw.agents.host.rmi.PeerLink;
import java.io.IOException;
import java.security.SecureRandom;
import java.util.List;
import java.util.Map;
import java.util.UUID;
import java.util.concurrent.ConcurrentHashMap;

/**
 * An operator's view of running agent hosts (what {@code mw agents}, {@code mw retract} and
 * {@code mw dispose} use): who a host is, the agents at it, what it owes agents' homes, dropping
 * what it owes, and retracting or disposing of an agent wherever it is now. It authenticates like
 * any peer (the cluster key, or TLS) and is not a host: it takes no agents. One authenticated link
 * per host asked, kept until {@link #close()}. Thread-safe.
 */
public final class HostClient implements AutoCloseable {

    /** How many moves a retract or dispose follows before it gives up on an agent that keeps moving. */
    private static final int MAX_ROUTE_HOPS = 16;

    private final ClusterKey key;
    private final boolean tls;
    private final String selfName;
    private final int timeoutMillis;
    private final SecureRandom random = new SecureRandom();
    private final Map<String, PeerLink> links = new ConcurrentHashMap<>();

    /**
     * @param key           the cluster key ({@link ClusterKey#tlsOnly()} with TLS alone)
     * @param tls           whether hosts use TLS (the JVM's default TLS context must then hold this peer's key)
     * @param timeoutMillis how long one call may take
     */
    public HostClient(ClusterKey key, boolean tls, int timeoutMillis) {
        this.key = key;
        this.tls = tls;
        this.timeoutMillis = timeoutMillis;
        this.selfName = "mw-" + ProcessHandle.current().pid();
    }

    /**
     * Where a request for an agent was taken.
     *
     * @param host the host the agent was at when it took the request
     * @param hops how many moves the request followed to get there
     */
    public record Taken(String host, int hops) {
    }

    /**
     * @param address a host
     * @return what it says of itself
     * @throws IOException if it cannot be reached, refuses this peer, or answers something else
     */
    public HostDescription describe(String address) throws IOException {
        byte[] body = ok(address, Op.DESCRIBE, new byte[0]);
        try {
            return HostDescription.decode(body, address);
        } catch (IllegalArgumentException e) {
            throw new IOException(e.getMessage(), e);
        }
    }

    /**
     * @param address a host
     * @return the agents at it now
     * @throws IOException if it cannot be reached or refuses this peer
     */
    public List<AgentInfo> agents(String address) throws IOException {
        return Bodies.readListReply(ok(address, Op.LIST, new byte[0]), address);
    }

    /**
     * @param address a host
     * @return what it owes agents' homes and has not delivered, the oldest first
     * @throws IOException if it cannot be reached, refuses this peer, or is a host that does not list them
     */
    public List<OwedDelivery> owed(String address) throws IOException {
        return Bodies.readOwedReply(ok(address, Op.OWED, new byte[0]), address);
    }

    /**
     * @param address a host
     * @param which   the deliveries to drop
     * @return the ones it dropped
     * @throws IOException if it cannot be reached or refuses
     */
    public List<OwedDelivery> dropOwed(String address, OwedSelector which) throws IOException {
        return Bodies.readOwedReply(ok(address, Op.DROP_OWED, Bodies.dropOwed(which)), address);
    }

    /**
     * Asks an agent to go home: it finishes the callback it is in and its state goes to its home.
     *
     * @param address a host where the agent is, or was (the request follows it from there)
     * @param id      the agent
     * @return where it took the request
     * @throws IOException if no host on its way knows it, or one cannot be reached
     */
    public Taken retract(String address, UUID id) throws IOException {
        return request(address, Op.RETRACT, id);
    }

    /**
     * Ends an agent's trip where it is, after the callback it is in; its home is told.
     *
     * @param address a host where the agent is, or was
     * @param id      the agent
     * @return where it took the request
     * @throws IOException if no host on its way knows it, or one cannot be reached
     */
    public Taken dispose(String address, UUID id) throws IOException {
        return request(address, Op.DISPOSE, id);
    }

    private Taken request(String address, Op op, UUID id) throws IOException {
        byte[] body = Bodies.agentRequest(id);
        String at = address;
        for (int hops = 0; hops <= MAX_ROUTE_HOPS; hops++) {
            Reply r = link(at).call(op, body);
            switch (r.status()) {
                case OK -> {
                    return new Taken(at, hops);
                }
                case MOVED -> at = r.text();
                case GONE -> throw new IOException("agent " + id + " is not at " + at + (hops > 0 ? " (followed from " + address + ")" : "")
                        + " and that host does not know where it went: it has ended its trip or was never there");
                default -> throw new IOException(at + " answered " + r.status() + " to " + op + ": " + r.text());
            }
        }
        throw new IOException("agent " + id + " moved more than " + MAX_ROUTE_HOPS + " times while the " + op + " followed it; try again");
    }

    private byte[] ok(String address, Op op, byte[] body) throws IOException {
        Reply r = link(address).call(op, body);
        if (r.status() != Reply.Status.OK) {
            throw new IOException(address + " answered " + r.status() + " to " + op + ": " + r.text());
        }
        return r.body();
    }

    private PeerLink link(String address) {
        return links.computeIfAbsent(address, a -> {
            HostAddress parsed = HostAddress.parse(a);
            return new PeerLink(parsed, selfName, key, new HostSockets.Client(parsed.host(), tls, timeoutMillis), random);
        });
    }

    /**
     * Closes the links: their agent wire connections are closed and their sessions forgotten (a
     * host keeps no state for them beyond its session table's limits; RMI closes its own idle
     * connections). Later calls open new links.
     */
    @Override
    public void close() {
        for (var it = links.values().iterator(); it.hasNext(); ) {
            it.next().drop();
            it.remove();
        }
    }
}
