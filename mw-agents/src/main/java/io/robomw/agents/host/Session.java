package io.robomw.agents.host;

import javax.crypto.Mac;
import javax.crypto.spec.SecretKeySpec;
import java.nio.ByteBuffer;
import java.security.GeneralSecurityException;
import java.util.Arrays;

/**
 * The keys and framing of one authenticated session between a peer and a host: the session key
 * both derive from the cluster key and the two nonces, and the request and reply layouts with
 * their truncated HMACs. All integers are big-endian.
 *
 * <pre>
 * request  [session id 8][seq 8][op 1][body][mac 16]      mac over everything before it
 * reply    [status 1][body][mac 16]                       mac also covers the request's seq
 * unknown session reply  [status 7]                       alone, without a MAC (the host lost the session)
 * authentication answer  [0][session id 8][host proof 32]  or  [1][reason, UTF-8]
 * </pre>
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
final class Session {

    private static final byte[] CLIENT = "robomw-agent-client".getBytes();
    private static final byte[] HOST = "robomw-agent-host".getBytes();
    private static final byte[] SESSION = "robomw-agent-session".getBytes();
    private static final byte[] REPLY = "reply".getBytes();
    static final int HEADER = 8 + 8 + 1;
    /** The first byte of an authentication answer that accepts the peer. */
    static final byte AUTH_ACCEPTED = 0;
    /** The first byte of an authentication answer that refuses the peer; the reason follows. */
    static final byte AUTH_REFUSED = 1;
    static final int MAC = ClusterKey.CALL_MAC_LENGTH;

    final long id;
    private final SecretKeySpec key;
    /**
     * One initialised HMAC per thread that uses this session: {@link Mac#getInstance} and
     * {@link Mac#init} cost more than the MAC of a small call, and {@link Mac#doFinal} leaves a
     * {@code Mac} ready for the next message under the same key.
     */
    private final ThreadLocal<Mac> macs;

    Session(long id, byte[] key) {
        this.id = id;
        this.key = new SecretKeySpec(key, "HmacSHA256");
        this.macs = ThreadLocal.withInitial(this::newMac);
    }

    private Mac newMac() {
        try {
            Mac m = Mac.getInstance("HmacSHA256");
            m.init(key);
            return m;
        } catch (GeneralSecurityException e) {
            throw new IllegalStateException("this JDK has no HmacSHA256", e);
        }
    }

    static byte[] clientProof(ClusterKey k, byte[] hostName, byte[] peerName, byte[] hostNonce, byte[] clientNonce) {
        return k.mac(CLIENT, hostName, peerName, hostNonce, clientNonce);
    }

    static byte[] hostProof(ClusterKey k, byte[] hostName, byte[] peerName, byte[] hostNonce, byte[] clientNonce) {
        return k.mac(HOST, hostName, peerName, hostNonce, clientNonce);
    }

    static byte[] sessionKey(ClusterKey k, byte[] hostNonce, byte[] clientNonce) {
        return k.mac(SESSION, hostNonce, clientNonce);
    }

    /** Writes the header (with an {@link Op#code()}) and the MAC of a request into its frame, in place. */
    void seal(long seq, int opCode, Frame frame) {
        byte[] b = frame.bytes;
        ByteBuffer.wrap(b, 0, HEADER).putLong(id).putLong(seq).put((byte) opCode);
        int n = b.length - MAC;
        System.arraycopy(mac(b, 0, n), 0, b, n, MAC);
    }

    /** @return whether a request's MAC is right (constant time) */
    boolean verifyRequest(byte[] request) {
        int n = request.length - MAC;
        return n >= HEADER && equalMac(mac(request, 0, n), request, n);
    }

    byte[] reply(long seq, Reply r) {
        return reply(seq, r.status().code(), r.body());
    }

    /** A reply with any status byte (a host sends only {@link Reply.Status} codes; tests send others). */
    byte[] reply(long seq, int statusCode, byte[] body) {
        ByteBuffer b = ByteBuffer.allocate(1 + body.length + MAC);
        b.put((byte) statusCode).put(body);
        b.put(replyMac(seq, b.array(), 1 + body.length));
        return b.array();
    }

    /**
     * @param seq   the request's sequence number
     * @param reply the reply as received
     * @return the reply, its MAC checked
     * @throws SecurityException if its MAC is wrong
     * @throws IllegalArgumentException naming the code if its status is unknown
     */
    Reply verifyReply(long seq, byte[] reply) {
        int n = reply.length - MAC;
        if (n < 1 || !equalMac(replyMac(seq, reply, n), reply, n)) {
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
    static boolean isUnknownSession(byte[] reply) {
        return reply.length == 1 && (reply[0] & 0xFF) == Reply.Status.UNKNOWN_SESSION.code();
    }

    // The MACs are those of ClusterKey.hmac (every part prefixed with its length), computed over
    // ranges of the message in place instead of over copies of it.

    private byte[] mac(byte[] data, int off, int len) {
        Mac m = macs.get();
        updateLength(m, len);
        m.update(data, off, len);
        return Arrays.copyOf(m.doFinal(), MAC);
    }

    private byte[] replyMac(long seq, byte[] data, int len) {
        Mac m = macs.get();
        updateLength(m, REPLY.length);
        m.update(REPLY);
        updateLength(m, 8);
        for (int shift = 56; shift >= 0; shift -= 8) {
            m.update((byte) (seq >>> shift));
        }
        updateLength(m, len);
        m.update(data, 0, len);
        return Arrays.copyOf(m.doFinal(), MAC);
    }

    private static void updateLength(Mac m, int n) {
        m.update((byte) (n >>> 24));
        m.update((byte) (n >>> 16));
        m.update((byte) (n >>> 8));
        m.update((byte) n);
    }

    /** Compares a computed MAC with the one at {@code off} in a message, in constant time. */
    private static boolean equalMac(byte[] mac, byte[] message, int off) {
        int diff = 0;
        for (int i = 0; i < MAC; i++) {
            diff |= mac[i] ^ message[off + i];
        }
        return diff == 0;
    }
}
