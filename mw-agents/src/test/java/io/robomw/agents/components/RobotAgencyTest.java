package io.robomw.agents.components;

import io.robomw.agents.host.AgentHost;
import io.robomw.agents.host.ClusterKey;
import io.robomw.agents.host.ClusterKeyLookup;
import io.robomw.agents.host.trip.VisitorAgent;
import io.robomw.api.AgentException;
import io.robomw.api.AgentRef;
import io.robomw.api.spi.AgencyConfig;
import io.robomw.api.spi.SecretRef;
import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

import java.nio.file.Files;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.List;
import java.util.Map;
import java.util.Optional;
import java.util.concurrent.TimeUnit;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/** A robot's agency: its in-process home, the cluster key it finds, and agents sent through it. */
class RobotAgencyTest {

    private static final String PASSPHRASE = "robot agency test";

    @TempDir
    Path userHome;

    private final List<AutoCloseable> open = new ArrayList<>();

    @AfterEach
    void closeAll() throws Exception {
        for (AutoCloseable c : open) {
            c.close();
        }
    }

    private AgentHost host(String name) throws Exception {
        AgentHost h = AgentHost.builder(name).clusterKey(ClusterKey.fromPassphrase(PASSPHRASE)).start();
        open.add(h);
        return h;
    }

    private RobotAgency agency(Map<String, String> env, Optional<SecretRef> key) {
        AgencyConfig defaults = AgencyConfig.defaults("nxt-1", "nxt.yaml");
        RobotAgency a = new RobotAgency(new AgencyConfig(defaults.homeName(), defaults.bind(), 0, key, "nxt.yaml"),
                new ClusterKeyLookup(env::get, userHome));
        open.add(0, a);
        return a;
    }

    @Test
    void anAgentSentFromTheRobotRunsAtTheHostAndItsResultComesToTheRobotsHome() throws Exception {
        AgentHost a = host("a");
        RobotAgency agency = agency(Map.of(AgencyConfig.KEY_VARIABLE, PASSPHRASE), Optional.empty());
        assertEquals(Optional.empty(), agency.homeAddress(), "no home before the first use");
        AgentRef ref = agency.sendAgent(a.address(), new VisitorAgent());
        assertEquals(List.of("a"), ref.result().get(10, TimeUnit.SECONDS));
        assertTrue(agency.homeAddress().orElseThrow().endsWith("/nxt-1-home"), agency.homeAddress().toString());
    }

    @Test
    void theKeyComesFromTheDefaultFileWhenNeitherTheRobotFileNorTheEnvironmentNamesOne() throws Exception {
        AgentHost a = host("a");
        Files.createDirectories(userHome.resolve(".robomw"));
        Files.writeString(userHome.resolve(AgencyConfig.DEFAULT_KEY_FILE), PASSPHRASE + "\n");
        AgentRef ref = agency(Map.of(), Optional.empty()).sendAgent(a.address(), new VisitorAgent());
        assertEquals(List.of("a"), ref.result().get(10, TimeUnit.SECONDS));
    }

    @Test
    void withoutAnyKeyTheFirstUseSaysEveryPlaceItLooked() {
        AgentException e = assertThrows(AgentException.class,
                () -> agency(Map.of(), Optional.empty()).sendAgent("rmi://127.0.0.1:1/x", new VisitorAgent()));
        assertTrue(e.getMessage().contains(AgencyConfig.KEY_VARIABLE) && e.getMessage().contains(".robomw/cluster.key")
                && e.getMessage().contains("nxt.yaml"), e.getMessage());
    }

    @Test
    void aKeyFileTheRobotFileNamesButThatIsMissingIsNamed() {
        Path missing = userHome.resolve("no-such.key");
        AgentException e = assertThrows(AgentException.class, () -> agency(Map.of(AgencyConfig.KEY_VARIABLE, PASSPHRASE),
                Optional.of(new SecretRef(SecretRef.Kind.FILE, missing.toString(), "nxt.yaml"))).sendAgent("rmi://127.0.0.1:1/x", new VisitorAgent()));
        assertTrue(e.getMessage().contains(missing.toString()) && e.getMessage().contains("does not exist"), e.getMessage());
    }
}
