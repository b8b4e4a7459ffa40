package io.robomw.agents.host;

import io.robomw.agents.host.ops.HostWatch;
import io.robomw.agents.host.trip.VisitorAgent;
import io.robomw.testkit.Await;
import io.robomw.testkit.Ports;
import io.robomw.api.AgentRef;
import io.robomw.api.AgentStatus;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.extension.RegisterExtension;

import java.io.IOException;
import java.time.Duration;

import java.util.List;
import java.util.concurrent.CopyOnWriteArrayList;
import java.util.concurrent.atomic.AtomicReference;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/** A watcher (the console) sees a host's agents, their itineraries and what happens to them, and can retract one it did not launch. */
class HostWatchTest {

    private static final ClusterKey KEY = ClusterKey.fromPassphrase("watch cluster");
    private static final Duration WITHIN = Duration.ofSeconds(10);
    @RegisterExtension
    final StartedHosts hosts = new StartedHosts();

    private AgentHost host(String name) throws Exception {
        return hosts.start(AgentHost.builder(name).clusterKey(KEY));
    }


    @Test
    void aWatcherAsksWhoTheHostIsOverItsOwnSessionHoweverOftenItAsks() throws Exception {
        AgentHost a = host("a");
        try (HostWatch watch = HostWatch.of(a.address(), KEY, false, "test-console")) {
            watch.poll();
            int sessions = a.sessionsKept();
            for (int i = 0; i < 5; i++) {
                HostDescription d = watch.describe();
                assertEquals("a", d.name());
                assertEquals(a.address(), d.address());
            }
            watch.poll();
            assertEquals(sessions, a.sessionsKept(), "no new session for each question");
        }
    }

    @Test
    void aWatcherSeesTheAgentItsItineraryAndItsReportThenRetractsItHome() throws Exception {
        AgentHost home = host("home");
        AgentHost a = host("a");
        AgentHost b = host("b");
        VisitorAgent agent = new VisitorAgent().holdUntilReleased();
        agent.itinerary().addStop(a.address()).addStop(b.address());
        AgentRef ref = home.agency().startTrip(agent);
        HostWatch watch = HostWatch.of(a.address(), KEY, false, "test-console");
        List<HostWatch.Event> events = new CopyOnWriteArrayList<>();
        AtomicReference<HostWatch.Snapshot> last = new AtomicReference<>();
        Await.until("agent listed at a with its report", WITHIN, () -> {
            HostWatch.Snapshot s = poll(watch);
            if (s == null) {
                return false;
            }
            last.set(s);
            events.addAll(s.events());
            return !s.agents().isEmpty() && events.stream().anyMatch(e -> e.kind().equals("report"));
        });
        HostWatch.Snapshot s = last.get();
        assertEquals("a", s.name());
        assertEquals("", s.robot());
        assertTrue(s.owed() != null, "a host reports what it owes (the report on its way home may be listed)");
        HostWatch.Agent seen = s.agents().get(0);
        assertEquals(ref.id(), seen.id());
        assertEquals(VisitorAgent.class.getName(), seen.className());
        assertEquals(home.address(), seen.home());
        assertEquals(List.of(a.address(), b.address()), seen.itinerary().stream().map(HostWatch.Stop::host).toList());
        assertEquals(0, seen.current(), "at its first stop");
        assertTrue(events.stream().anyMatch(e -> e.kind().equals("arrived") && e.agent().equals(ref.id())), "arrival: " + events);
        assertTrue(events.stream().anyMatch(e -> e.kind().equals("report") && e.detail().equals("at a")), "report text: " + events);

        // a retract means now: the agent's wait for "release" is interrupted, no message needed
        assertEquals(a.address(), watch.retract(a.address(), ref.id()));
        Await.until("the agent is home, retracted", WITHIN, () -> ref.status() == AgentStatus.RETRACTED);
        Await.until("a tells the watcher it went home", WITHIN, () -> {
            HostWatch.Snapshot later = poll(watch);
            if (later != null) {
                events.addAll(later.events());
            }
            return events.stream().anyMatch(e -> e.kind().equals("retracted"));
        });
        assertTrue(b.agents().isEmpty(), "it never went on to b");
        long seqs = events.stream().map(HostWatch.Event::seq).distinct().count();
        assertEquals(events.size(), seqs, "no event twice: " + events);
    }

