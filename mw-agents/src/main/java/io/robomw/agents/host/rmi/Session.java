package io.robomw.agents.host.rmi;

import io.robomw.agents.host.ClusterKey;
import io.robomw.agents.host.HostDescription;
import io.robomw.agents.host.ops.HostWatch;
import io.robomw.agents.host.protocol.AgentEvent;
import io.robomw.agents.host.protocol.AgentImage;
import io.robomw.agents.host.protocol.Bodies;
import io.robomw.agents.host.protocol.Frame;
import io.robomw.agents.host.protocol.Op;
import io.robomw.agents.host.protocol.Reply;
import io.robomw.agents.host.security.CallAuthenticator;
import io.robomw.agents.host.wire.WireFrames;
import io.robomw.agents.messaging.security.ReplayGuard;

import java.nio.ByteBuffer;
import java.util.Arrays;

/**
 * The keys and framing of one authenticated session between a peer and a host: the session key
 * both derive from the cluster key and the two nonces, and the request and reply layouts with
 * their tags ({@link CallAuthenticator}). All integers are big-endian.
 *
 * <pre>
 * authentication request [version 1][authenticator 1][peer name: u16 length, UTF-8][host nonce 32][client nonce 32][client proof 32]
 *                        version 4: [4][authenticator 1][peer name: u16 length, UTF-8][target][host nonce 32][client nonce 32][client proof 32]
 * target                 [address length 1: 4 or 16][the address the peer meant to reach][its port 2]   (the host's RMI address)
 * authentication answer  [0][session id 8][host proof 32]  or  [1][reason, UTF-8]
 *                        versions 3 and 4: [0][session id 8][host proof 32][wire port 2]   (port 0: the host takes no transfers on the wire)
 * request  [session id 8][seq 8][op 1][body][mac 16]      mac over everything before it
 * reply    [status 1][body][mac 16]                       mac also covers the request's seq
 * unknown session reply  [status 7]                       alone, without a MAC (the host lost the session)
 *
 * terms        = [version 1][authenticator 1]
 * client proof = HMAC-SHA256(cluster key, "robomw-agent-client", terms, host name, peer name, host nonce, client nonce)
 *                version 4: HMAC-SHA256(cluster key, "robomw-agent-client", terms, host name, peer name, host nonce, client nonce, target)
 * host proof   = HMAC-SHA256(cluster key, "robomw-agent-host", terms, host name, peer name, host nonce, client nonce)
 *                version 3: HMAC-SHA256(cluster key, "robomw-agent-host", terms, host name, peer name, host nonce, client nonce, wire port 2)
 *                version 4: HMAC-SHA256(cluster key, "robomw-agent-host", terms, host name, peer name, host nonce, client nonce, wire port 2, target)
 * session key  = HMAC-SHA256(cluster key, "robomw-agent-session", terms, host nonce, client nonce)
 *                (ClusterKey.mac: every part prefixed with its length, a u32)
 * </pre>
 *
 * <p><b>Protocol version</b>: the first byte of an authentication request. Version 1 (builds
 * before 2026-11-24) had neither that byte nor the authenticator's, and its proofs and session key
 * did not cover them. Version {@value #PROTOCOL_VERSION} makes every call over RMI; version
 * {@value #WIRE_VERSION} also carries transfers on the agent wire ({@link WireFrames}), whose port
 * the host's answer names. Version {@value #BOUND_VERSION} is version 3 with the <b>channel
 * bound</b>: the request names the address the peer meant to reach (its <i>target</i>: the IP
 * address and port of the host's RMI address as the peer resolved it), both proofs cover it, and
 * the host refuses a target that is not its own address. A relay that passes a peer's calls on to
 * a real host (a registry entry rewritten, an address the peer was given) is thus refused by the
 * host, and the peer is told so; it cannot rewrite the target without breaking the proof.
 *
 * <p>Version {@value #COMPACT_VERSION} is version 4 from a host that reads agent states in the
 * compact form: over a session of an earlier version, a peer sends agents in Java serialization's
 * standard form. Peers of this build propose 5; a host of this build takes 2 to 5 (peers of builds
 * before 4 are served as before: their own sessions are not bound). A host of a build before the
 * compact form refuses 5, naming its versions; a peer of this build then authenticates with 4 (5
 * and 4 bind the channel alike, so a forged refusal gains a relay nothing). A host of a build
 * before 4 refuses that too; a peer of this build then gives up with an error saying so, unless it
 * was told to talk to older builds ({@link io.robomw.agents.host.AgentHostBuilder#olderHosts()}): it then
 * authenticates again with 3 (and 2 if that is refused too) and proposes 5 again after it loses the
 * connection. A peer never falls back on its own: the refusal is not authenticated, so a relay
 * could forge one to talk it down to an unbound version. Any other version is refused with a
 * reason naming both (a version-1 request reads as version 0: its name's length comes first), and
 * so are the authenticator codes of {@link CallAuthenticator} a host does not know. The terms are
 * inside both proofs and the session key, so neither side can be talked into other terms than the
 * peer proposed.
 *
 * <p><b>Replays.</b> Each session keeps the window of the sequence numbers it has served
 * ({@link ReplayGuard}, {@value ReplayGuard#WINDOW} wide): a number served before, or below the
 * window, is dropped. The window lives and ends with its session (a host that forgets a session
 * answers its calls {@code UNKNOWN_SESSION} and serves none), so a host never serves, nor tags a
 * reply to, one number twice under one key.
 *
 * <table>
 * <caption>Operation codes ({@link Op})</caption>
 * <tr><th>code</th><th>operation</th><th>body</th></tr>
 * <tr><td>0</td><td>TRANSFER</td><td>an {@link AgentImage}</td></tr>
 * <tr><td>1</td><td>PUT_ARCHIVE</td><td>{@link Bodies#archive}</td></tr>
 * <tr><td>2</td><td>LIST</td><td>empty; the reply's body is {@link Bodies#listReply}</td></tr>
 * <tr><td>3</td><td>EVENT</td><td>an {@link AgentEvent}</td></tr>
 * <tr><td>4</td><td>MESSAGE</td><td>{@link Bodies#message}</td></tr>
 * <tr><td>5</td><td>RETRACT</td><td>{@link Bodies#agentRequest}</td></tr>
 * <tr><td>6</td><td>DISPOSE</td><td>{@link Bodies#agentRequest}</td></tr>
 * <tr><td>7</td><td>DESCRIBE</td><td>empty; the reply is a {@link HostDescription}</td></tr>
 * <tr><td>8</td><td>WATCH</td><td>the last event number the watcher saw (u64); the reply is laid out in {@link HostWatch}</td></tr>
 * <tr><td>9</td><td>OWED</td><td>empty; the reply's body is {@link Bodies#owedReply}</td></tr>
 * <tr><td>10</td><td>DROP_OWED</td><td>{@link Bodies#dropOwed}; the reply's body lists the ones dropped, as {@link Bodies#owedReply}</td></tr>
 * <tr><td>11</td><td>ARRIVALS</td><td>{@link Bodies#arrivals}: news for the home that some of its agents arrived elsewhere; sent on the agent
 * wire where there is one</td></tr>
 * </table>
 *
 * <table>
 * <caption>Reply status codes ({@link Reply.Status})</caption>
 * <tr><th>code</th><th>status</th><th>body</th></tr>
 * <tr><td>0</td><td>OK</td><td>the answer, if any</td></tr>
 * <tr><td>1</td><td>NEED_ARCHIVE</td><td>empty</td></tr>
 * <tr><td>2</td><td>DUPLICATE</td><td>empty</td></tr>
 * <tr><td>3</td><td>REFUSED</td><td>why, UTF-8</td></tr>
 * <tr><td>4</td><td>MOVED</td><td>the address the agent went to, UTF-8</td></tr>
 * <tr><td>5</td><td>GONE</td><td>why, UTF-8</td></tr>
 * <tr><td>6</td><td>NOT_HANDLED</td><td>why, UTF-8</td></tr>
 * <tr><td>7</td><td>UNKNOWN_SESSION</td><td>none (the one-byte reply above)</td></tr>
 * </table>
 *
 * <p>An operation or status code this side does not know is refused with an error naming the
 * code (and, where the caller knows it, the peer); it is never looked up by position.
 */
