package io.robomw.cli.robot;

import io.robomw.agents.messaging.MessagingNode;
import io.robomw.agents.messaging.MessagingSettings;
import io.robomw.agents.messaging.robot.RobotProtocol;
import io.robomw.agents.messaging.robot.RobotServer;
import io.robomw.api.Capability;
import io.robomw.api.Pose;
import io.robomw.api.Position;
import io.robomw.api.ReturnType;
import io.robomw.api.Robot;
import io.robomw.api.RobotLinkException;
import io.robomw.api.Robots;
import io.robomw.api.SensorType;
import io.robomw.api.UnsupportedActionException;
import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.BeforeEach;
import org.junit.jupiter.params.ParameterizedTest;
import org.junit.jupiter.params.provider.ValueSource;
import org.junit.jupiter.api.Test;

import java.nio.file.Path;
import java.time.Duration;
import java.util.Set;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/** A ConfiguredRobot on the instant test platform, served over TCP and RMI and driven through Robots.remote. */
class RemoteRobotTest {

    private Robot local;
    private MessagingNode server;

    @BeforeEach
    void serve() throws Exception {
        local = Robots.open(Path.of(getClass().getResource("/robots/instant.yaml").toURI()));
        server = MessagingNode.builder("host").settings(RobotProtocol.forServer(MessagingSettings.defaults()))
                .bind("tcp://127.0.0.1:0").bind("rmi://127.0.0.1:0/instant-1").build();
        RobotServer.serveInsecure(server, local);
    }

    @AfterEach
    void stop() {
        server.close();
        local.close();
    }

    @ParameterizedTest
    @ValueSource(strings = {"tcp", "rmi"})
    void remoteRobotMovesTurnsAndSenses(String scheme) {
        String address = scheme.equals("tcp") ? server.address("tcp") + "/instant-1" : server.address("rmi");
        try (Robot robot = Robots.remote(address)) {
            assertEquals("instant-1", robot.name());
            assertEquals(Set.of(Capability.GROUND), robot.capabilities());
            assertEquals("sonar", robot.sensors().get(0).name());
            robot.move(0.5, 0.2);
            robot.turn(Math.PI / 2, 1.0);
            assertEquals(42.0, robot.getValue(Position.FRONT, SensorType.SONAR, ReturnType.CENTIMETERS), 1e-9);
            assertEquals(0.42, robot.getValue("sonar", ReturnType.METERS), 1e-9);
            Pose pose = robot.pose();
            assertEquals(0.5, pose.x(), 1e-6);
            assertEquals(Math.PI / 2, pose.heading(), 1e-6);
        }
    }

    @Test
    void remoteRobotThrowsWhatALocalOneWould() {
        try (Robot robot = Robots.remote(server.address("tcp") + "/instant-1")) {
            UnsupportedActionException tooFast = assertThrows(UnsupportedActionException.class, () -> robot.move(1.0, 9.0));
            assertEquals("instant-1", tooFast.robot());
            assertTrue(tooFast.getMessage().contains("above its maximum"), tooFast.getMessage());
            assertThrows(UnsupportedActionException.class, () -> robot.getValue(Position.BACK, SensorType.SONAR, ReturnType.CENTIMETERS));
            assertThrows(UnsupportedActionException.class, () -> robot.changeAltitude(1, 1));
        }
    }

    @Test
    void unreachableRemoteRobotFailsWithALinkError() {
        String address = server.address("tcp") + "/instant-1";
        Robot robot = Robots.remote(address);
        server.close();
        assertThrows(RobotLinkException.class, () -> robot.move(0.1, 0.1));
        robot.close();
    }

    @Test
    void unknownRobotNameIsRefused() {
        RobotLinkException e = assertThrows(RobotLinkException.class, () -> Robots.remote(server.address("tcp") + "/nobody"));
        assertTrue(e.getMessage().contains("nobody"), e.getMessage());
    }

    @Test
    void callsAreBoundedByTheReplyTimeout() {
        assertEquals(Duration.ofSeconds(5), RobotProtocol.forClient(MessagingSettings.defaults()).replyTimeout());
    }
}
