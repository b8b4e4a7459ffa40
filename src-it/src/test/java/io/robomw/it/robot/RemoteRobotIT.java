package io.robomw.it.robot;

import io.robomw.api.Capability;
import io.robomw.api.Pose;
import io.robomw.api.Position;
import io.robomw.api.ReturnType;
import io.robomw.api.Robot;
import io.robomw.api.Robots;
import io.robomw.api.SensorType;
import io.robomw.api.UnsupportedActionException;
import io.robomw.it.messaging.PeerProcess;
import org.junit.jupiter.api.AfterAll;
import org.junit.jupiter.api.BeforeAll;
import org.junit.jupiter.api.TestInstance;
import org.junit.jupiter.params.ParameterizedTest;
import org.junit.jupiter.params.provider.ValueSource;

import java.nio.file.Path;
import java.util.List;
import java.util.Set;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;

/**
 * A robot served by another JVM, driven through {@code Robots.remote} over TCP and RMI. The served
 * robot is a real ConfiguredRobot from a YAML description, on the instant test platform.
 */
@TestInstance(TestInstance.Lifecycle.PER_CLASS)
class RemoteRobotIT {

    private PeerProcess host;
    private String tcp;
    private String rmi;

    @BeforeAll
    void serve() throws Exception {
        host = PeerProcess.peer("robot-host", List.of());
        tcp = host.ask("bind tcp://127.0.0.1:0", "BOUND").substring(6);
        rmi = host.ask("bind rmi://127.0.0.1:0/instant-1", "BOUND").substring(6);
        Path yaml = Path.of(getClass().getResource("/robots/instant.yaml").toURI());
        host.ask("robot " + yaml, "SERVING instant-1");
    }

    @AfterAll
    void stop() {
        if (host != null) {
            host.close();
        }
    }

    private String address(String scheme) {
        return scheme.equals("tcp") ? tcp + "/instant-1" : rmi;
    }

    @ParameterizedTest
    @ValueSource(strings = {"tcp", "rmi"})
    void remoteRobotIsDrivenThroughRobotsRemote(String scheme) {
        try (Robot robot = Robots.remote(address(scheme))) {
            assertEquals("instant-1", robot.name());
            assertEquals(Set.of(Capability.GROUND), robot.capabilities());
            robot.resetPose(Pose.ORIGIN);
            robot.move(0.25, 0.2);
            robot.turn(Math.PI, 1.0);
            robot.move(0.25, 0.2);
            assertEquals(42.0, robot.getValue(Position.FRONT, SensorType.SONAR, ReturnType.CENTIMETERS), 1e-9);
            Pose pose = robot.pose();
            assertEquals(0.0, pose.x(), 1e-6);
            assertEquals(0.0, pose.y(), 1e-6);
        }
    }

    @ParameterizedTest
    @ValueSource(strings = {"tcp", "rmi"})
    void remoteRobotThrowsTheSameExceptionsAsALocalOne(String scheme) {
        try (Robot robot = Robots.remote(address(scheme))) {
            UnsupportedActionException e = assertThrows(UnsupportedActionException.class, () -> robot.move(1.0, 5.0));
            assertEquals("instant-1", e.robot());
            assertThrows(UnsupportedActionException.class, () -> robot.getValue("no-such-sensor", ReturnType.METERS));
            assertThrows(UnsupportedActionException.class, () -> robot.changeAltitude(1.0, 0.5));
        }
    }
}
