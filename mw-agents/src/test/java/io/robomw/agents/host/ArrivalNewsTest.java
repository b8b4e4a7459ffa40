package io.robomw.agents.host;

import io.robomw.agents.host.trip.VisitorAgent;
import io.robomw.api.AgentRef;
import io.robomw.api.AgentStatus;
import io.robomw.testkit.Await;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.extension.RegisterExtension;

import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.TimeUnit;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

/** A home learns where its agents arrived (hosts it did not send them to) from news the hosts send in batches on the agent wire. */
class ArrivalNewsTest {

    private static final ClusterKey KEY = ClusterKey.fromPassphrase("test cluster");
    private static final Duration WITHIN = Duration.ofSeconds(60);
    @RegisterExtension
    final StartedHosts hosts = new StartedHosts();

    private AgentHost host(String name) throws Exception {
        return hosts.start(AgentHost.builder(name).clusterKey(KEY));
    }

    @Test
    void theHomeSeesEveryAgentAtTheHostItMovedToOnItsOwnAndTheNewsCameOnTheWire() throws Exception {
        AgentHost home = host("home");
        AgentHost a = host("a");
        AgentHost b = host("b");
        List<AgentRef> refs = new ArrayList<>();
        for (int i = 0; i < 40; i++) {
            VisitorAgent agent = new VisitorAgent().holdUntilReleased();
            agent.itinerary().addStop(a.address()).addStop(b.address());
            refs.add(home.agency().startTrip(agent));
        }
        Await.until("40 agents held at a", WITHIN, () -> a.agents().size() == 40);
        assertEquals(0, home.wireFramesServed(), "no agent went to the home: its wire has served nothing yet");
        // Released at a, each goes on to b on its own (a holds it again there: its release is not part of its state):
        // only b's news tells the home it is there.
        for (AgentRef r : refs) {
            r.sendOnewayMessage("release");
        }
        Await.until("the home sees all 40 at b", WITHIN, () -> refs.stream().allMatch(r -> b.address().equals(r.location())),
                () -> refs.stream().map(AgentRef::location).toList().toString());
        assertEquals(40, b.agents().size());
        refs.forEach(r -> assertEquals(AgentStatus.ACTIVE, r.status()));
        long calls = home.wireFramesServed();
        assertTrue(calls >= 1 && calls <= 40, "the news came on the home's agent wire, at most one call per arrival: " + calls);
        for (AgentRef r : refs) {
            r.sendOnewayMessage("release");
        }
        for (AgentRef r : refs) {
            assertEquals(List.of("a", "b"), r.result().get(60, TimeUnit.SECONDS));
        }
    }
}