public final class Session {

    private static final byte[] CLIENT = "robomw-agent-client".getBytes();
    private static final byte[] HOST = "robomw-agent-host".getBytes();
    private static final byte[] SESSION = "robomw-agent-session".getBytes();
    /**
     * Agent protocol version 2: every call over RMI. The first byte of an authentication request;
     * hosts of this build take it (from peers of builds before the agent wire) and answer as before.
     */
    public static final int PROTOCOL_VERSION = 2;
    /**
     * Agent protocol version 3: version 2, and transfers on the agent wire ({@link WireFrames}).
     * What peers of this build propose; the authentication answer then ends with the host's wire
     * port, which the host's proof covers.
     */
    public static final int WIRE_VERSION = 3;
    /**
     * Agent protocol version 4: version 3 with the channel bound (the request's target, inside both
     * proofs, must be the host's own address).
     */
    public static final int BOUND_VERSION = 4;
    /**
     * Agent protocol version 5: version 4, from a host that reads agent states in the compact form
     * ({@link io.robomw.agents.host.code.StateCodec#writeCompact}). What peers of this build propose;
     * over a session of an earlier version, agents travel in Java serialization's standard form,
     * which every build reads.
     */
    public static final int COMPACT_VERSION = 5;
    public static final int HEADER = 8 + 8 + 1;
    /** The first byte of an authentication answer that accepts the peer. */
    public static final byte AUTH_ACCEPTED = 0;
    /** The first byte of an authentication answer that refuses the peer; the reason follows. */
    public static final byte AUTH_REFUSED = 1;
    public static final int MAC = CallAuthenticator.TAG;

