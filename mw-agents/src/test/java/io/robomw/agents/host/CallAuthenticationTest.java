package io.robomw.agents.host;

import io.robomw.agents.host.protocol.Frame;
import io.robomw.agents.host.protocol.Op;
import io.robomw.agents.host.protocol.Reply;
import io.robomw.agents.host.rmi.HostEndpoint;
import io.robomw.agents.host.rmi.PeerLink;
import io.robomw.agents.host.rmi.Session;
import io.robomw.agents.host.rmi.Target;
import io.robomw.agents.host.security.CallAuthenticator;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.params.ParameterizedTest;
import org.junit.jupiter.params.provider.ValueSource;

import java.io.ByteArrayOutputStream;
import java.io.DataOutputStream;
import java.io.IOException;
import java.nio.ByteBuffer;
import java.nio.charset.StandardCharsets;
import java.security.SecureRandom;
import java.util.ArrayList;
import java.util.List;

import static org.junit.jupiter.api.Assertions.assertArrayEquals;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * The promises of docs/agents.md ("Trust") for every call between hosts, with each authenticator
 * a peer may propose: a host serves a call only from a peer that proved the cluster key, only as
 * it was sealed (a changed byte anywhere is dropped), and only once (a replay is dropped); a peer
 * takes a reply only as the host sealed it, and only for the call it asked; the version and the
 * authenticator are covered by the proofs, and unknown ones are refused naming them. The peer here
 * speaks to a {@link HostEndpoint} directly, byte for byte, as {@link PeerLink} would over RMI.
 */
class CallAuthenticationTest {

    private static final ClusterKey KEY = ClusterKey.fromPassphrase("call authentication test");
    private static final ClusterKey OTHER_KEY = ClusterKey.fromPassphrase("not the cluster's");

    /** What the host was asked to do: the bodies of the calls it served. */
    private final List<String> served = new ArrayList<>();
    private final HostEndpoint host = new HostEndpoint("host-h", KEY, (peer, op, m, off, len) -> {
        served.add(op + " " + new String(m, off, len, StandardCharsets.UTF_8));
        return Reply.ok(("done " + served.size()).getBytes(StandardCharsets.UTF_8));
    });

    /** A peer's side of the handshake, as PeerLink does it. @return the answer and the session it makes, if accepted */
    private record Handshake(byte[] answer, Session session) {
    }

    private Handshake authenticate(ClusterKey key, int version, int authenticator, int proofAuthenticator) throws IOException {
        byte[] hostNonce = host.challenge();
        byte[] clientNonce = new byte[32];
        new SecureRandom().nextBytes(clientNonce);
        byte[] hostName = "host-h".getBytes(StandardCharsets.UTF_8);
        byte[] peerName = "peer-p".getBytes(StandardCharsets.UTF_8);
        byte[] terms = Session.terms(version, proofAuthenticator);
        ByteArrayOutputStream req = new ByteArrayOutputStream();
        DataOutputStream out = new DataOutputStream(req);
        out.writeByte(version);
        out.writeByte(authenticator);
        out.writeUTF("peer-p");
        out.write(hostNonce);
        out.write(clientNonce);
        out.write(Session.clientProof(key, terms, hostName, peerName, hostNonce, clientNonce));
        byte[] answer = host.authenticate(req.toByteArray());
        if (answer[0] != Session.AUTH_ACCEPTED) {
            return new Handshake(answer, null);
        }
        ByteBuffer b = ByteBuffer.wrap(answer, 1, answer.length - 1);
        long id = b.getLong();
        byte[] proof = new byte[32];
        b.get(proof);
        if (version == Session.WIRE_VERSION) {
            byte[] offer = new byte[2];
            b.get(offer);
            assertEquals(0, b.remaining(), "a version-3 answer ends with the wire port");
            assertArrayEquals(Session.hostProof(key, terms, hostName, peerName, hostNonce, clientNonce, offer), proof,
                    "the host proves the key in turn, and its proof covers the wire port it offers");
        } else {
            assertEquals(0, b.remaining(), "a version-2 answer is as builds before the wire read it");
            assertArrayEquals(Session.hostProof(key, terms, hostName, peerName, hostNonce, clientNonce), proof, "the host proves the key in turn");
        }
        return new Handshake(answer, new Session(id, Session.sessionKey(key, terms, hostNonce, clientNonce), authenticator));
    }

