package io.robomw.sim.emulator.ft.txt;

import io.robomw.config.description.DifferentialDrive;
import io.robomw.config.description.RobotDescription;
import io.robomw.config.description.RobotDescriptionLoader;
import io.robomw.config.description.SensorSpec;
import io.robomw.platform.ft.txt.TxtPorts;
import org.junit.jupiter.api.Test;

import java.nio.file.Path;
import java.util.Map;

import static org.junit.jupiter.api.Assertions.assertEquals;

/** examples/robots/ft-txt.yaml loads, wires the TXT as documented, and has the NXT robot's geometry. */
class TxtExampleRobotTest {

    private static final Path EXAMPLES = Path.of("..", "examples", "robots");

    @Test
    void shouldDescribeTheNxtGeometryOnTheTxtsPortsAndEncoders() {
        RobotDescription txt = new RobotDescriptionLoader().load(EXAMPLES.resolve("ft-txt.yaml"));
        RobotDescription nxt = new RobotDescriptionLoader().load(EXAMPLES.resolve("nxt-two-wheeled.yaml"));
        assertEquals("ft-txt", txt.platform());
        assertEquals("192.168.7.2", txt.connection().requireText("host"));
        DifferentialDrive t = txt.drive().orElseThrow();
        DifferentialDrive n = nxt.drive().orElseThrow();
        assertEquals(n.wheelDiameter(), t.wheelDiameter());
        assertEquals(n.trackWidth(), t.trackWidth());
        assertEquals(n.gearRatio(), t.gearRatio());
        assertEquals(n.maxSpeed(), t.maxSpeed());
        assertEquals(nxt.body(), txt.body());
        assertEquals(63, t.encoderTicksPerRevolution());
        assertEquals(Map.of("M1", 0, "M2", 1), TxtPorts.wheelCounters(txt.motors(), txt.source()));
        SensorSpec bumper = txt.sensor("bumper").orElseThrow();
        SensorSpec sonar = txt.sensor("sonar").orElseThrow();
        assertEquals(0, TxtPorts.input(bumper.port()));
        assertEquals(1, TxtPorts.input(sonar.port()));
    }
}
