package io.robomw.agents.host.rmi;

import io.robomw.agents.host.ClusterKey;
import io.robomw.agents.host.protocol.Op;
import io.robomw.agents.host.protocol.Reply;
import io.robomw.agents.host.security.CallAuthenticator;
import io.robomw.agents.host.wire.WireServer;
import io.robomw.api.spi.FailurePolicy;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import io.robomw.agents.net.ThrottledWarnings;

import java.io.ByteArrayInputStream;
import java.io.DataInputStream;
import java.io.IOException;
import java.net.InetAddress;
import java.nio.ByteBuffer;
import java.nio.charset.StandardCharsets;
import java.security.MessageDigest;
import java.security.SecureRandom;
import java.time.Duration;
import java.util.HexFormat;
import java.util.LinkedHashMap;
import java.util.Map;
import java.util.concurrent.ConcurrentHashMap;
import java.util.concurrent.atomic.LongAdder;

/**
 * The server side of {@link AgentHostRemote}: hands out challenges, checks peers' proofs, keeps
 * their sessions, checks every call's MAC and sequence number, and passes verified calls to the
 * host. Anything that fails a check is refused with a log line naming the peer and a count in
 * {@link #refused()}; the endpoint goes on serving everyone else.
 */
public final class HostEndpoint implements AgentHostRemote {

    private static final Logger LOG = LoggerFactory.getLogger(HostEndpoint.class);
    private static final long NONCE_LIFETIME_NANOS = 30_000_000_000L;
    private static final int MAX_PENDING_NONCES = 4096;
    private static final int MAX_SESSIONS = 4096;

    /** What the host does with a verified call. */
    public interface Handler {
        /**
         * @param peer    the authenticated peer's name
         * @param op      the operation
         * @param message holds the call's body (not to be kept: it is the request as received)
         * @param offset  where the body starts
         * @param length  its length
         * @return the reply
         */
        Reply handle(String peer, Op op, byte[] message, int offset, int length);
    }

    /** An authenticated peer: its name, its session, and the address it authenticated from. */
    public record Peer(String name, Session session, String clientHost) {
    }

    /** The largest byte array a call may carry on a connection that has not proved the cluster key ({@link HostConnections}). */
    public static final int UNPROVEN_MAX_BYTES = HostConnections.UNPROVEN_MAX_BYTES;

    private final String hostName;
    private final ClusterKey key;
    private final Handler handler;
    private final SecureRandom random = new SecureRandom();
    private final Map<String, Long> nonces = new LinkedHashMap<>();
    private final Map<Long, Peer> sessions = new ConcurrentHashMap<>();
    private final LongAdder refused = new LongAdder();
    private final ThrottledWarnings refusedPeers = new ThrottledWarnings(LOG, Duration.ofSeconds(1));
    private final ThrottledWarnings droppedCalls = new ThrottledWarnings(LOG, Duration.ofSeconds(1));

    private final FailurePolicy failures;
    /** The highest protocol version this endpoint takes: {@link Session#COMPACT_VERSION}, or a lower one to act as a host of a build before it. */
    private final int highestVersion;
    /** The state of the RMI connections calls come on, or {@code null} for an endpoint called directly (tests). */
    private final HostConnections connections;
    /** The port of the host's agent wire ({@link WireServer}), 0 while it has none. */
    private volatile int wirePort;
    /** The host's RMI address, which version-4 peers must have meant to reach; {@code null} until it is exported. */
    private volatile InetAddress bindAddress;
    private volatile int port;

    public HostEndpoint(String hostName, ClusterKey key, Handler handler) {
        this(hostName, key, handler, Session.COMPACT_VERSION);
    }

    /**
     * @param highestVersion {@link Session#COMPACT_VERSION}, or a lower version for an endpoint that
     *                       refuses the versions above it as older builds do (tests of mixed versions)
     */
    public HostEndpoint(String hostName, ClusterKey key, Handler handler, int highestVersion) {
        this(hostName, key, handler, highestVersion, FailurePolicy.logging(), null);
    }

    /**
     * @param highestVersion as above
     * @param failures       where a failure of the handler, other than a refusal, goes: the call is
     *                       refused and the thread serving it goes on
     * @param connections    the state of the RMI connections calls come on: which proved the key, where they come from
     *                       ({@code null} for an endpoint called directly, in tests)
     */
    public HostEndpoint(String hostName, ClusterKey key, Handler handler, int highestVersion, FailurePolicy failures, HostConnections connections) {
        this.hostName = hostName;
        this.key = key;
        this.handler = handler;
        this.highestVersion = highestVersion;
        this.failures = failures;
        this.connections = connections;
    }

    /**
     * @param bind the address the host's RMI endpoint listens on
     * @param port its port: a version-4 peer's target must be this address (any of this machine's for the wildcard address) and port
     */
    public void address(InetAddress bind, int port) {
        this.bindAddress = bind;
        this.port = port;
    }

    /** @return the peers' sessions kept now (for tests: one per link that authenticated) */
    public int sessions() {
        return sessions.size();
    }