    private Session session(int authenticator) throws IOException {
        Handshake h = authenticate(KEY, Session.PROTOCOL_VERSION, authenticator, authenticator);
        assertEquals(Session.AUTH_ACCEPTED, h.answer()[0], () -> "refused: " + refusal(h.answer()));
        return h.session();
    }

    private static String refusal(byte[] answer) {
        return new String(answer, 1, answer.length - 1, StandardCharsets.UTF_8);
    }

    private static byte[] sealed(Session s, long seq, String body) {
        Frame f = Frame.of(body.getBytes(StandardCharsets.UTF_8));
        s.seal(seq, Op.LIST.code(), f);
        return f.bytes;
    }

    @ParameterizedTest
    @ValueSource(ints = {CallAuthenticator.HMAC_SHA256_128, CallAuthenticator.AES_256_GCM})
    void aCallSealedOnTheSessionIsServedOnceAndItsReplyChecks(int authenticator) throws IOException {
        Session s = session(authenticator);
        byte[] reply = host.call(sealed(s, 1, "first"));
        assertEquals("done 1", s.verifyReply(1, reply).text());
        assertEquals(List.of("LIST first"), served);
    }

    @ParameterizedTest
    @ValueSource(ints = {CallAuthenticator.HMAC_SHA256_128, CallAuthenticator.AES_256_GCM})
    void aChangedByteAnywhereInACallGetsItDroppedUnserved(int authenticator) throws IOException {
        Session s = session(authenticator);
        byte[] call = sealed(s, 5, "move agent 1 MB");
        // the sequence number, the operation, the body, the tag (the session id would find no session)
        for (int at : new int[] {8, 15, 16, Session.HEADER + 3, call.length - 1}) {
            byte[] tampered = call.clone();
            tampered[at] ^= 0x01;
            assertArrayEquals(new byte[0], host.call(tampered), "flipped byte " + at);
        }
        byte[] cut = java.util.Arrays.copyOf(call, call.length - 1);
        assertArrayEquals(new byte[0], host.call(cut), "a call cut short");
        assertEquals(List.of(), served);
        assertEquals(6, host.refused());
        assertEquals("done 1", s.verifyReply(5, host.call(call)).text(), "the genuine call is still served after tampered copies of it");
    }

    @ParameterizedTest
    @ValueSource(ints = {CallAuthenticator.HMAC_SHA256_128, CallAuthenticator.AES_256_GCM})
    void aReplayedCallIsDroppedAndServedOnlyOnce(int authenticator) throws IOException {
        Session s = session(authenticator);
        byte[] call = sealed(s, 10, "dispose");
        host.call(call);
        assertArrayEquals(new byte[0], host.call(call), "the same call again");
        host.call(sealed(s, 11, "later"));
        assertArrayEquals(new byte[0], host.call(call), "an older call after a later one");
        assertEquals(List.of("LIST dispose", "LIST later"), served);
        assertEquals(2, host.refused());
    }

    @Test
    void aCallSealedUnderAnotherKeyIsDroppedEvenWithALiveSessionId() throws IOException {
        Session genuine = session(CallAuthenticator.AES_256_GCM);
        Session forger = new Session(genuine.id, OTHER_KEY.mac("guessed session key".getBytes(StandardCharsets.UTF_8)), CallAuthenticator.AES_256_GCM);
        assertArrayEquals(new byte[0], host.call(sealed(forger, 1, "forged")));
        assertEquals(List.of(), served);
    }

    @Test
    void aPeerWithTheWrongClusterKeyIsRefused() throws IOException {
        Handshake h = authenticate(OTHER_KEY, Session.PROTOCOL_VERSION, CallAuthenticator.AES_256_GCM, CallAuthenticator.AES_256_GCM);
        assertEquals(Session.AUTH_REFUSED, h.answer()[0]);
        assertTrue(refusal(h.answer()).contains("wrong cluster key"), refusal(h.answer()));
    }

