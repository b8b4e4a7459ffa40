package io.robomw.console;

import io.robomw.agents.host.AgentHost;
import io.robomw.agents.host.ClusterKey;
import io.robomw.testkit.Await;
import io.robomw.api.Agent;
import io.robomw.api.AgentRef;
import org.junit.jupiter.api.Test;

import java.time.Duration;
import java.util.List;
import java.util.concurrent.TimeUnit;

import static org.junit.jupiter.api.Assertions.assertEquals;

/** A console told of one host finds the hosts that one knows (the cluster's directory) and watches them too. */
class ConsoleDiscoveryTest {

    private static final ClusterKey KEY = ClusterKey.fromPassphrase("discovery cluster");

    /** Visits its stops and comes home. */
    public static class Hopper extends Agent {
        private static final long serialVersionUID = 1L;

        @Override
        public void run() {
            context().setResult(context().hostName());
        }
    }

    @Test
    void aHostThatMetAnotherLeadsTheConsoleToIt() throws Exception {
        try (AgentHost home = AgentHost.builder("home").clusterKey(KEY).start();
             AgentHost a = AgentHost.builder("a").clusterKey(KEY).start();
             AgentHost b = AgentHost.builder("b").clusterKey(KEY).start()) {
            Hopper hopper = new Hopper();
            hopper.itinerary().addStop(a.address()).addStop(b.address());
            AgentRef ref = home.agency().startTrip(hopper);
            assertEquals("b", ref.result().get(10, TimeUnit.SECONDS));
            Await.until("a knows b", Duration.ofSeconds(10), () -> {
                try {
                    return AgentHost.describe(a.address(), KEY, false).known().stream().anyMatch(k -> k.address().equals(b.address()));
                } catch (java.io.IOException e) {
                    return false;
                }
            });
            try (Console console = Console.builder("test").noPage().hosts(List.of(a.address())).clusterKey(KEY, false)
                    .period(Duration.ofMillis(100)).discover().start()) {
                Await.until("the console watches b too", Duration.ofSeconds(20), () -> console.watchedHosts().contains(b.address()));
                assertEquals(1, console.watchedHosts().stream().filter(b.address()::equals).count(), "once");
            }
        }
    }
}
