package io.robomw.agents.host;

import io.robomw.agents.host.ops.HostWatch;
import io.robomw.agents.host.protocol.AgentEvent;
import io.robomw.agents.host.protocol.AgentImage;
import io.robomw.agents.host.protocol.Bodies;
import io.robomw.agents.host.protocol.Op;
import io.robomw.agents.host.protocol.Reply;
import io.robomw.agents.host.rmi.HostEndpoint;
import io.robomw.agents.host.rmi.HostSockets;
import io.robomw.agents.host.rmi.PeerLink;
import io.robomw.agents.host.rmi.Session;
import io.robomw.agents.host.wire.WireFrames;
import io.robomw.agents.host.wire.WireReader;
import io.robomw.agents.host.wire.WireWriter;
import com.code_intelligence.jazzer.api.FuzzedDataProvider;
import com.code_intelligence.jazzer.junit.FuzzTest;
import org.junit.jupiter.api.AfterAll;

import java.io.IOException;
import java.util.Arrays;

/**
 * Fuzz tests of what an agent host decodes from its peers (docs/fuzzing.md): event, image and
 * description bodies, every call body layout of {@link Bodies}, the endpoint's authentication and
 * call frames, and the calls a host serves. A decoder may refuse bytes only the way it documents
 * (an {@link IllegalArgumentException} or {@link IOException} naming what is wrong; a refused
 * reply from the host); what it accepts must survive its own encoder. Anything else (an index out
 * of bounds, a negative array size, memory claimed by a length field, a host that stops serving)
 * is a finding.
 */
class HostDecodersFuzzTest {

    private static final ClusterKey KEY = ClusterKey.fromPassphrase("fuzz");
    private static AgentHost host;
    private static AgentHost wireHost;
    private static Session wireSession;
    /** Each input's frames are numbered from its own base: no input replays another's numbers. */
    private static long wireSeqBase = 1L << 20;

    @AfterAll
    static void closeHost() {
        if (host != null) {
            host.close();
        }
        if (wireHost != null) {
            wireHost.close();
        }
    }

    @FuzzTest
    void agentEvent(byte[] input) {
        AgentEvent e;
        try {
            e = AgentEvent.decode(input);
        } catch (IllegalArgumentException refused) {
            return;
        }
        AgentEvent again = AgentEvent.decode(e.encode());
        if (!again.id().equals(e.id()) || again.seq() != e.seq() || again.kind() != e.kind() || !Arrays.equals(again.payload(), e.payload())) {
            throw new AssertionError("an event does not survive its own encoding: " + e + " -> " + again);
        }
    }

    @FuzzTest
    void agentImage(byte[] input) {
        AgentImage image;
        try {
            image = AgentImage.decode(input);
        } catch (IllegalArgumentException refused) {
            return;
        }
        AgentImage again = AgentImage.decode(image.encode());
        if (!again.id().equals(image.id()) || again.hop() != image.hop() || again.kind() != image.kind() || again.stateLength() != image.stateLength()) {
            throw new AssertionError("an image does not survive its own encoding");
        }
    }

    @FuzzTest
    void hostDescription(byte[] input) {
        HostDescription d;
        try {
            d = HostDescription.decode(input, "fuzz");
        } catch (IllegalArgumentException refused) {
            return;
        }
        if (!HostDescription.decode(d.encode(), "fuzz").equals(d)) {
            throw new AssertionError("a description does not survive its own encoding: " + d);
        }
    }

    /** A host's answer to WATCH, as a watcher ({@code mw console}) reads it. */
    @FuzzTest
    void watch(byte[] input) {
        try {
            HostWatch.decode("fuzz", input, 0);
        } catch (IOException refused) {
            // the documented refusal
        }
    }

    /** Every layout of {@link Bodies}: the first byte picks the reader, the rest is the body. */
    @FuzzTest
    void bodies(FuzzedDataProvider data) {
        int which = data.consumeInt(0, 9);
        byte[] body = data.consumeRemainingAsBytes();
        try {
            switch (which) {
                case 0 -> Bodies.readListReply(body, "fuzz");
                case 1 -> Bodies.readOwedReply(body, "fuzz");
                case 2 -> Bodies.readDropOwed(body);
                case 3 -> Bodies.readVisits(body);
                case 4 -> Bodies.readMessage(body);
                case 5 -> Bodies.readAgentRequest(body);
                case 6 -> Bodies.readArchive(body);
                case 7 -> Bodies.readOwedEvent(body);
                case 8 -> Bodies.readArrivals(body);
                default -> Bodies.readListReply(body, "fuzz");
            }
        } catch (IllegalArgumentException | IOException refused) {
            // the documented refusal
        }
    }