    /** @param port where the host's agent wire listens, offered to version-3 peers in their authentication answer */
    public void wirePort(int port) {
        this.wirePort = port;
    }

    /** @return the host's name */
    public String hostName() {
        return hostName;
    }

    /** Counts one refused frame or call (the agent wire's refusals count with the endpoint's). */
    public void countRefused() {
        refused.increment();
    }

    /** @return the peer of a session, or {@code null} if this host does not know the session */
    public Peer peer(long sessionId) {
        return sessions.get(sessionId);
    }

    /** @return how many authentications and calls were refused */
    public long refused() {
        return refused.sum();
    }

    @Override
    public byte[] challenge() {
        byte[] nonce = new byte[32];
        random.nextBytes(nonce);
        synchronized (nonces) {
            long now = System.nanoTime();
            nonces.values().removeIf(expiry -> expiry - now < 0);
            if (nonces.size() >= MAX_PENDING_NONCES) {
                nonces.remove(nonces.keySet().iterator().next());
            }
            nonces.put(HexFormat.of().formatHex(nonce), now + NONCE_LIFETIME_NANOS);
        }
        return nonce;
    }

    @Override
    public byte[] authenticate(byte[] request) {
        try {
            return authenticated(request);
        } finally {
            if (connections != null) {
                connections.callDone();
            }
        }
    }

    private byte[] authenticated(byte[] request) {
        String peer = "?";
        try {
            DataInputStream in = new DataInputStream(new ByteArrayInputStream(request));
            int version = in.readUnsignedByte();
            if (!takes(version)) {
                return refuse(peer, "it speaks agent protocol version " + version + (version == 0 ? " or 1 (a build before 2026-11-24)" : "")
                        + "; this host speaks " + spoken() + ": run the same RoboMW on both");
            }
            int authenticator = in.readUnsignedByte();
            peer = in.readUTF();
            if (!CallAuthenticator.known(authenticator)) {
                return refuse(peer, CallAuthenticator.unknown(authenticator));
            }
            Target target = version >= Session.BOUND_VERSION ? Target.read(in) : null;
            byte[] terms = Session.terms(version, authenticator);
            byte[] hostNonce = in.readNBytes(32);
            byte[] clientNonce = in.readNBytes(32);
            byte[] proof = in.readNBytes(32);
            if (proof.length != 32 || in.available() != 0) {
                return refuse(peer, "malformed authentication request (" + request.length + " bytes)");
            }
            Long expiry;
            synchronized (nonces) {
                expiry = nonces.remove(HexFormat.of().formatHex(hostNonce));
            }
            if (expiry == null || expiry - System.nanoTime() < 0) {
                return refuse(peer, "its challenge is unknown, used or expired");
            }
            byte[] hostNameBytes = hostName.getBytes(StandardCharsets.UTF_8);
            byte[] peerName = peer.getBytes(StandardCharsets.UTF_8);
            byte[] expected = target == null ? Session.clientProof(key, terms, hostNameBytes, peerName, hostNonce, clientNonce)
                    : Session.clientProof(key, terms, hostNameBytes, peerName, hostNonce, clientNonce, target);
            if (!MessageDigest.isEqual(proof, expected)) {
                return refuse(peer, "wrong cluster key");
            }
            if (target != null) {
                InetAddress bind = bindAddress;
                if (bind == null || !target.reaches(bind, port)) {
                    // The proof is genuine but was made for another address: whoever passed it on stands between the peer and this host.
                    return refuse(peer, "it meant to reach " + hostName + " at " + target + ", but this host is at "
                            + (bind == null ? "no address yet" : new Target(bind, port).toString())
                            + ": something between them (a relay, a rewritten registry entry) passed its authentication on; not serving it");
                }
            }
            long id = random.nextLong();
            if (sessions.size() >= MAX_SESSIONS) {
                sessions.remove(sessions.keySet().iterator().next());
            }
            sessions.put(id, new Peer(peer, new Session(id, Session.sessionKey(key, terms, hostNonce, clientNonce), authenticator), clientHost()));
            if (connections != null) {
                connections.proven();
            }
            LOG.debug("host {}: peer {} ({}) authenticated, protocol version {}", hostName, peer, clientHost(), version);
            if (version >= Session.WIRE_VERSION) {
                // The wire takes frames tagged with AES-GCM only: a session of another authenticator gets port 0 (none).
                int port = authenticator == CallAuthenticator.AES_256_GCM ? wirePort : 0;
                byte[] offer = {(byte) (port >>> 8), (byte) port};
                byte[] hostProof = target == null ? Session.hostProof(key, terms, hostNameBytes, peerName, hostNonce, clientNonce, offer)
                        : Session.hostProof(key, terms, hostNameBytes, peerName, hostNonce, clientNonce, offer, target);
                return ByteBuffer.allocate(1 + 8 + 32 + 2).put(Session.AUTH_ACCEPTED).putLong(id).put(hostProof).put(offer).array();
            }
            return ByteBuffer.allocate(1 + 8 + 32).put(Session.AUTH_ACCEPTED).putLong(id)
                    .put(Session.hostProof(key, terms, hostNameBytes, peerName, hostNonce, clientNonce)).array();
        } catch (IOException | RuntimeException e) {
            return refuse(peer, "malformed authentication request of " + (request == null ? 0 : request.length) + " bytes ("
                    + (e instanceof java.io.EOFException ? "it ends early" : e.getMessage() == null ? e.getClass().getSimpleName() : e.getMessage()) + ")");
        }
    }

