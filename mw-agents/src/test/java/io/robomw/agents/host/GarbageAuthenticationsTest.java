package io.robomw.agents.host;

import io.robomw.agents.host.rmi.AgentHostRemote;
import io.robomw.agents.host.rmi.HostSockets;
import io.robomw.agents.host.rmi.Session;
import io.robomw.testkit.LogLines;
import io.robomw.agents.host.code.CodeArchive;
import org.junit.jupiter.api.Test;

import io.robomw.testkit.Await;

import java.rmi.RemoteException;
import java.rmi.registry.LocateRegistry;
import java.time.Duration;
import java.util.List;
import java.util.Random;
import java.util.regex.Matcher;
import java.util.regex.Pattern;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * A flood of garbage {@code authenticate()} calls must not flood the host's log (issue 15: 200
 * calls logged 200 WARN lines, some reading "malformed authentication request: null"): refusals
 * are logged at most once a second with a count of the others, each in words, and the host still
 * serves a peer that proves the key.
 */
class GarbageAuthenticationsTest {

    private static final ClusterKey KEY = ClusterKey.fromPassphrase("garbage authentications");
    private static final int CALLS = 200;

    @Test
    void twoHundredGarbageAuthenticationsLogAFewLinesInWordsAndTheHostStillServes() throws Exception {
        try (AgentHost host = AgentHost.builder("flooded").clusterKey(KEY).start(); LogLines log = new LogLines()) {
            HostAddress a = HostAddress.parse(host.address());
            AgentHostRemote stranger = (AgentHostRemote) LocateRegistry.getRegistry(a.host(), a.port(), new HostSockets.Client(a.host(), false, 10_000))
                    .lookup(a.name());
            Random random = new Random(15);
            long start = System.nanoTime();
            for (int i = 0; i < CALLS; i++) {
                byte[] answer = stranger.authenticate(garbage(i, random));
                assertEquals(Session.AUTH_REFUSED, answer[0], "garbage " + i + " is refused");
            }
            long elapsedSeconds = (System.nanoTime() - start) / 1_000_000_000L;

            List<String> refusals = log.containing("host flooded: refused peer");
            // One line at once, then at most one a second; one more for a line begun at a second's edge.
            assertTrue(!refusals.isEmpty() && refusals.size() <= elapsedSeconds + 2,
                    refusals.size() + " refusal lines for " + CALLS + " calls in " + elapsedSeconds + " s, the first: " + refusals.stream().limit(3).toList());
            for (String line : refusals) {
                assertTrue(!line.contains(": null") && !line.endsWith("null"), "each refusal says what was wrong: " + line);
            }

            // A line after the flood (a second or more after the last one) accounts for it: each garbage
            // call was either logged on a line of its own or counted by a later line.
            Await.until("a refusal line after the flood", Duration.ofSeconds(30), () -> {
                try {
                    stranger.authenticate(new byte[0]);
                } catch (RemoteException e) {
                    throw new AssertionError("the host stopped answering", e);
                }
                return log.containing("host flooded: refused peer").size() > refusals.size();
            });
            List<String> all = log.containing("host flooded: refused peer");
            long counted = 0;
            for (String line : all) {
                Matcher count = Pattern.compile("\\(and (\\d+) more like it").matcher(line);
                counted += count.find() ? Long.parseLong(count.group(1)) : 0;
            }
            assertTrue(all.size() - 1 + counted >= CALLS,
                    "the lines and their counts account for the " + CALLS + " garbage calls: " + (all.size() - 1) + " lines and "
                            + counted + " counted, the last: " + all.get(all.size() - 1));

            HostProbe peer = new HostProbe(host.address(), KEY);
            String answer = peer.putArchive(CodeArchive.Digest.of(new byte[] {1}), new byte[] {2});
            assertTrue(answer.startsWith("REFUSED"), "a peer with the key is authenticated and its call answered: " + answer);
        }
    }

    /** Empty, cut after the version, wrong version, random bytes and a right-sized request of random bytes, in turn. */
    private static byte[] garbage(int i, Random random) {
        byte[] b = switch (i % 5) {
            case 0 -> new byte[0];
            case 1 -> new byte[] {(byte) Session.PROTOCOL_VERSION};
            case 2 -> new byte[] {(byte) 0x7f, 1, 2, 3};
            case 3 -> new byte[1 + random.nextInt(300)];
            default -> new byte[2 + 2 + 5 + 3 * 32];
        };
        if (i % 5 >= 3) {
            random.nextBytes(b);
            if (i % 5 == 4) {
                b[0] = (byte) Session.PROTOCOL_VERSION;
                b[1] = 1;
                b[2] = 0;
                b[3] = 5;
            }
        }
        return b;
    }
}
