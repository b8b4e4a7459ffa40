package io.robomw.agents.host;

import io.robomw.agents.host.trip.NumberedReporter;
import io.robomw.testkit.Await;
import io.robomw.testkit.Ports;
import io.robomw.api.AgentRef;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.extension.RegisterExtension;
import org.junit.jupiter.api.io.TempDir;

import java.io.Serializable;
import java.nio.file.Path;
import java.time.Duration;

import java.util.List;
import java.util.concurrent.CopyOnWriteArrayList;
import java.util.concurrent.TimeUnit;

import static org.junit.jupiter.api.Assertions.assertEquals;

/**
 * An agent resumed from a durable store numbers its reports past the ones it sent before the host
 * stopped, so its home (which drops numbers it has seen) takes every later report.
 */
class ResumedNumberingTest {

    private static final ClusterKey KEY = ClusterKey.fromPassphrase("numbering");
    @RegisterExtension
    final StartedHosts hosts = new StartedHosts();

    @TempDir
    Path dir;

    private AgentHost started(AgentHostBuilder b) throws Exception {
        return hosts.start(b.clusterKey(KEY));
    }


    @Test
    void reportsAfterAResumeMidStopReachTheHomeAndNoneIsTakenTwice() throws Exception {
        AgentHost home = started(AgentHost.builder("home"));
        AgentHost a = started(AgentHost.builder("a").port(Ports.free()).store(dir.resolve("a")).stopGrace(Duration.ZERO));
        AgentHost b = started(AgentHost.builder("b"));
        NumberedReporter agent = new NumberedReporter("a");
        agent.itinerary().addStop(a.address()).addStop(b.address());
        AgentRef ref = home.agency().startTrip(agent);
        List<Serializable> reports = new CopyOnWriteArrayList<>();
        ref.addReportListener(reports::add);
        ref.sendMessage("go", Duration.ofSeconds(10));
        Await.until("the three reports from a are home", Duration.ofSeconds(10), () -> reports.size() == 3);

        int port = HostAddress.parse(a.address()).port();
        a.close(); // interrupts the stop: the store says it had started
        hosts.restart(AgentHost.builder("a").port(port).store(dir.resolve("a")).clusterKey(KEY));

        assertEquals("done", ref.result().get(30, TimeUnit.SECONDS));
        assertEquals(List.of("a early 1", "a early 2", "a early 3", "b early 1", "b early 2", "b early 3"), reports);
    }
}
