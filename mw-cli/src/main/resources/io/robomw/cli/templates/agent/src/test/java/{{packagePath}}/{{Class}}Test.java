package {{package}};

import io.robomw.agents.host.AgentHost;
import io.robomw.agents.host.ClusterKey;
import io.robomw.api.AgentRef;
import io.robomw.sim.Simulation;
import org.junit.jupiter.api.Test;

import java.nio.file.Path;
import java.util.List;
import java.util.concurrent.TimeUnit;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

/** The agent at an agent host whose robot is simulated, sent from a home host: both in this JVM, over RMI on 127.0.0.1. */
class {{Class}}Test {

    @Test
    void drivesTheRobotAtTheHostAndComesHomeWithItsStop() throws Exception {
        ClusterKey key = ClusterKey.fromPassphrase("a test passphrase");
        try (Simulation sim = Simulation.load(Path.of("src/test/resources/test-world.yaml"))) {
            sim.startRealTime(4);
            try (AgentHost robotHost = AgentHost.builder("robot-host").port(0).robot(sim.robot("bot")).clusterKey(key).noMessaging().start();
                 AgentHost home = AgentHost.builder("home").port(0).clusterKey(key).noMessaging().start()) {
                AgentRef ref = home.agency().dispatchClones(new {{Class}}(0.2), robotHost.address()).get(0);
                Object result = ref.result().get(60, TimeUnit.SECONDS);
                List<?> stops = (List<?>) result;
                assertEquals(1, stops.size(), String.valueOf(stops));
                assertTrue(stops.get(0).toString().startsWith("bot at robot-host drove 0.20 m"), String.valueOf(stops));
                assertEquals(0.2, sim.robot("bot").pose().x(), 0.03, "the simulated robot drove 0.2 m");
            }
        }
    }
}
