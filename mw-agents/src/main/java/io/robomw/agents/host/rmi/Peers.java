package io.robomw.agents.host.rmi;

import io.robomw.agents.host.ClusterKey;
import io.robomw.agents.host.HostAddress;
import io.robomw.agents.host.HostDescription;
import io.robomw.agents.host.code.StateCodec;
import io.robomw.agents.host.core.HostState;
import io.robomw.agents.host.protocol.Frame;
import io.robomw.agents.host.protocol.Op;
import io.robomw.agents.host.protocol.Reply;
import java.security.SecureRandom;
import java.util.Map;
import java.util.concurrent.ConcurrentHashMap;

/**
 * A host's calls to other hosts: one authenticated {@link PeerLink} per host called, made on first
 * use and kept. A call to this host's own address is served here directly, without RMI. A
 * transfer's frame goes to the link as it is: sealed in place, not copied into a request.
 * Thread-safe.
 */
public final class Peers {

    private final HostState host;
    private final ClusterKey key;
    private final boolean tls;
    private final HostEndpoint.Handler self;
    private final SecureRandom random = new SecureRandom();
    private final Map<String, PeerLink> links = new ConcurrentHashMap<>();
    /** The TLS context of agent wire connections (the host's own), or {@code null}; set before the host calls anyone. */
    private volatile javax.net.ssl.SSLContext wireTls;
    private volatile java.time.Duration wireSpin = java.time.Duration.ZERO;
    private volatile boolean version2Only;
    private volatile boolean wireOff;
    private volatile boolean olderHosts;

    /**
     * @param host the host calling
     * @param key  the cluster key to prove
     * @param tls  whether to call over TLS
     * @param self serves calls this host makes to itself
     */
    public Peers(HostState host, ClusterKey key, boolean tls, HostEndpoint.Handler self) {
        this.host = host;
        this.key = key;
        this.tls = tls;
        this.self = self;
    }

    /**
     * @param target the host's address
     * @param op     the operation
     * @param body   its body (copied into the call's frame)
     * @return the host's verified reply
     * @throws PeerException if the host cannot be reached, refuses this host, or the call fails
     */
    public Reply call(String target, Op op, byte[] body) throws PeerException {
        if (target.equals(host.address)) {
            return self.handle(host.name, op, body, 0, body.length);
        }
        return link(target).call(op, body);
    }

    /**
     * A call whose body is already in its frame (a transfer): sent without copying it into a request.
     *
     * @param target the host's address
     * @param op     the operation
     * @param frame  the body in its frame, sealed in place
     * @return the host's verified reply
     * @throws PeerException if the host cannot be reached, refuses this host, or the call fails
     */
    public Reply call(String target, Op op, Frame frame) throws PeerException {
        if (target.equals(host.address)) {
            return self.handle(host.name, op, frame.bytes, frame.bodyOffset(), frame.bodyLength());
        }
        return link(target).call(op, frame);
    }

    /**
     * @param target a host's address
     * @return the form of agent state it reads ({@link io.robomw.agents.host.visit.HopSender#stateFormOf}); this host reads both
     */
    public StateCodec.Form stateFormOf(String target) {
        if (target.equals(host.address)) {
            return StateCodec.Form.COMPACT;
        }
        return link(target).version() >= Session.COMPACT_VERSION ? StateCodec.Form.COMPACT : StateCodec.Form.STANDARD;
    }

    /**
     * @param target a host's address
     * @return what it says of itself
     * @throws PeerException if it cannot be reached, refuses, or answers something that is not a description
     */
    public HostDescription describe(String target) throws PeerException {
        Reply r = call(target, Op.DESCRIBE, new byte[0]);
        if (r.status() != Reply.Status.OK) {
            throw new PeerException(target + " answered " + r.status() + " to DESCRIBE: " + r.text(), false, null);
        }
        try {
            return HostDescription.decode(r.body(), target);
        } catch (IllegalArgumentException e) {
            throw new PeerException(e.getMessage(), false, e);
        }
    }

    /**
     * How this host's links use the agent wire.
     *
     * @param tls          the TLS context of wire connections (the host's own), or {@code null} for plain ones
     * @param spin         how long a transfer spins for its reply before it blocks
     * @param version2Only propose agent protocol version 2 only, as builds before the wire (tests of mixed versions)
     * @param off          send every call over RMI, even to hosts that offer a wire
     */
    public void wire(javax.net.ssl.SSLContext tls, java.time.Duration spin, boolean version2Only, boolean off) {
        this.wireTls = tls;
        this.wireSpin = spin;
        this.version2Only = version2Only;
        this.wireOff = off;
    }

    /** @param allowed whether links may fall back to agent protocol versions before 4 (unbound channels) with hosts that refuse 4 */
    public void olderHosts(boolean allowed) {
        this.olderHosts = allowed;
    }

    /** Closes the links' idle wire connections. */
    public void close() {
        links.values().forEach(PeerLink::close);
    }

    private PeerLink link(String target) {
        return links.computeIfAbsent(target, t -> {
            HostAddress a = HostAddress.parse(t);
            PeerLink l = new PeerLink(a, host.name, key, new HostSockets.Client(a.host(), tls, host.timeoutMillis), random, wireTls, host.timeoutMillis);
            l.wireSpin(wireSpin, host::fewAgentsLately);
            l.wireTagger(host.wireTaggers);
            if (version2Only) {
                l.proposeVersion2Only();
            }
            if (wireOff) {
                l.wireOff();
            }
            if (olderHosts) {
                l.olderHosts();
            }
            return l;
        });
    }
}