    public final long id;
    private final CallAuthenticator authenticator;
    /** The key of the session's agent wire frame tags (AES-256), or {@code null} when its authenticator is not AES-GCM. */
    public final javax.crypto.spec.SecretKeySpec frameKey;
    private final ReplayGuard served = new ReplayGuard();

    /** A session with the authenticator peers of this build propose. */
    public Session(long id, byte[] key) {
        this(id, key, CallAuthenticator.DEFAULT);
    }

    /**
     * @param id                the host's session id
     * @param key               the session key
     * @param authenticatorCode a {@link CallAuthenticator} code
     * @throws IllegalArgumentException naming the code if it is unknown
     */
    public Session(long id, byte[] key, int authenticatorCode) {
        this.id = id;
        this.authenticator = CallAuthenticator.of(authenticatorCode, key);
        this.frameKey = authenticatorCode == CallAuthenticator.AES_256_GCM ? new javax.crypto.spec.SecretKeySpec(key, "AES") : null;
    }

    /** @return the code of the session's authenticator */
    int authenticatorCode() {
        return authenticator.code();
    }

    /** @return the terms both proofs and the session key cover: [version][authenticator] */
    public static byte[] terms(int version, int authenticatorCode) {
        return new byte[] {(byte) version, (byte) authenticatorCode};
    }

    public static byte[] clientProof(ClusterKey k, byte[] terms, byte[] hostName, byte[] peerName, byte[] hostNonce, byte[] clientNonce) {
        return k.mac(CLIENT, terms, hostName, peerName, hostNonce, clientNonce);
    }

    public static byte[] hostProof(ClusterKey k, byte[] terms, byte[] hostName, byte[] peerName, byte[] hostNonce, byte[] clientNonce) {
        return k.mac(HOST, terms, hostName, peerName, hostNonce, clientNonce);
    }

    /**
     * The host's proof in a version-3 answer: it also covers the offer (the host's wire port, u16), so
     * nobody can send the peer's transfers elsewhere.
     */
    public static byte[] hostProof(ClusterKey k, byte[] terms, byte[] hostName, byte[] peerName, byte[] hostNonce, byte[] clientNonce, byte[] offer) {
        return k.mac(HOST, terms, hostName, peerName, hostNonce, clientNonce, offer);
    }