    /** @return whether this endpoint takes a peer of that protocol version */
    private boolean takes(int version) {
        return version >= Session.PROTOCOL_VERSION && version <= highestVersion;
    }

    /** @return the versions this endpoint takes, for a refusal */
    private String spoken() {
        if (highestVersion == Session.PROTOCOL_VERSION) {
            return "version " + Session.PROTOCOL_VERSION;
        }
        StringBuilder b = new StringBuilder("versions ");
        for (int v = Session.PROTOCOL_VERSION; v <= highestVersion; v++) {
            b.append(v).append(v == highestVersion ? "" : v == highestVersion - 1 ? " and " : ", ");
        }
        return b.toString();
    }

    private byte[] refuse(String peer, String why) {
        refused.increment();
        refusedPeers.warn("host {}: refused peer '{}' from {}: {}", hostName, peer, clientHost(), why);
        byte[] text = ("refused: " + why).getBytes(StandardCharsets.UTF_8);
        byte[] out = new byte[1 + text.length];
        out[0] = Session.AUTH_REFUSED;
        System.arraycopy(text, 0, out, 1, text.length);
        return out;
    }

    @Override
    public byte[] call(byte[] request) {
        try {
            return served(request);
        } finally {
            if (connections != null) {
                connections.callDone();
            }
        }
    }

    private byte[] served(byte[] request) {
        if (request == null || request.length < Session.HEADER + Session.MAC) {
            refused.increment();
            droppedCalls.warn("host {}: dropped a call of {} bytes from {}: too short", hostName, request == null ? 0 : request.length, clientHost());
            return new byte[0];
        }
        ByteBuffer b = ByteBuffer.wrap(request);
        long id = b.getLong();
        long seq = b.getLong();
        int opCode = b.get() & 0xFF;
        Peer peer = sessions.get(id);
        if (peer == null) {
            // Not secret: a host that restarted forgot its sessions; the peer authenticates again.
            return Session.unknownSessionReply();
        }
        if (peer.session().servedBefore(seq)) {
            refused.increment();
            LOG.warn("host {}: dropped a replayed call (sequence {}) from peer '{}' at {}", hostName, seq, peer.name(), clientHost());
            return new byte[0];
        }
        if (!peer.session().verifyRequest(request)) {
            refused.increment();
            droppedCalls.warn("host {}: dropped a call from {} claiming peer '{}' session: wrong MAC", hostName, clientHost(), peer.name());
            return new byte[0];
        }
        if (!peer.session().firstTime(seq)) {
            refused.increment();
            droppedCalls.warn("host {}: dropped a replayed call (sequence {}) from peer '{}' at {}", hostName, seq, peer.name(), clientHost());
            return new byte[0];
        }
        if (connections != null) {
            connections.proven();
        }
        return peer.session().reply(seq, serve(peer, opCode, request, Session.HEADER, request.length - Session.MAC - Session.HEADER, clientHost()));
    }

    /**
     * Serves a verified call (from RMI or the agent wire): an unknown operation code is refused naming it.
     *
     * @param peer    the authenticated peer
     * @param opCode  the call's operation byte
     * @param message holds the body
     * @param offset  where the body starts
     * @param length  its length
     * @param from    where the call came from, for the log
     * @return the reply
     */
    public Reply serve(Peer peer, int opCode, byte[] message, int offset, int length, String from) {
        Op op;
        try {
            op = Op.fromCode(opCode);
        } catch (IllegalArgumentException e) {
            refused.increment();
            droppedCalls.warn("host {}: refused a call from peer '{}' at {}: {}", hostName, peer.name(), from, e.getMessage());
            return Reply.of(Reply.Status.REFUSED, "host " + hostName + " refused the call: " + e.getMessage());
        }
        try {
            return handler.handle(peer.name(), op, message, offset, length);
        } catch (Throwable e) {
            failures.surviveOrRethrow(Thread.currentThread().getName(), e);
            refused.increment();
            LOG.warn("host {}: {} call from peer '{}' failed: {}", hostName, op, peer.name(), e.toString());
            return Reply.of(Reply.Status.REFUSED, "the host could not handle the call: " + e.getMessage());
        }
    }

    /** @return where the call in hand comes from (the host's sockets hide it from RMI, so RMI's own answer would be 0.0.0.0) */
    private String clientHost() {
        return connections == null ? "this process" : connections.currentRemote();
    }
}