    @ParameterizedTest
    @ValueSource(ints = {CallAuthenticator.HMAC_SHA256_128, CallAuthenticator.AES_256_GCM})
    void aReplyIsTakenOnlyAsSealedAndOnlyForTheCallItAnswers(int authenticator) throws IOException {
        Session s = session(authenticator);
        byte[] reply = host.call(sealed(s, 3, "list"));
        byte[] tampered = reply.clone();
        tampered[1] ^= 0x20;
        assertThrows(SecurityException.class, () -> s.verifyReply(3, tampered));
        assertThrows(SecurityException.class, () -> s.verifyReply(4, reply), "a reply to call 3 is no answer to call 4");
        Session other = session(authenticator);
        assertThrows(SecurityException.class, () -> other.verifyReply(3, reply), "nor to call 3 of another session");
        assertEquals("done 1", s.verifyReply(3, reply).text());
    }

    @Test
    void theProofsCoverTheAuthenticatorSoAPeerCannotBeTalkedIntoAnother() throws IOException {
        // A request that says HMAC (1) with a proof made for the GCM tag (2), as a man in the middle rewriting the byte would send.
        Handshake h = authenticate(KEY, Session.PROTOCOL_VERSION, CallAuthenticator.HMAC_SHA256_128, CallAuthenticator.AES_256_GCM);
        assertEquals(Session.AUTH_REFUSED, h.answer()[0]);
        assertTrue(refusal(h.answer()).contains("wrong cluster key"), refusal(h.answer()));
    }

    @Test
    void anUnknownAuthenticatorCodeIsRefusedNamingIt() throws IOException {
        Handshake h = authenticate(KEY, Session.PROTOCOL_VERSION, 99, 99);
        assertEquals(Session.AUTH_REFUSED, h.answer()[0]);
        String why = refusal(h.answer());
        assertTrue(why.contains("unknown call authenticator code 99") && why.contains("2 AES-256-GCM tag"), why);
    }

    /** A version-4 request as PeerLink makes it: the target, the address the peer meant to reach, under the proof. */
    private byte[] boundRequest(ClusterKey key, Target target, Target signed) throws IOException {
        byte[] hostNonce = host.challenge();
        byte[] clientNonce = new byte[32];
        new SecureRandom().nextBytes(clientNonce);
        byte[] terms = Session.terms(Session.BOUND_VERSION, CallAuthenticator.AES_256_GCM);
        ByteArrayOutputStream req = new ByteArrayOutputStream();
        DataOutputStream out = new DataOutputStream(req);
        out.writeByte(Session.BOUND_VERSION);
        out.writeByte(CallAuthenticator.AES_256_GCM);
        out.writeUTF("peer-p");
        out.write(target.bytes());
        out.write(hostNonce);
        out.write(clientNonce);
        out.write(Session.clientProof(key, terms, "host-h".getBytes(StandardCharsets.UTF_8), "peer-p".getBytes(StandardCharsets.UTF_8), hostNonce,
                clientNonce, signed));
        return req.toByteArray();
    }

    @Test
    void versionFourIsTakenFromAPeerThatMeantToReachThisHost() throws IOException {
        java.net.InetAddress loopback = java.net.InetAddress.getLoopbackAddress();
        host.address(loopback, 1099);
        Target here = new Target(loopback, 1099);
        byte[] answer = host.authenticate(boundRequest(KEY, here, here));
        assertEquals(Session.AUTH_ACCEPTED, answer[0], () -> refusal(answer));
        assertEquals(1 + 8 + 32 + 2, answer.length, "a version-4 answer is laid out as version 3's");
    }

    @Test
    void versionFourFromAPeerThatMeantAnotherAddressIsRefusedNamingBoth() throws IOException {
        java.net.InetAddress loopback = java.net.InetAddress.getLoopbackAddress();
        host.address(loopback, 1099);
        Target relay = new Target(loopback, 4000);
        byte[] relayed = host.authenticate(boundRequest(KEY, relay, relay));
        assertEquals(Session.AUTH_REFUSED, relayed[0]);
        assertTrue(refusal(relayed).contains("it meant to reach host-h at 127.0.0.1:4000, but this host is at 127.0.0.1:1099"), refusal(relayed));
        Target here = new Target(loopback, 1099);
        byte[] rewritten = host.authenticate(boundRequest(KEY, here, relay));
        assertEquals(Session.AUTH_REFUSED, rewritten[0], "a relay that rewrites the target breaks the proof");
        assertTrue(refusal(rewritten).contains("wrong cluster key"), refusal(rewritten));
        assertEquals(List.of(), served);
    }

