package io.robomw.agents.host;

import io.robomw.agents.host.protocol.Bodies;
import io.robomw.agents.host.core.HostState;
import io.robomw.agents.host.protocol.AgentEvent;
import io.robomw.agents.host.protocol.Op;
import io.robomw.agents.host.code.CodeArchive;
import io.robomw.agents.host.trip.VisitorAgent;
import io.robomw.testkit.LogLines;
import org.junit.jupiter.api.BeforeEach;
import org.junit.jupiter.api.extension.RegisterExtension;
import org.junit.jupiter.api.Test;

import java.util.List;
import java.util.UUID;
import java.util.concurrent.TimeUnit;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * An authenticated peer sends calls with codes no host knows: each is refused with a reply that
 * names the code, counted, and the host goes on serving agents.
 */
class UnknownCodesTest {

    private static final ClusterKey KEY = ClusterKey.fromPassphrase("unknown codes");
    @RegisterExtension
    final StartedHosts hosts = new StartedHosts();
    private AgentHost host;
    private AgentHost home;
    private HostProbe probe;
    private CodeArchive archive;

    @BeforeEach
    void start() throws Exception {
        host = hosts.start(AgentHost.builder("strict").clusterKey(KEY));
        home = hosts.start(AgentHost.builder("home").clusterKey(KEY));
        probe = new HostProbe(host.address(), KEY);
        archive = HostProbe.archiveOf(VisitorAgent.class);
        assertEquals("OK ", probe.putArchive(archive.digest(), archive.bytes()));
    }

    private void refusedAndStillServing(String answer, String says) throws Exception {
        assertTrue(answer.startsWith("REFUSED") && answer.contains(says), answer);
        assertEquals(List.of("strict"), home.agency().sendAgent(host.address(), new VisitorAgent()).result().get(10, TimeUnit.SECONDS));
    }

    @Test
    void callWithAnUnknownOperationCodeIsRefused() throws Exception {
        long before = host.refused();
        refusedAndStillServing(probe.call(42, new byte[0]), "unknown operation code 42");
        assertTrue(host.refused() > before, "counted");
    }

    @Test
    void transferWithAnUnknownImageKindIsRefused() throws Exception {
        byte[] image = HostProbe.image(archive.digest(), HostProbe.state(new VisitorAgent()));
        image[0] = 5;
        refusedAndStillServing(probe.call(Op.TRANSFER.code(), image), "refused a transfer from peer 'probe': unknown agent image kind code 5");
    }

    @Test
    void transferWhoseItineraryHasAnUnknownPolicyCodeIsRefused() throws Exception {
        VisitorAgent agent = new VisitorAgent();
        agent.itinerary().repeat(5);
        byte[] state = HostProbe.state(agent);
        // The itinerary's position (current -1, round 0, rounds 5), then its policy code.
        int at = indexAfter(state, new byte[] {-1, -1, -1, -1, 0, 0, 0, 0, 0, 0, 0, 5});
        assertEquals(0, state[at], "SKIP's code");
        state[at] = 77;
        refusedAndStillServing(probe.transfer(archive.digest(), VisitorAgent.class.getName(), state), "unknown unreachable-policy code 77");
    }

    @Test
    void eventWithAnUnknownKindIsRefused() throws Exception {
        byte[] event = new AgentEvent(UUID.randomUUID(), 1, AgentEvent.Kind.REPORT, "rmi://127.0.0.1:1/x", new byte[0]).encode();
        event[24] = 42;
        refusedAndStillServing(probe.call(Op.EVENT.code(), event), "refused an event from peer 'probe': unknown event kind code 42");
    }

    @Test
    void messageWithAnUnknownOneWayFlagIsRefused() throws Exception {
        byte[] body = Bodies.message(UUID.randomUUID(), true, new byte[0]);
        body[16] = 3;
        refusedAndStillServing(probe.call(Op.MESSAGE.code(), body), "refused a message from peer 'probe': unknown one-way flag 3");
    }

    @Test
    void requestCutShortIsRefused() throws Exception {
        refusedAndStillServing(probe.call(Op.DISPOSE.code(), new byte[3]), "refused a DISPOSE from peer 'probe': a RETRACT or DISPOSE body of 3 bytes");
    }

    @Test
    void aFloodOfRefusedCallsLogsAFewLinesASecondAndCountsEveryOne() throws Exception {
        byte[] event = new AgentEvent(UUID.randomUUID(), 1, AgentEvent.Kind.REPORT, "rmi://127.0.0.1:1/x", new byte[0]).encode();
        event[24] = 42;
        long before = host.refused();
        try (LogLines log = new LogLines()) {
            long start = System.nanoTime();
            for (int i = 0; i < 200; i++) {
                assertTrue(host.serve("flood", Op.EVENT, event).text().contains("unknown event kind code 42"));
            }
            long elapsedSeconds = (System.nanoTime() - start) / 1_000_000_000L;
            List<String> lines = log.containing("host strict: refused an event from peer 'flood'");
            // A burst at once, then at most a burst a second; one more burst for one begun at a second's edge.
            long most = HostState.REFUSALS_LOGGED_PER_SECOND * (elapsedSeconds + 2);
            assertTrue(!lines.isEmpty() && lines.size() <= most, lines.size() + " lines for 200 refusals in " + elapsedSeconds + " s (at most " + most + ")");
        }
        assertEquals(before + 200, host.refused(), "every refusal is counted");
    }

    private static int indexAfter(byte[] bytes, byte[] pattern) {
        for (int i = 0; i + pattern.length < bytes.length; i++) {
            if (java.util.Arrays.equals(bytes, i, i + pattern.length, pattern, 0, pattern.length)) {
                return i + pattern.length;
            }
        }
        throw new AssertionError("pattern not found");
    }
}
