package io.robomw.it.agents;

import io.robomw.testkit.Await;
import io.robomw.agents.host.AgentHost;
import io.robomw.api.AgentRef;
import io.robomw.examples.agents.PatrolAgent;
import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

import java.nio.file.Path;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.TimeUnit;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * A durable agent host is killed (kill -9) while agents are at it and on their way to it; started
 * again on the same store, it resumes them: every agent comes home, none twice, and no stop runs
 * twice.
 */
class AgentHostCrashIT {

    @TempDir
    Path dir;
    private final List<HostProcess> hosts = new ArrayList<>();
    private AgentHost home;

    @AfterEach
    void stop() {
        if (home != null) {
            home.close();
        }
        hosts.forEach(HostProcess::close);
    }

    private HostProcess host(String name) throws Exception {
        HostProcess h = HostProcess.start(name, "--world", AgentTripIT.world().toString(), "--world-robot", "sim-1", "--speed", "1",
                "--key-file", AgentTripIT.keyFile(dir).toString(), "--store", dir.resolve(name).toString());
        hosts.add(h);
        return h;
    }

    @Test
    void hostKilledWithAgentsInFlightLosesNoneAndRunsNoStopTwice() throws Exception {
        HostProcess a = host("a");
        HostProcess b = host("b");
        HostProcess c = host("c");
        home = AgentHost.builder("crash-home").clusterKey(AgentTripIT.KEY).start();
        int n = 4;
        List<AgentRef> refs = new ArrayList<>();
        for (int i = 0; i < n; i++) {
            PatrolAgent agent = new PatrolAgent(0.1);
            agent.itinerary().addStop(a.address()).addStop(b.address()).addStop(c.address())
                    .retry(120, Duration.ofMillis(250)); // long enough for b to come back
            refs.add(home.agency().startTrip(agent));
        }
        // Kill b once it holds agents (they drive there for about a second each).
        Await.until("an agent reaches b", Duration.ofSeconds(60), () -> {
            try {
                return !AgentHost.list(b.address(), AgentTripIT.KEY, false).isEmpty();
            } catch (java.io.IOException e) {
                throw new java.io.UncheckedIOException(e);
            }
        });
        b.kill();
        b.restart();
        assertTrue(b.log().contains("resumed"), "b resumed agents from its store:\n" + b.log());
        for (AgentRef r : refs) {
            @SuppressWarnings("unchecked")
            List<PatrolAgent.Visit> visits = (List<PatrolAgent.Visit>) r.result().get(90, TimeUnit.SECONDS);
            List<String> at = visits.stream().map(PatrolAgent.Visit::host).toList();
            assertEquals("a", at.get(0), "agent " + r.id() + " visits " + at);
            assertEquals("c", at.get(at.size() - 1), "agent " + r.id() + " went on after the restart: " + at);
            long bVisits = at.stream().filter("b"::equals).count();
            assertTrue(bVisits <= 1, "the stop at b ran at most once for agent " + r.id() + ": " + at);
        }
    }
}