    @Test
    void anAgentGoingRoundAtOneHostStaysListedThere() throws Exception {
        AgentHost home = host("home");
        AgentHost b = host("b");
        VisitorAgent agent = new VisitorAgent().holdUntilReleased();
        agent.itinerary().repeat(3);
        AgentRef ref = home.agency().sendAgent(b.address(), agent);
        Await.until("listed at b", WITHIN, () -> !b.agents().isEmpty());
        ref.sendMessage("release", Duration.ofSeconds(5));
        Await.until("on its second round at b", WITHIN, () -> b.agents().stream().anyMatch(a -> a.hop() >= 2));
        assertEquals(1, b.agents().size(), "the agent, once: its new copy replaced the old one");
        ref.sendMessage("release", Duration.ofSeconds(5));
        Await.until("on its third round", WITHIN, () -> b.agents().stream().anyMatch(a -> a.hop() >= 3));
        ref.sendMessage("release", Duration.ofSeconds(5));
        assertEquals(List.of("b", "b", "b"), ref.result().get(10, java.util.concurrent.TimeUnit.SECONDS));
    }

    @Test
    void aWatcherWithoutTheClusterKeyIsRefused() throws Exception {
        AgentHost a = host("a");
        HostWatch stranger = HostWatch.of(a.address(), ClusterKey.fromPassphrase("not ours"), false, "stranger");
        IOException e = assertThrows(IOException.class, stranger::poll);
        assertTrue(e.getMessage().contains("refused"), e.getMessage());
    }

    @Test
    void aHostThatIsDownFailsThePollAndIsWatchedAgainWhenItIsBack() throws Exception {
        int port = Ports.free();
        AgentHost a = hosts.start(AgentHost.builder("a").port(port).clusterKey(KEY));
        String address = a.address();
        HostWatch watch = HostWatch.of(address, KEY, false, "test-console");
        assertEquals("a", watch.poll().name());
        a.close();
        IOException down = assertThrows(IOException.class, watch::poll);
        assertTrue(down.getMessage().contains(address), down.getMessage());
        // Back on the same port, as a restarted host is (the closed one's listening socket may take a moment to be
        // released by RMI: seen once in CI).
        hosts.restart(AgentHost.builder("a").port(port).clusterKey(KEY));
        Await.until("the restarted host answers", WITHIN, () -> poll(watch) != null);
    }

    @Test
    void aMalformedAnswerIsAClearError() {
        IOException version = assertThrows(IOException.class, () -> HostWatch.decode("rmi://x:1/x", new byte[] {9}, 0));
        assertTrue(version.getMessage().contains("format version 9"), version.getMessage());
        IOException cut = assertThrows(IOException.class, () -> HostWatch.decode("rmi://x:1/x", new byte[] {1, 1, 0, 0, 0, 50, 0}, 0));
        assertTrue(cut.getMessage().contains("section (tag 1) of 50 bytes"), cut.getMessage());
        IOException noHost = assertThrows(IOException.class, () -> HostWatch.decode("rmi://x:1/x", new byte[] {1, 9, 0, 0, 0, 0}, 0));
        assertTrue(noHost.getMessage().contains("without its host section"), noHost.getMessage());
        IOException hugeCount = assertThrows(IOException.class,
                () -> HostWatch.decode("rmi://x:1/x", new byte[] {1, 2, 0, 0, 0, 4, 0x7f, 0, 0, 0}, 0));
        assertTrue(hugeCount.getMessage().contains("agents in 0 bytes"), hugeCount.getMessage());
    }

    private static HostWatch.Snapshot poll(HostWatch w) {
        try {
            return w.poll();
        } catch (IOException e) {
            return null;
        }
    }
}
