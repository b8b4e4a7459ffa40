package io.robomw.agents.host;

import javax.crypto.Mac;
import javax.crypto.spec.SecretKeySpec;
import java.nio.ByteBuffer;
import java.security.GeneralSecurityException;
import java.util.Arrays;

/**
 * The keys and framing of one authenticated session between a peer and a host: the session key
 * both derive from the cluster key and the two nonces, and the request and reply layouts with
 * their truncated HMACs. Requests: {@code [session id 8][seq 8][op 1][body][mac 16]}; replies:
 * {@code [status 1][body][mac 16]}, the reply's MAC also covering the request's sequence number.
 */
final class Session {

    private static final byte[] CLIENT = "robomw-agent-client".getBytes();
    private static final byte[] HOST = "robomw-agent-host".getBytes();
    private static final byte[] SESSION = "robomw-agent-session".getBytes();
    private static final byte[] REPLY = "reply".getBytes();
    static final int HEADER = 8 + 8 + 1;
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

    /** Writes the header and the MAC of a request into its frame, in place. */
    void seal(long seq, Op op, Frame frame) {
        byte[] b = frame.bytes;
        ByteBuffer.wrap(b, 0, HEADER).putLong(id).putLong(seq).put((byte) op.ordinal());
        int n = b.length - MAC;
        System.arraycopy(mac(b, 0, n), 0, b, n, MAC);
    }

    /** @return whether a request's MAC is right (constant time) */
    boolean verifyRequest(byte[] request) {
        int n = request.length - MAC;
        return n >= HEADER && equalMac(mac(request, 0, n), request, n);
    }

    byte[] reply(long seq, Reply r) {
        ByteBuffer b = ByteBuffer.allocate(1 + r.body().length + MAC);
        b.put((byte) r.status().ordinal()).put(r.body());
        b.put(replyMac(seq, b.array(), 1 + r.body().length));
        return b.array();
    }

    Reply verifyReply(long seq, byte[] reply) {
        int n = reply.length - MAC;
        if (n < 1 || !equalMac(replyMac(seq, reply, n), reply, n)) {
            throw new SecurityException("reply has a wrong MAC: not from the host the session was made with");
        }
        return new Reply(Reply.Status.of(reply[0]), Arrays.copyOfRange(reply, 1, n));
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