    /** The RMI endpoint's two entry points, with bytes from an unauthenticated peer. */
    @FuzzTest
    void endpoint(FuzzedDataProvider data) {
        HostEndpoint endpoint = new HostEndpoint("fuzz", KEY, (peer, op, message, offset, length) -> Reply.ok());
        byte[] auth = data.consumeBytes(data.consumeInt(0, 200));
        byte[] answer = endpoint.authenticate(auth);
        if (answer.length == 0 || answer[0] != Session.AUTH_REFUSED) {
            throw new AssertionError("a peer that never asked for a challenge was authenticated");
        }
        byte[] call = endpoint.call(data.consumeRemainingAsBytes());
        if (call.length > 1) {
            throw new AssertionError("an unauthenticated call got a reply of " + call.length + " bytes");
        }
    }

    /**
     * The agent wire of a running host (protocol version 3, {@link WireFrames}): the input is a
     * {@link WireScript} of raw bytes and frames (sealed here with a real session, so the fuzzer
     * reaches past the tag check), written on a real loopback connection, which is then half-closed.
     * The host may answer only with frames a peer can read (version 3, a known status, an untagged
     * answer of at most {@value WireFrames#MAX_REASON_BYTES} bytes), must close the connection
     * (never hang), and must serve a new connection's HELLO afterwards.
     */
    @FuzzTest
    void wireFrames(byte[] input) throws Exception {
        // The target talks to its own host on loopback, and only there (Jazzer's SSRF detector refuses other connections).
        try (com.code_intelligence.jazzer.api.SilentCloseable loopbackOnly = com.code_intelligence.jazzer.api.BugDetectors.allowNetworkConnections(
                (host, port) -> host.equals("127.0.0.1") || host.equals("localhost"))) {
            wireFramesOnLoopback(input);
        }
    }

    private void wireFramesOnLoopback(byte[] input) throws Exception {
        if (wireHost == null) {
            wireHost = AgentHost.builder("wire-fuzzed").clusterKey(KEY).noMessaging().stopGrace(java.time.Duration.ZERO).start();
            wireSession = new PeerLink(HostAddress.parse(wireHost.address()), "fuzz", KEY, new HostSockets.Client("127.0.0.1", false, 10_000),
                    new java.security.SecureRandom()).sessionForTests();
        }
        long base = wireSeqBase;
        wireSeqBase += 1 << 17;
        try (java.net.Socket s = new java.net.Socket("127.0.0.1", wireHost.wirePort())) {
            s.setSoTimeout(20_000);
            try {
                WireScript.play(input, wireSession, base, s.getOutputStream());
                s.shutdownOutput();
            } catch (java.net.SocketException closedEarly) {
                // the host refused what came first and closed: what it answered is read below
            }
            WireReader answers = new WireReader(s.getInputStream(), null);
            try {
                WireFrames.Header h;
                while ((h = answers.header()) != null) {
                    boolean untagged = h.code() == Reply.Status.UNKNOWN_SESSION.code() || h.code() == WireFrames.STATUS_FRAME_REFUSED;
                    if (h.version() != WireFrames.VERSION || (!untagged && h.code() > Reply.Status.UNKNOWN_SESSION.code())
                            || (untagged && h.length() > WireFrames.MAX_REASON_BYTES) || h.length() > 1 << 20) {
                        throw new AssertionError("the host answered a frame a peer cannot read: " + h);
                    }
                    answers.frame(h, null);
                }
            } catch (java.net.SocketException reset) {
                // a refusing host may reset the connection after its answer
            }
        }
        try (java.net.Socket s = new java.net.Socket("127.0.0.1", wireHost.wirePort())) {
            s.setSoTimeout(20_000);
            long n = base + (1 << 17) - 1;
            WireWriter w = new WireWriter(WireWriter.of(s.getOutputStream()));
            w.write(wireSession.frameKey, WireFrames.DIRECTION_REQUEST, WireFrames.OP_HELLO, wireSession.id, n, new byte[0], 0, 0);
            WireFrames.Header h = new WireReader(s.getInputStream(), null).header();
            if (h == null || h.code() != Reply.Status.OK.code()) {
                throw new AssertionError("the host stopped serving its wire after a script of " + input.length + " bytes: " + h);
            }
        }
    }

    /** The calls a running host serves, as a verified peer would make them: an operation code and a body. */
    @FuzzTest
    void hostCalls(FuzzedDataProvider data) throws Exception {
        if (host == null) {
            host = AgentHost.builder("fuzzed").clusterKey(KEY).noMessaging().stopGrace(java.time.Duration.ZERO).start();
        }
        Op op = Op.fromCode(data.consumeInt(0, 10));
        byte[] body = data.consumeRemainingAsBytes();
        Reply r = host.serve("fuzz", op, body);
        if (r == null || r.status() == null) {
            throw new AssertionError("no reply to " + op);
        }
        if (host.serve("fuzz", Op.LIST, new byte[0]).status() != Reply.Status.OK) {
            throw new AssertionError("the host stopped serving after a " + op + " of " + body.length + " bytes");
        }
    }
}