    /** The peer's proof in a version-4 request: it also covers the target, the address the peer meant to reach. */
    public static byte[] clientProof(ClusterKey k, byte[] terms, byte[] hostName, byte[] peerName, byte[] hostNonce, byte[] clientNonce, Target target) {
        return k.mac(CLIENT, terms, hostName, peerName, hostNonce, clientNonce, target.bytes());
    }

    /** The host's proof in a version-4 answer: the offer and the target the host checked. */
    public static byte[] hostProof(ClusterKey k, byte[] terms, byte[] hostName, byte[] peerName, byte[] hostNonce, byte[] clientNonce, byte[] offer,
            Target target) {
        return k.mac(HOST, terms, hostName, peerName, hostNonce, clientNonce, offer, target.bytes());
    }

    public static byte[] sessionKey(ClusterKey k, byte[] terms, byte[] hostNonce, byte[] clientNonce) {
        return k.mac(SESSION, terms, hostNonce, clientNonce);
    }

    /** Writes the header (with an {@link Op#code()}) and the MAC of a request into its frame, in place. */
    public void seal(long seq, int opCode, Frame frame) {
        byte[] b = frame.bytes;
        ByteBuffer.wrap(b, 0, HEADER).putLong(id).putLong(seq).put((byte) opCode);
        int n = frame.length - MAC;
        authenticator.tag(false, seq, b, 0, n, b, n);
    }

    /** @return whether a request's MAC is right (constant time) */
    public boolean verifyRequest(byte[] request) {
        int n = request.length - MAC;
        return n >= HEADER && authenticator.verify(false, ByteBuffer.wrap(request, 8, 8).getLong(), request, 0, n, request, n);
    }

    /**
     * @param seq a request's sequence number
     * @return whether the session has served it (or it is below the window): a replay, dropped before its MAC is checked
     */
    public boolean servedBefore(long seq) {
        return served.seen(id, seq);
    }

    /**
     * Records a verified request's number as served.
     *
     * @param seq its sequence number
     * @return {@code false} if the session has served it before (or it is below the window): a replay, not to be served
     */
    public boolean firstTime(long seq) {
        return served.accept(id, seq);
    }

    public byte[] reply(long seq, Reply r) {
        return reply(seq, r.status().code(), r.body());
    }

    /** A reply with any status byte (a host sends only {@link Reply.Status} codes; tests send others). */
    public byte[] reply(long seq, int statusCode, byte[] body) {
        byte[] b = new byte[1 + body.length + MAC];
        b[0] = (byte) statusCode;
        System.arraycopy(body, 0, b, 1, body.length);
        authenticator.tag(true, seq, b, 0, 1 + body.length, b, 1 + body.length);
        return b;
    }

    /**
     * @param seq   the request's sequence number
     * @param reply the reply as received
     * @return the reply, its MAC checked
     * @throws SecurityException if its MAC is wrong
     * @throws IllegalArgumentException naming the code if its status is unknown
     */
    public Reply verifyReply(long seq, byte[] reply) {
        int n = reply.length - MAC;
        if (n < 1 || !authenticator.verify(true, seq, reply, 0, n, reply, n)) {
            throw new SecurityException("reply has a wrong MAC: not from the host the session was made with");
        }
        return new Reply(Reply.Status.fromCode(reply[0] & 0xFF), Arrays.copyOfRange(reply, 1, n));
    }

    /** @return the reply to a call on a session the host does not know (not secret, so not MAC'd) */
    static byte[] unknownSessionReply() {
        return new byte[] {(byte) Reply.Status.UNKNOWN_SESSION.code()};
    }

    /**
     * @param reply a reply as received
     * @return whether it says the host does not know the session: the call was not served, and the
     *         peer authenticates again and repeats it (a forged one costs no more than that: a repeated
     *         transfer is a hop the host has seen)
     */
    public static boolean isUnknownSession(byte[] reply) {
        return reply.length == 1 && (reply[0] & 0xFF) == Reply.Status.UNKNOWN_SESSION.code();
    }
}
