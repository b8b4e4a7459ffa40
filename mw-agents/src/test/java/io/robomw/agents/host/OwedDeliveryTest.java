package io.robomw.agents.host;

import io.robomw.agents.host.ops.HostClient;
import io.robomw.agents.host.ops.HostWatch;
import io.robomw.agents.host.protocol.AgentImage;
import io.robomw.agents.host.protocol.Op;
import io.robomw.agents.host.code.CodeArchive;
import io.robomw.agents.host.trip.VisitorAgent;
import io.robomw.testkit.Await;
import io.robomw.testkit.Ports;
import io.robomw.api.AgentRef;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.extension.RegisterExtension;
import org.junit.jupiter.api.io.TempDir;

import java.nio.file.Path;
import java.time.Duration;
import java.time.Instant;

import java.util.List;
import java.util.Set;
import java.util.UUID;
import java.util.concurrent.ExecutionException;
import java.util.concurrent.TimeUnit;
import java.util.stream.Collectors;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * What a host owes homes that do not answer: listed with their age over the wire, dropped by an
 * operator, given up after the delivery expiry, and gone from a durable store once dropped; and an
 * operator's retract or dispose follows an agent from where it was.
 */
class OwedDeliveryTest {

    private static final ClusterKey KEY = ClusterKey.fromPassphrase("owed");
    @RegisterExtension
    final StartedHosts hosts = new StartedHosts();

    @TempDir
    Path dir;

    private AgentHost started(AgentHostBuilder b) throws Exception {
        return hosts.start(b.clusterKey(KEY));
    }


    /** Sends an agent whose home is nowhere (a closed port): its report and result stay owed. @return its id */
    private static UUID sendAgentWithAGoneHome(AgentHost to) throws Exception {
        HostProbe probe = new HostProbe(to.address(), KEY);
        CodeArchive archive = HostProbe.archiveOf(VisitorAgent.class);
        assertEquals("OK ", probe.putArchive(archive.digest(), archive.bytes()));
        byte[] image = HostProbe.image(archive.digest(), HostProbe.state(new VisitorAgent()));
        assertEquals("OK ", probe.call(Op.TRANSFER.code(), image));
        return AgentImage.decode(image).id();
    }

    /** What the console shows on a host's card: WATCH carries the deliveries owed, per home, with the oldest's time. */
    @Test
    void aWatcherSeesTheDeliveriesOwedPerHome() throws Exception {
        AgentHost a = started(AgentHost.builder("a"));
        HostWatch watch = HostWatch.of(a.address(), KEY, false, "test-console");
        assertEquals(List.of(), watch.poll().owed(), "nothing owed yet, and the host says so");
        Instant before = Instant.now();
        sendAgentWithAGoneHome(a);
        try (HostClient operator = new HostClient(KEY, false, 10_000)) {
            Await.until("the report, the visits and the result are owed", Duration.ofSeconds(10), () -> owedAt(operator, a).size() == 3);
            List<HostWatch.Owed> owed = watch.poll().owed();
            assertEquals(1, owed.size(), "one home: " + owed);
            assertEquals("rmi://127.0.0.1:1/probe-home", owed.get(0).home());
            assertEquals(3, owed.get(0).count());
            assertTrue(owed.get(0).oldestMillis() >= before.minusSeconds(1).toEpochMilli() && owed.get(0).oldestMillis() <= System.currentTimeMillis(),
                    "owed since " + owed.get(0).oldestMillis());
            operator.dropOwed(a.address(), OwedSelector.all());
            assertEquals(List.of(), watch.poll().owed(), "dropped: nothing owed");
        }
    }

    @Test
    void deliveriesOwedToAGoneHomeAreListedWithTheirAgeAndTriesAndDroppedByTheOperator() throws Exception {
        AgentHost a = started(AgentHost.builder("a").port(Ports.free()).store(dir.resolve("a")));
        Instant before = Instant.now();
        UUID id = sendAgentWithAGoneHome(a);
        HostClient operator = new HostClient(KEY, false, 10_000);
        Await.until("the report, the visits and the result are owed and have been tried", Duration.ofSeconds(10), () -> {
            List<OwedDelivery> owed = owedAt(operator, a);
            return owed.size() == 3 && owed.get(0).attempts() > 0; // in order: the result waits behind the report
        });
        List<OwedDelivery> owed = operator.owed(a.address());
        assertEquals(Set.of("REPORT", "VISITS", "RESULT"), owed.stream().map(OwedDelivery::kind).collect(Collectors.toSet()));
        for (OwedDelivery d : owed) {
            assertEquals(id, d.agent());
            assertEquals("rmi://127.0.0.1:1/probe-home", d.home());
            assertTrue(!d.owedSince().isBefore(before.minusSeconds(1)) && !d.owedSince().isAfter(Instant.now()), "owed since " + d.owedSince());
        }
        assertEquals("REPORT", owed.get(0).kind(), "the oldest first");
        assertTrue(owed.get(0).lastError().contains("127.0.0.1:1"), "the last error says why: " + owed.get(0).lastError());

        assertEquals(0, operator.dropOwed(a.address(), OwedSelector.agent(UUID.randomUUID())).size(), "another agent's: nothing dropped");
        assertEquals(3, operator.dropOwed(a.address(), OwedSelector.home("rmi://127.0.0.1:1/probe-home")).size());
        assertTrue(operator.owed(a.address()).isEmpty());

        int port = HostAddress.parse(a.address()).port();
        a.close();
        AgentHost again = hosts.restart(AgentHost.builder("a").port(port).store(dir.resolve("a")).clusterKey(KEY));
        assertTrue(again.owed().isEmpty(), "dropped deliveries are not owed again after a restart: " + again.owed());
    }

