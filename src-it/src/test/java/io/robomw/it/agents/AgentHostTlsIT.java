package io.robomw.it.agents;

import io.robomw.agents.messaging.TestKeys;
import io.robomw.it.demo.MwProcess;
import org.junit.jupiter.api.Test;

import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertNotEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * Agent hosts that authenticate peers by mutual TLS alone (no cluster key): a dispatcher with a
 * certificate the hosts trust gets its agent's results home; one with a stranger's certificate is
 * refused.
 */
class AgentHostTlsIT {

    @Test
    void agentTravelsBetweenTlsHostsAndAStrangerIsRefused() throws Exception {
        TestKeys keys = TestKeys.create(Files.createTempDirectory(Path.of("target"), "agent-tls-"));
        Path storePassword = Files.writeString(keys.dir().resolve("store.password"), TestKeys.PASSWORD);
        String[] tls = {"--tls-keystore", keys.dir().resolve("node.p12").toAbsolutePath().toString(),
                "--tls-truststore", keys.dir().resolve("trust.p12").toAbsolutePath().toString(), "--tls-password-file",
                storePassword.toAbsolutePath().toString()};
        String world = AgentTripIT.world().toString();
        try (HostProcess a = HostProcess.start("tls-a", concat(new String[] {"--world", world, "--world-robot", "sim-1", "--speed", "4"}, tls));
             HostProcess b = HostProcess.start("tls-b", concat(new String[] {"--world", world, "--world-robot", "sim-1", "--speed", "4"}, tls))) {
            Path jar = MwProcess.CHECKOUT.resolve("examples/target/examples-0.1.0-SNAPSHOT.jar");
            try (MwProcess trusted = MwProcess.start("tls-dispatch", concat(new String[] {"dispatch", "--jar", jar.toString(),
                    "--agent", "io.robomw.examples.agents.PatrolAgent", a.address(), b.address()}, tls))) {
                assertEquals(0, trusted.waitFor(Duration.ofMinutes(1)), trusted.output());
                assertTrue(trusted.output().contains("tls-a/sim-1") && trusted.output().contains("tls-b/sim-1"), trusted.output());
            }
            String[] stranger = tls.clone();
            stranger[1] = keys.dir().resolve("stranger.p12").toAbsolutePath().toString();
            try (MwProcess refused = MwProcess.start("tls-stranger", concat(new String[] {"dispatch", "--jar", jar.toString(),
                    "--agent", "io.robomw.examples.agents.PatrolAgent", a.address()}, stranger))) {
                assertNotEquals(0, refused.waitFor(Duration.ofMinutes(1)), refused.output());
            }
        }
    }

    private static String[] concat(String[] a, String[] b) {
        String[] out = new String[a.length + b.length];
        System.arraycopy(a, 0, out, 0, a.length);
        System.arraycopy(b, 0, out, a.length, b.length);
        return out;
    }
}
