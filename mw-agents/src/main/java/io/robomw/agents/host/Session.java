package io.robomw.agents.host;

import java.nio.ByteBuffer;
import java.security.MessageDigest;
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
    private final byte[] key;

    Session(long id, byte[] key) {
        this.id = id;
        this.key = key;
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

    byte[] request(long seq, Op op, byte[] body) {
        ByteBuffer b = ByteBuffer.allocate(HEADER + body.length + MAC);
        b.putLong(id).putLong(seq).put((byte) op.ordinal()).put(body);
        b.put(mac(b.array(), 0, HEADER + body.length));
        return b.array();
    }

    /** @return whether a request's MAC is right (constant time) */
    boolean verifyRequest(byte[] request) {
        int n = request.length - MAC;
        return n >= HEADER && MessageDigest.isEqual(mac(request, 0, n), Arrays.copyOfRange(request, n, request.length));
    }

    byte[] reply(long seq, Reply r) {
        ByteBuffer b = ByteBuffer.allocate(1 + r.body().length + MAC);
        b.put((byte) r.status().ordinal()).put(r.body());
        b.put(replyMac(seq, b.array(), 1 + r.body().length));
        return b.array();
    }

    Reply verifyReply(long seq, byte[] reply) {
        int n = reply.length - MAC;
        if (n < 1 || !MessageDigest.isEqual(replyMac(seq, reply, n), Arrays.copyOfRange(reply, n, reply.length))) {
            throw new SecurityException("reply has a wrong MAC: not from the host the session was made with");
        }
        return new Reply(Reply.Status.of(reply[0]), Arrays.copyOfRange(reply, 1, n));
    }

    private byte[] mac(byte[] data, int off, int len) {
        return Arrays.copyOf(ClusterKey.hmac(key, Arrays.copyOfRange(data, off, off + len)), MAC);
    }

    private byte[] replyMac(long seq, byte[] data, int len) {
        return Arrays.copyOf(ClusterKey.hmac(key, REPLY, ByteBuffer.allocate(8).putLong(seq).array(), Arrays.copyOf(data, len)), MAC);
    }
}
