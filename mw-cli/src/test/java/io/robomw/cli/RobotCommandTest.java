package io.robomw.cli;

import io.robomw.agents.messaging.MessagingNode;
import io.robomw.agents.messaging.MessagingSettings;
import io.robomw.agents.messaging.robot.RobotProtocol;
import io.robomw.agents.messaging.robot.RobotServer;
import io.robomw.api.Robot;
import io.robomw.api.Robots;
import org.junit.jupiter.api.Test;

import java.nio.file.Path;
import java.time.Duration;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

/** {@code mw robot ROBOT move|turn|get|pose|stop}: a robot file opened with its driver, and a served robot by its address. */
class RobotCommandTest {

    private static String instantFile() throws Exception {
        return Path.of(RobotCommandTest.class.getResource("/robots/instant.yaml").toURI()).toString();
    }

    @Test
    void oneCommandAtATimeToARobotFile() throws Exception {
        String file = instantFile();
        CliRun move = CliRun.mw("robot", file, "move", "0.2", "0.1");
        assertEquals(0, move.status(), move.err());
        assertTrue(move.out().contains("moved 0.2 m; pose x 0.200 m, y 0.000 m, heading 0.0°"), move.out());

        CliRun turn = CliRun.mw("robot", file, "turn", "90deg");
        assertEquals(0, turn.status(), turn.err());
        assertTrue(turn.out().contains("turned 90.0°; pose x 0.000 m, y 0.000 m, heading 90.0°"), turn.out());

        CliRun byPlace = CliRun.mw("robot", file, "get", "FRONT", "SONAR", "CM");
        assertEquals(0, byPlace.status(), byPlace.err());
        assertEquals("front sonar = 42 centimeters", byPlace.out().strip());
        CliRun byName = CliRun.mw("robot", file, "get", "sonar", "m");
        assertEquals("sonar = 0.4200 meters", byName.out().strip());

        CliRun pose = CliRun.mw("robot", file, "pose");
        assertEquals("instant-1: x 0.000 m, y 0.000 m, heading 0.0°", pose.out().strip());
        CliRun stop = CliRun.mw("robot", file, "stop");
        assertEquals(0, stop.status(), stop.err());
        assertTrue(stop.out().startsWith("instant-1 stopped"), stop.out());
    }

    @Test
    void whatTheRobotCannotDoIsOneLineAndExitTwo() throws Exception {
        String file = instantFile();
        CliRun noSensor = CliRun.mw("robot", file, "get", "BOTTOM", "LIGHT");
        assertEquals(2, noSensor.status());
        assertEquals(1, noSensor.errLines().size(), noSensor.err());
        assertTrue(noSensor.err().startsWith("mw robot get: "), noSensor.err());

        CliRun tooFast = CliRun.mw("robot", file, "move", "0.2", "5");
        assertEquals(2, tooFast.status());
        assertTrue(tooFast.err().contains("max_speed") || tooFast.err().contains("0.3"), tooFast.err());

        // Waits for the file a while (mw emulate --write-robot may still be writing it), 1 s here rather than the launcher's 30 s.
        CliRun noFile = CliRun.mwWaitingForFiles(Duration.ofSeconds(1), "robot", "nothing.yaml", "pose");
        assertEquals(2, noFile.status());
        assertTrue(noFile.err().contains("waiting up to 1s for nothing.yaml"), noFile.err());
        assertTrue(noFile.err().contains("no robot file nothing.yaml"), noFile.err());

        CliRun noVerb = CliRun.mw("robot", file);
        assertEquals(2, noVerb.status());
        assertTrue(noVerb.err().contains("(mw robot --help)"), noVerb.err());
    }

    @Test
    void aServedRobotByItsAddress() throws Exception {
        try (Robot local = Robots.open(Path.of(instantFile()));
             MessagingNode server = MessagingNode.builder("host").settings(RobotProtocol.forServer(MessagingSettings.defaults()))
                     .bind("tcp://127.0.0.1:0").build()) {
            RobotServer.serveInsecure(server, local);
            String address = server.address("tcp") + "/instant-1";
            CliRun move = CliRun.mw("robot", address, "move", "0.5", "0.2");
            assertEquals(0, move.status(), move.err());
            assertEquals(0.5, local.pose().x(), 1e-6, "the served robot moved");
            CliRun pose = CliRun.mw("robot", address, "pose");
            assertTrue(pose.out().contains("instant-1: x 0.500 m"), pose.out());
        }
    }

    @Test
    void teleopWithoutATerminalSaysSo() throws Exception {
        CliRun run = CliRun.mw("robot", instantFile(), "teleop");
        assertEquals(2, run.status());
        assertTrue(run.err().contains("needs a terminal"), run.err());
    }
}
