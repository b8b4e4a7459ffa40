package io.robomw.it.agents;

import io.robomw.agents.host.AgentHost;
import io.robomw.agents.host.ClusterKey;
import io.robomw.api.AgentRef;
import io.robomw.examples.agents.PatrolAgent;
import io.robomw.examples.agents.SquareSurveyAgent;
import org.junit.jupiter.api.AfterAll;
import org.junit.jupiter.api.BeforeAll;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

import java.io.Serializable;
import java.net.URISyntaxException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.List;
import java.util.Map;
import java.util.concurrent.ConcurrentHashMap;
import java.util.concurrent.TimeUnit;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * Agents whose classes exist only in the examples jar of this (sending) JVM travel to three agent
 * hosts in three other JVMs, each with its own simulated robot, drive there, read a sensor, and
 * bring their results home.
 */
class AgentTripIT {

    static final String PASSPHRASE = "integration cluster";
    static final ClusterKey KEY = ClusterKey.fromPassphrase(PASSPHRASE);

    @TempDir
    static Path dir;
    static final List<HostProcess> hosts = new ArrayList<>();
    static AgentHost home;

    @BeforeAll
    static void startHosts() throws Exception {
        assertFalse(HostProcess.middlewareOnlyClassPath().contains("examples"), "the hosts must not have the example agents");
        Path keyFile = keyFile(dir);
        // h1 and h2 take agents on their agent wire (protocol 3); h3 has none (--no-wire), so the
        // trip's last hop, and every hop to and from it, goes over RMI: both paths between processes.
        // h2 computes its AES-GCM tags with the JDK's provider, the others with the Amazon Corretto
        // Crypto Provider where it loads: calls and frames between h2 and the others cross providers.
        for (String name : List.of("h1", "h2", "h3")) {
            List<String> args = new ArrayList<>(List.of("--world", world().toString(), "--world-robot", "sim-1", "--speed", "4", "--key-file", keyFile.toString()));
            if (name.equals("h3")) {
                args.add("--no-wire");
            }
            List<String> jvm = name.equals("h2") ? List.of("-Drobomw.agents.aesGcm=jdk") : List.of();
            hosts.add(HostProcess.start(name, jvm, args.toArray(String[]::new)));
        }
        home = AgentHost.builder("it-home").clusterKey(KEY).start();
    }

    static Path keyFile(Path dir) throws Exception {
        Path keyFile = dir.resolve("cluster.key");
        Files.writeString(keyFile, PASSPHRASE + "\n");
        return keyFile;
    }

    static Path world() throws URISyntaxException {
        return Path.of(AgentTripIT.class.getResource("/robots/sim-world.yaml").toURI());
    }

    @AfterAll
    static void stopHosts() {
        if (home != null) {
            home.close();
        }
        hosts.forEach(HostProcess::close);
    }

    @Test
    void agentFromAJarVisitsThreeHostsDrivesReadsASensorAndItsResultsComeHome() throws Exception {
        PatrolAgent agent = new PatrolAgent(0.2);
        hosts.forEach(h -> agent.itinerary().addStop(h.address()));
        List<Serializable> reports = new ArrayList<>();
        AgentRef ref = home.agency().startTrip(agent);
        ref.addReportListener(reports::add);
        @SuppressWarnings("unchecked")
        List<PatrolAgent.Visit> visits = (List<PatrolAgent.Visit>) ref.result().get(60, TimeUnit.SECONDS);
        assertEquals(List.of("h1", "h2", "h3"), visits.stream().map(PatrolAgent.Visit::host).toList());
        for (PatrolAgent.Visit v : visits) {
            assertEquals("sim-1", v.robot());
            assertEquals(0.2, v.pose().x(), 0.02, "drove 0.2 m at " + v.host());
            // sim-1 starts at x = 2.0 facing the east wall of a 4 m arena: after 0.2 m it is ~1.7 m from it.
            assertEquals(1.7, v.range(), 0.15, "front range at " + v.host());
        }
        assertTrue(hosts.get(1).log().contains("received archive"), "h2 was sent the agent's code");
        assertTrue(hosts.get(0).wire().matches("127\\.0\\.0\\.1:[1-9][0-9]*"), "h1 has an agent wire: " + hosts.get(0).wire());
        assertTrue(hosts.get(2).wire().startsWith("none"), "h3 has none: " + hosts.get(2).wire());
        String h2 = hosts.get(1).log();
        assertTrue(h2.contains("AES-GCM from the JDK's provider (robomw.agents.aesGcm=jdk)"), "h2 tags with the JDK's AES-GCM");
        String os = System.getProperty("os.name").toLowerCase(java.util.Locale.ROOT);
        if (os.contains("linux") && List.of("amd64", "x86_64", "aarch64").contains(System.getProperty("os.arch"))) {
            assertTrue(hosts.get(0).log().contains("AES-GCM from AmazonCorrettoCryptoProvider"), "h1 tags with ACCP's AES-GCM, where it ships");
        }
        for (HostProcess h : hosts) {
            String log = h.log();
            assertFalse(log.contains("wrong tag") || log.contains("wrong MAC"), "no call or frame refused between providers at " + h.address());
        }
    }

    @Test
    void dispatchClonesRunsBothClonesInParallelAndReturnsBothResults() throws Exception {
        Map<String, Long> firstReport = new ConcurrentHashMap<>();
        List<AgentRef> refs = home.agency().dispatchClones(new SquareSurveyAgent(0.25), hosts.get(0).address(), hosts.get(1).address());
        for (AgentRef r : refs) {
            r.addReportListener(v -> firstReport.putIfAbsent(r.id().toString(), System.nanoTime()));
        }
        SquareSurveyAgent.Survey a = (SquareSurveyAgent.Survey) refs.get(0).result().get(60, TimeUnit.SECONDS);
        long firstDone = System.nanoTime();
        SquareSurveyAgent.Survey b = (SquareSurveyAgent.Survey) refs.get(1).result().get(60, TimeUnit.SECONDS);
        assertEquals("h1", a.host());
        assertEquals("h2", b.host());
        for (SquareSurveyAgent.Survey s : List.of(a, b)) {
            assertEquals(1.0, s.distanceDriven(), 1e-9);
            assertEquals(16, s.samples().size());
            assertTrue(s.odometryClosure() < 0.05, "square closes within 5 cm by odometry: " + s.odometryClosure());
        }
        assertEquals(2, firstReport.size(), "both clones reported while driving");
        assertTrue(firstReport.values().stream().allMatch(t -> t < firstDone), "the second clone was driving before the first finished: they ran in parallel");
    }
}
