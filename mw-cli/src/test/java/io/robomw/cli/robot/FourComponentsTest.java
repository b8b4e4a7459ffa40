package io.robomw.cli.robot;

import io.robomw.agents.host.AgentHost;
import io.robomw.agents.host.ClusterKey;
import io.robomw.agents.host.trip.VisitorAgent;
import io.robomw.testkit.Await;
import io.robomw.agents.messaging.MessagingNode;
import io.robomw.agents.messaging.MessagingSettings;
import io.robomw.agents.messaging.robot.RobotProtocol;
import io.robomw.agents.messaging.robot.RobotServer;
import io.robomw.api.Message;
import io.robomw.api.Robot;
import io.robomw.api.Robots;
import io.robomw.api.spi.AgencyConfig;
import io.robomw.api.spi.PlatformServices;
import io.robomw.api.spi.SecretRef;
import io.robomw.config.robot.ConfiguredRobot;
import io.robomw.sim.Simulation;
import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.BeforeEach;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.Optional;
import java.util.concurrent.CopyOnWriteArrayList;
import java.util.concurrent.TimeUnit;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * Every robot has the paper's four components linked: a robot opened from its file, a simulated
 * one and a remote one move and sense as before, and also publish, send and receive messages and
 * send agents, through the providers mw-agents puts on the class path.
 */
class FourComponentsTest {

    private static final String PASSPHRASE = "four components";

    @TempDir
    Path dir;

    private final List<AutoCloseable> open = new ArrayList<>();
    private AgentHost host;
    private MessagingNode peer;
    private final List<Message> received = new CopyOnWriteArrayList<>();

    @BeforeEach
    void start() throws Exception {
        Files.writeString(dir.resolve("cluster.key"), PASSPHRASE);
        host = opened(AgentHost.builder("lab").clusterKey(ClusterKey.fromPassphrase(PASSPHRASE)).start());
        peer = opened(MessagingNode.builder("peer").bind("tcp://127.0.0.1:0").build());
        peer.addMessageListener("news", null, received::add);
        peer.subscribeMessage("news", null);
    }

    @AfterEach
    void closeAll() throws Exception {
        for (AutoCloseable c : open) {
            c.close();
        }
    }

    private <T extends AutoCloseable> T opened(T c) {
        open.add(0, c);
        return c;
    }

    private Path robotFile() throws Exception {
        String base = Files.readString(Path.of(getClass().getResource("/robots/instant.yaml").toURI()));
        Path file = dir.resolve("instant.yaml");
        Files.writeString(file, base + """
                messaging:
                  connect: %s
                agency:
                  key_file: cluster.key
                """.formatted(peer.address("tcp")));
        return file;
    }

    @Test
    void aRobotOpenedFromItsFilePublishesToThePeersItsFileConnectsTo() throws Exception {
        try (Robot robot = opened(Robots.open(robotFile()))) {
            robot.move(0.1, 0.1);
            MessagingNode node = ((io.robomw.agents.components.RobotMessaging) ((ConfiguredRobot) robot).messaging()).node();
            Await.until("the peer's subscription reaches the robot", Duration.ofSeconds(10), () -> node.subscriberCount("news") == 1);
            robot.publishMessage("news", "moved", "read", null);
            Await.until("the robot's publication reaches the peer", Duration.ofSeconds(10), () -> received.size() == 1);
            assertEquals("instant-1", received.get(0).sender());
        }
    }

    @Test
    void aRobotOpenedFromItsFileSendsAnAgentAndItsResultComesHome() throws Exception {
        try (Robot robot = opened(Robots.open(robotFile()))) {
            assertEquals(List.of("lab"), robot.sendAgent(host.address(), new VisitorAgent()).result().get(10, TimeUnit.SECONDS));
        }
    }

    @Test
    void aSimulatedRobotHasMessagingToo() throws Exception {
        try (Simulation sim = Simulation.load(Path.of("..", "examples", "worlds", "arena.yaml"))) {
            Robot robot = sim.robots().get(0);
            List<Message> direct = new CopyOnWriteArrayList<>();
            peer.addMessageListener("direct", null, direct::add);
            robot.sendMessage("peer", peer.address("tcp"), null, "direct", "hello", "greet");
            Await.until("the simulated robot's message reaches the peer", Duration.ofSeconds(10), () -> !direct.isEmpty());
            assertEquals(robot.name(), direct.get(0).sender());
        }
    }

    @Test
    void aRemoteRobotSendsAgentsThroughThisProgramsOwnHome() throws Exception {
        Robot local = opened(Robots.open(Path.of(getClass().getResource("/robots/instant.yaml").toURI())));
        MessagingNode server = opened(MessagingNode.builder("server").settings(RobotProtocol.forServer(MessagingSettings.defaults()))
                .bind("tcp://127.0.0.1:0").build());
        opened(RobotServer.serveInsecure(server, local));
        AgencyConfig agency = new AgencyConfig("remote-home", "127.0.0.1", 0,
                Optional.of(new SecretRef(SecretRef.Kind.FILE, dir.resolve("cluster.key").toString(), "test")), "test");
        try (Robot remote = opened(Robots.remote(server.address("tcp") + "/instant-1", PlatformServices.none().with(AgencyConfig.class, agency)))) {
            remote.move(0.1, 0.1);
            assertEquals(List.of("lab"), remote.sendAgent(host.address(), new VisitorAgent()).result().get(10, TimeUnit.SECONDS));
        }
    }
}
