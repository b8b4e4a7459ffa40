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
 * A simulated robot (dyn4j world, {@code platform: sim}, stepped in real time at 20× speed) served
 * by another JVM and driven through {@code Robots.remote} over TCP and over RMI.
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
        rmi = host.ask("bind rmi://127.0.0.1:0/sim-1", "BOUND").substring(6);
        Path world = Path.of(getClass().getResource("/robots/sim-world.yaml").toURI());
        host.ask("sim " + world + " sim-1 20", "SERVING sim-1");
    }

    @AfterAll
    void stop() {
        if (host != null) {
            host.close();
        }
    }

    private String address(String scheme) {
        return scheme.equals("tcp") ? tcp + "/sim-1" : rmi;
    }

    @ParameterizedTest
    @ValueSource(strings = {"tcp", "rmi"})
    void simulatedRobotIsDrivenThroughRobotsRemote(String scheme) {
        try (Robot robot = Robots.remote(address(scheme))) {
            assertEquals("sim-1", robot.name());
            assertEquals(Set.of(Capability.GROUND), robot.capabilities());
            robot.resetPose(Pose.ORIGIN);
            double before = robot.getValue(Position.FRONT, SensorType.SONAR, ReturnType.CENTIMETERS);
            robot.move(0.25, 0.2);
            double after = robot.getValue(Position.FRONT, SensorType.SONAR, ReturnType.CENTIMETERS);
            assertEquals(25.0, before - after, 3.0, "the wall in front came 25 cm closer (" + before + " -> " + after + ")");
            robot.turn(Math.PI, 1.0);
            robot.move(0.25, 0.2);
            Pose pose = robot.pose();
            assertEquals(0.0, pose.x(), 0.02);
            assertEquals(0.0, pose.y(), 0.02);
        }
    }

    @ParameterizedTest
    @ValueSource(strings = {"tcp", "rmi"})
    void remoteRobotThrowsTheSameExceptionsAsALocalOne(String scheme) {
        try (Robot robot = Robots.remote(address(scheme))) {
            UnsupportedActionException e = assertThrows(UnsupportedActionException.class, () -> robot.move(1.0, 5.0));
            assertEquals("sim-1", e.robot());
            assertThrows(UnsupportedActionException.class, () -> robot.getValue("no-such-sensor", ReturnType.METERS));
            assertThrows(UnsupportedActionException.class, () -> robot.changeAltitude(1.0, 0.5));
        }
    }
}