    @Test
    void versionThreeIsTakenAndItsAnswerNamesTheWirePortUnderTheProof() throws IOException {
        host.wirePort(4242);
        Handshake h = authenticate(KEY, Session.WIRE_VERSION, CallAuthenticator.AES_256_GCM, CallAuthenticator.AES_256_GCM);
        assertEquals(Session.AUTH_ACCEPTED, h.answer()[0], () -> refusal(h.answer()));
        assertEquals(4242, ((h.answer()[41] & 0xFF) << 8) | (h.answer()[42] & 0xFF));
        Handshake hmac = authenticate(KEY, Session.WIRE_VERSION, CallAuthenticator.HMAC_SHA256_128, CallAuthenticator.HMAC_SHA256_128);
        assertEquals(0, ((hmac.answer()[41] & 0xFF) << 8) | (hmac.answer()[42] & 0xFF), "no wire for a session not tagged with AES-GCM");
        HostEndpoint old = new HostEndpoint("host-h", KEY, (peer, op, m, off, len) -> Reply.ok(), Session.PROTOCOL_VERSION);
        byte[] refused = old.authenticate(new byte[] {(byte) Session.WIRE_VERSION, (byte) CallAuthenticator.AES_256_GCM, 0, 0});
        assertTrue(refusal(refused).contains("version 3; this host speaks version 2"), "as a build before the wire refuses it: " + refusal(refused));
    }

    @Test
    void aPeerOfAnotherProtocolVersionIsRefusedNamingBoth() throws IOException {
        Handshake h = authenticate(KEY, 6, CallAuthenticator.AES_256_GCM, CallAuthenticator.AES_256_GCM);
        assertEquals(Session.AUTH_REFUSED, h.answer()[0]);
        assertTrue(refusal(h.answer()).contains("version 6; this host speaks versions 2, 3, 4 and 5"), refusal(h.answer()));
        HostEndpoint beforeCompact = new HostEndpoint("host-h", KEY, (peer, op, m, off, len) -> Reply.ok(), Session.BOUND_VERSION);
        byte[] refused = beforeCompact.authenticate(new byte[] {(byte) Session.COMPACT_VERSION, (byte) CallAuthenticator.AES_256_GCM, 0, 0});
        assertTrue(refusal(refused).contains("protocol version 5; this host speaks versions 2, 3 and 4"),
                "as a build before the compact form refuses it, in the words a peer falls back to 4 on: " + refusal(refused));
        // A protocol-1 request (no version byte: the peer name's u16 length first) reads as version 0.
        ByteArrayOutputStream old = new ByteArrayOutputStream();
        DataOutputStream out = new DataOutputStream(old);
        out.writeUTF("peer-p");
        out.write(host.challenge());
        out.write(new byte[64]);
        byte[] answer = host.authenticate(old.toByteArray());
        assertEquals(Session.AUTH_REFUSED, answer[0]);
        assertTrue(refusal(answer).contains("version 0 or 1"), refusal(answer));
    }

    @Test
    void theSameReplyNumberTaggedTwiceInARowIsAnErrorNotATag() {
        Session s = new Session(7, new byte[32], CallAuthenticator.AES_256_GCM);
        s.reply(9, Reply.ok());
        // GCM under one key and nonce twice would give the hash subkey away. The replay window keeps a host from
        // answering a number twice; the JDK's refusal to reuse the nonce it has just used is the last safety net.
        assertThrows(IllegalStateException.class, () -> s.reply(9, Reply.of(Reply.Status.REFUSED, "other")));
    }

    @Test
    void unknownAuthenticatorCodesAreAnErrorNamingTheCode() {
        IllegalArgumentException e = assertThrows(IllegalArgumentException.class, () -> CallAuthenticator.of(0, new byte[32]));
        assertTrue(e.getMessage().contains("code 0"), e.getMessage());
    }
}