    @Test
    void aDeliveryOwedLongerThanTheExpiryIsGivenUpAndNotResumed() throws Exception {
        DeliveryPolicy quick = DeliveryPolicy.defaults().withExpiry(Duration.ofMillis(300)).withMaxBackoff(Duration.ofMillis(100));
        AgentHost a = started(AgentHost.builder("a").port(Ports.free()).store(dir.resolve("a")).deliveryPolicy(quick));
        sendAgentWithAGoneHome(a);
        // The transfer's OK means a holds it; once it is gone from a's agents its result has been owed.
        Await.until("the agent ended its trip", Duration.ofSeconds(10), () -> a.agents().isEmpty());
        Await.until("the deliveries are given up after the expiry", Duration.ofSeconds(10), () -> a.owed().isEmpty());
        int port = HostAddress.parse(a.address()).port();
        a.close();
        AgentHost again = hosts.restart(AgentHost.builder("a").port(port).store(dir.resolve("a")).clusterKey(KEY));
        assertTrue(again.owed().isEmpty(), "given-up deliveries are not owed again after a restart: " + again.owed());
    }

    @Test
    void anOwedDeliveryKeepsItsAgeAcrossARestart() throws Exception {
        AgentHost a = started(AgentHost.builder("a").port(Ports.free()).store(dir.resolve("a")));
        sendAgentWithAGoneHome(a);
        Await.until("the result is owed", Duration.ofSeconds(10), () -> a.owed().size() == 3);
        Instant since = a.owed().get(0).owedSince();
        int port = HostAddress.parse(a.address()).port();
        a.close();
        AgentHost again = hosts.restart(AgentHost.builder("a").port(port).store(dir.resolve("a")).clusterKey(KEY));
        assertEquals(3, again.owed().size());
        assertEquals(since, again.owed().get(0).owedSince());
    }

    @Test
    void anOperatorsDisposeFollowsTheAgentFromWhereItWas() throws Exception {
        AgentHost home = started(AgentHost.builder("home"));
        AgentHost a = started(AgentHost.builder("a"));
        AgentHost b = started(AgentHost.builder("b"));
        VisitorAgent agent = new VisitorAgent().holdUntilReleased();
        agent.itinerary().addStop(a.address()).addStop(b.address());
        AgentRef ref = home.agency().startTrip(agent);
        ref.sendMessage("release", Duration.ofSeconds(5));
        Await.until("the agent is at b", Duration.ofSeconds(10), () -> !b.agents().isEmpty());

        HostClient.Taken taken = new HostClient(KEY, false, 10_000).dispose(a.address(), ref.id());
        assertEquals(b.address(), taken.host());
        assertEquals(1, taken.hops());
        // not released: the dispose interrupts the agent's hold at b
        ExecutionException e = assertThrows(ExecutionException.class, () -> ref.result().get(10, TimeUnit.SECONDS));
        assertTrue(e.getCause().getMessage().contains("disposed"), e.getCause().getMessage());
    }

    @Test
    void anOperatorsRetractOfAnAgentNoHostKnowsSaysSo() throws Exception {
        AgentHost a = started(AgentHost.builder("a"));
        UUID nobody = UUID.randomUUID();
        java.io.IOException e = assertThrows(java.io.IOException.class, () -> new HostClient(KEY, false, 10_000).retract(a.address(), nobody));
        assertTrue(e.getMessage().contains(nobody.toString()) && e.getMessage().contains("not at " + a.address()), e.getMessage());
    }

    private static List<OwedDelivery> owedAt(HostClient operator, AgentHost h) {
        try {
            return operator.owed(h.address());
        } catch (java.io.IOException e) {
            throw new AssertionError(e);
        }
    }
}
