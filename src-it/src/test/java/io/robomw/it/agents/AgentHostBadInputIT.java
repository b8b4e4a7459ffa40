package io.robomw.it.agents;

import io.robomw.agents.host.AgentHost;
import io.robomw.agents.host.ClusterKey;
import io.robomw.agents.host.HostProbe;
import io.robomw.agents.host.code.CodeArchive;
import io.robomw.agents.host.trip.VisitorAgent;
import org.junit.jupiter.api.AfterAll;
import org.junit.jupiter.api.BeforeAll;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

import java.io.IOException;
import java.nio.ByteBuffer;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicLong;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * An agent host in its own JVM is sent what no honest peer sends: a wrong cluster key, a tampered
 * archive, state with a class that is not allowed, a depth bomb, a stream announcing a huge
 * array. Each is refused with a log line saying why, and the host goes on serving agents.
 */
class AgentHostBadInputIT {

    @TempDir
    static Path dir;
    static HostProcess host;
    static CodeArchive archive;

    @BeforeAll
    static void start() throws Exception {
        host = HostProcess.start("guarded", "--key-file", AgentTripIT.keyFile(dir).toString());
        archive = HostProbe.archiveOf(VisitorAgent.class);
        assertEquals("OK ", new HostProbe(host.address(), AgentTripIT.KEY).putArchive(archive.digest(), archive.bytes()));
    }

    @AfterAll
    static void stop() {
        if (host != null) {
            host.close();
        }
    }

    private static HostProbe probe() {
        return new HostProbe(host.address(), AgentTripIT.KEY);
    }

    private static void hostStillServesAgents() throws Exception {
        try (AgentHost home = AgentHost.builder("bad-input-home").clusterKey(AgentTripIT.KEY).start()) {
            assertEquals(List.of("guarded"), home.agency().sendAgent(host.address(), new VisitorAgent()).result().get(30, TimeUnit.SECONDS));
        }
    }

    private static void logSays(String text) throws IOException {
        String log = host.log();
        assertTrue(log.contains(text), "the host's log says '" + text + "':\n" + log);
    }

    @Test
    void peerWithTheWrongKeyIsRefused() throws Exception {
        HostProbe intruder = new HostProbe(host.address(), ClusterKey.fromPassphrase("a guess"));
        IOException e = assertThrows(IOException.class, () -> intruder.transfer(archive.digest(), VisitorAgent.class.getName(), HostProbe.state(new VisitorAgent())));
        assertTrue(e.getMessage().contains("wrong cluster key"), e.getMessage());
        logSays("refused peer 'probe'");
        hostStillServesAgents();
    }

    @Test
    void callsWithCodesTheHostDoesNotKnowAreRefused() throws Exception {
        String op = probe().call(42, new byte[0]);
        assertTrue(op.startsWith("REFUSED") && op.contains("unknown operation code 42"), op);
        byte[] image = HostProbe.image(archive.digest(), HostProbe.state(new VisitorAgent()));
        image[0] = 5; // the image kind code: 0 trip, 1 homecoming
        String transfer = probe().call(0, image);
        assertTrue(transfer.startsWith("REFUSED") && transfer.contains("unknown agent image kind code 5"), transfer);
        logSays("refused a call from peer 'probe'");
        logSays("unknown agent image kind code 5");
        hostStillServesAgents();
    }

    @Test
    void tamperedArchiveIsRefused() throws Exception {
        byte[] jar = archive.bytes();
        jar[jar.length / 2] ^= 0x5A;
        String answer = probe().putArchive(archive.digest(), jar);
        assertTrue(answer.startsWith("REFUSED") && answer.contains("tampered"), answer);
        logSays("but its bytes hash to");
        hostStillServesAgents();
    }

    @Test
    void stateWithAClassNotAllowedIsRefused() throws Exception {
        String answer = probe().transfer(archive.digest(), VisitorAgent.class.getName(), HostProbe.state(new VisitorAgent().extra(new AtomicLong(7))));
        assertTrue(answer.startsWith("REFUSED") && answer.contains("java.util.concurrent.atomic.AtomicLong"), answer);
        logSays("class java.util.concurrent.atomic.AtomicLong is neither the agent's own code nor on the host's allow-list");
        hostStillServesAgents();
    }

    @Test
    void depthBombIsRefused() throws Exception {
        ArrayList<Object> bomb = new ArrayList<>();
        ArrayList<Object> inner = bomb;
        for (int i = 0; i < 500; i++) {
            ArrayList<Object> next = new ArrayList<>();
            inner.add(next);
            inner = next;
        }
        String answer = probe().transfer(archive.digest(), VisitorAgent.class.getName(), HostProbe.state(new VisitorAgent().extra(bomb)));
        assertTrue(answer.startsWith("REFUSED") && answer.contains("a limit was broken (depth"), answer);
        logSays("a limit was broken (depth");
        hostStillServesAgents();
    }

    @Test
    void streamAnnouncingAHugeArrayIsRefusedBeforeItIsAllocated() throws Exception {
        int marker = 4242;
        byte[] state = HostProbe.state(new VisitorAgent().payload(marker));
        int at = indexOfLength(state, marker);
        // Announce 2^31 - 16 bytes, and send none of them.
        byte[] forged = ByteBuffer.allocate(at + 4).put(state, 0, at).putInt(Integer.MAX_VALUE - 15).array();
        String answer = probe().transfer(archive.digest(), VisitorAgent.class.getName(), forged);
        assertTrue(answer.startsWith("REFUSED") && answer.contains("array length 2147483632"), answer);
        logSays("array length 2147483632");
        hostStillServesAgents();
    }

    /** Where the payload array's 4-byte length sits: just before its {@code length} zero bytes at the end of the stream. */
    private static int indexOfLength(byte[] s, int length) {
        for (int i = 0; i + 4 + length <= s.length; i++) {
            if (ByteBuffer.wrap(s, i, 4).getInt() == length) {
                boolean zeros = true;
                for (int k = i + 4; k < i + 4 + length && zeros; k++) {
                    zeros = s[k] == 0;
                }
                if (zeros) {
                    return i;
                }
            }
        }
        throw new AssertionError("no byte[" + length + "] in the stream");
    }
}
