package io.robomw.agents.host;

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

    @AfterAll
    static void closeHost() {
        if (host != null) {
            host.close();
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
        int which = data.consumeInt(0, 8);
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
