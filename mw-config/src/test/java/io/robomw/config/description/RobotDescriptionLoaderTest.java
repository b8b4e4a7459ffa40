package io.robomw.config.description;

import io.robomw.api.Capability;
import io.robomw.api.Position;
import io.robomw.api.SensorType;
import io.robomw.api.spi.ConnectionSettings;
import io.robomw.config.description.ActuatorSpec.Action;
import io.robomw.config.description.Conversion.Point;
import io.robomw.config.description.DescriptionException.Problem;
import io.robomw.config.description.DifferentialDrive.Wheel;
import org.junit.jupiter.api.Test;

import java.net.URISyntaxException;
import java.nio.file.Path;
import java.time.Duration;
import java.util.List;
import java.util.Map;
import java.util.Optional;
import java.util.OptionalDouble;
import java.util.Set;

import static org.junit.jupiter.api.Assertions.assertAll;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTimeout;
import static org.junit.jupiter.api.Assertions.assertTrue;

class RobotDescriptionLoaderTest {

    private static final String SOURCE = "robot.yaml";

    private final RobotDescriptionLoader loader = new RobotDescriptionLoader();

    private static Path resource(String name) throws URISyntaxException {
        return Path.of(RobotDescriptionLoaderTest.class.getResource("/robots/" + name).toURI());
    }

    private DescriptionException refused(String yaml) {
        return assertThrows(DescriptionException.class, () -> loader.parse(yaml, SOURCE));
    }

    /** The one problem of a file that has exactly one. */
    private Problem onlyProblem(String yaml) {
        DescriptionException e = refused(yaml);
        assertEquals(1, e.problems().size(), () -> "expected one problem, got " + e.problems());
        return e.problems().get(0);
    }

    private static void assertProblem(int line, int column, String messageFragment, Problem problem) {
        assertAll(
                () -> assertEquals(SOURCE, problem.file(), problem::toString),
                () -> assertEquals(line, problem.line(), () -> "line of " + problem),
                () -> assertEquals(column, problem.column(), () -> "column of " + problem),
                () -> assertTrue(problem.message().contains(messageFragment),
                        () -> "expected '" + messageFragment + "' in " + problem));
    }

    // ---- valid files ----

    @Test
    void shouldLoadCompleteNxtRobot() throws Exception {
        Path file = resource("nxt-scout.yaml");
        String source = file.toString();

        RobotDescription d = loader.load(file);

        assertAll(
                () -> assertEquals("nxt-scout", d.name()),
                () -> assertEquals("nxt", d.platform()),
                () -> assertEquals(new ConnectionSettings(Map.of("device", "/dev/rfcomm0", "baud", 115200L, "bluetooth", true), source),
                        d.connection()),
                () -> assertEquals(Duration.ofMillis(20), d.cyclePeriod()),
                () -> assertEquals(Duration.ofMillis(250), d.watchdogTimeout()),
                () -> assertEquals(Set.of(Capability.GROUND), d.capabilities()),
                () -> assertEquals(Optional.of(new DifferentialDrive(0.056, 0.112, 1, 0.3, 360, new Wheel("B", false), new Wheel("C", false))),
                        d.drive()),
                () -> assertEquals(new Body(0.22, 0.16, 0.65, 0.7), d.body()),
                () -> assertEquals(List.of(
                        new SensorSpec("sonar", SensorType.SONAR, Position.FRONT, "S4",
                                new Conversion(0.01, 0, List.of(), OptionalDouble.of(0.2), true, OptionalDouble.empty()),
                                Map.of("mode", "continuous")),
                        new SensorSpec("bumper", SensorType.TOUCH, Position.BACK, "S1", Conversion.IDENTITY, Map.of()),
                        new SensorSpec("floor", SensorType.LIGHT, Position.BOTTOM, "S3",
                                new Conversion(1, 0, List.of(new Point(0, 0), new Point(1023, 1)), OptionalDouble.empty(), false,
                                        OptionalDouble.of(500)),
                                Map.of("floodlight", true)),
                        new SensorSpec("left-odometer", SensorType.TACHO, Position.CENTER, "B", Conversion.IDENTITY, Map.of())),
                        d.sensors()),
                () -> assertEquals(List.of(new ActuatorSpec("gripper", "A", Map.of(
                                "open", new Action(OptionalDouble.of(90), 180),
                                "close", new Action(OptionalDouble.of(-90), 180),
                                "rotate", new Action(OptionalDouble.empty(), 120)))),
                        d.actuators()),
                () -> assertEquals(source, d.source()),
                () -> assertEquals(List.of("B", "C", "A"), d.motorPorts()));
    }

    @Test
    void shouldLoadFischertechnikRobotWithDefaults() throws Exception {
        Path file = resource("fischertechnik-rover.yaml");
        String source = file.toString();

        RobotDescription d = loader.load(file);

        assertAll(
                () -> assertEquals("ft-rover", d.name()),
                () -> assertEquals("ft-intelligent", d.platform()),
                () -> assertEquals(new ConnectionSettings(Map.of("port", "/dev/ttyS0", "baud", 9600L), source), d.connection()),
                () -> assertEquals(Duration.ofMillis(10), d.cyclePeriod(), "default 100 Hz"),
                () -> assertEquals(Duration.ofMillis(500), d.watchdogTimeout(), "default 0.5 s"),
                () -> assertEquals(Set.of(Capability.GROUND, Capability.WATER), d.capabilities()),
                () -> assertEquals(Optional.of(new DifferentialDrive(0.045, 0.15, 2, 0.2, 8,
                                new Wheel("M1", true, Optional.of("E1")), new Wheel("M2", false, Optional.of("E2")))),
                        d.drive()),
                () -> assertEquals(Body.DEFAULT, d.body()),
                () -> assertEquals(List.of(
                        new SensorSpec("trail", SensorType.INFRARED, Position.BOTTOM, "EX",
                                new Conversion(1, 0, List.of(new Point(80, 0.80), new Point(300, 0.20), new Point(900, 0.06)),
                                        OptionalDouble.empty(), false, OptionalDouble.empty()), Map.of()),
                        new SensorSpec("floor", SensorType.LIGHT, Position.BOTTOM, "EY",
                                new Conversion(0.001, -0.05, List.of(), OptionalDouble.empty(), false, OptionalDouble.empty()), Map.of()),
                        new SensorSpec("bumper", SensorType.TOUCH, Position.FRONT_LEFT, "E3", Conversion.IDENTITY, Map.of())),
                        d.sensors()),
                () -> assertEquals(List.of(new ActuatorSpec("crane", "M3", Map.of("lift", new Action(OptionalDouble.of(720), 90)))),
                        d.actuators()),
                () -> assertEquals(List.of("M1", "M2", "M3"), d.motorPorts()));
    }

    @Test
    void shouldReadNumericPortAsText() {
        RobotDescription d = loader.parse("""
                name: scout
                platform: nxt
                sensors:
                  - {name: sonar, type: sonar, position: front, port: 4}
                """, SOURCE);

        assertEquals("4", d.sensors().get(0).port());
    }

    @Test
    void shouldGiveGroundCapabilityWhenNoneIsListed() {
        RobotDescription d = loader.parse("""
                name: scout
                platform: nxt
                """, SOURCE);

        assertEquals(Set.of(Capability.GROUND), d.capabilities());
    }

    @Test
    void shouldReadYesInConnectionBlockAsTrue() {
        RobotDescription d = loader.parse("""
                name: scout
                platform: nxt
                connection: {device: /dev/ttyUSB0, rtscts: yes}
                """, SOURCE);

        assertEquals(Boolean.TRUE, d.connection().values().get("rtscts"),
                "YAML 1.1 'yes' is a boolean true, as drive.left.reversed reads it");
    }

    // ---- unknown keys ----

    @Test
    void shouldReportUnknownTopLevelKeyAtItsPosition() {
        Problem p = onlyProblem("""
                name: scout
                platform: nxt
                colour: red
                """);

        assertProblem(3, 1, "unknown key 'colour'", p);
        assertTrue(p.message().contains("known keys here:") && p.message().contains("drive"), p::toString);
    }

    @Test
    void shouldReportUnknownKeyInDriveWithItsPath() {
        Problem p = onlyProblem("""
                name: scout
                platform: nxt
                drive:
                  wheel_diameter: 0.056
                  track_width: 0.112
                  max_speed: 0.3
                  wheels: 2
                  left: {port: B}
                  right: {port: C}
                """);

        assertProblem(7, 3, "unknown key 'drive.wheels'", p);
    }

    @Test
    void shouldReportUnknownKeyInWheelWithItsPath() {
        Problem p = onlyProblem("""
                name: scout
                platform: nxt
                drive:
                  wheel_diameter: 0.056
                  track_width: 0.112
                  max_speed: 0.3
                  left: {port: B, reverse: true}
                  right: {port: C}
                """);

        assertProblem(7, 19, "unknown key 'drive.left.reverse'", p);
    }

    @Test
    void shouldReportUnknownKeyInSensorWithItsIndex() {
        Problem p = onlyProblem("""
                name: scout
                platform: nxt
                sensors:
                  - {name: sonar, type: sonar, position: front, port: 4, range: 2.5}
                """);

        assertProblem(4, 58, "unknown key 'sensors[0].range'", p);
    }

    // ---- wrong types ----

    @Test
    void shouldReportTextWhereNumberIsExpected() {
        Problem p = onlyProblem("""
                name: scout
                platform: nxt
                drive:
                  wheel_diameter: big
                  track_width: 0.112
                  max_speed: 0.3
                  left: {port: B}
                  right: {port: C}
                """);

        assertProblem(4, 19, "'drive.wheel_diameter' must be a number", p);
        assertTrue(p.message().contains("got 'big'"), p::toString);
    }

    @Test
    void shouldReportTextWhereTopLevelNumberIsExpected() {
        Problem p = onlyProblem("""
                name: scout
                platform: nxt
                cycle_hz: fast
                """);

        assertProblem(3, 11, "'cycle_hz' must be a number", p);
    }

    @Test
    void shouldReportListWhereMappingIsExpected() {
        Problem p = onlyProblem("""
                name: scout
                platform: nxt
                body: [0.2, 0.15]
                """);

        assertProblem(3, 7, "'body' must be a mapping", p);
        assertTrue(p.message().contains("got a list"), p::toString);
    }

    @Test
    void shouldReportMappingWhereListIsExpected() {
        Problem p = onlyProblem("""
                name: scout
                platform: nxt
                sensors: {name: sonar}
                """);

        assertProblem(3, 10, "'sensors' must be a list", p);
    }

    // ---- missing keys ----

    @Test
    void shouldReportMissingName() {
        Problem p = onlyProblem("""
                platform: nxt
                cycle_hz: 50
                """);

        assertProblem(1, 1, "missing key 'name'", p);
    }

    @Test
    void shouldReportMissingPlatformAtStartOfMapping() {
        Problem p = onlyProblem("""
                # a robot without a platform
                name: scout
                """);

        assertProblem(2, 1, "missing key 'platform'", p);
    }

    @Test
    void shouldReportMissingWheelPortAtTheWheelMapping() {
        Problem p = onlyProblem("""
                name: scout
                platform: nxt
                drive:
                  wheel_diameter: 0.056
                  track_width: 0.112
                  max_speed: 0.3
                  left:
                    reversed: true
                  right: {port: C}
                """);

        assertProblem(8, 5, "missing key 'drive.left.port'", p);
    }

    @Test
    void shouldReportMissingSensorPortAtTheSensorMapping() {
        Problem p = onlyProblem("""
                name: scout
                platform: nxt
                sensors:
                  - name: sonar
                    type: sonar
                    position: front
                """);

        assertProblem(4, 5, "missing key 'sensors[0].port'", p);
    }

    // ---- ports and names ----

    @Test
    void shouldRejectTwoSensorsOnOnePort() {
        Problem p = onlyProblem("""
                name: scout
                platform: nxt
                sensors:
                  - {name: sonar, type: sonar, position: front, port: 4}
                  - {name: bumper, type: touch, position: back, port: 4}
                """);

        assertProblem(5, 55, "'sensors[1].port': input port 4", p);
        assertTrue(p.message().contains("sensor 'sonar'"), p::toString);
    }

    @Test
    void shouldRejectTwoSensorsWithOneName() {
        Problem p = onlyProblem("""
                name: scout
                platform: nxt
                sensors:
                  - {name: sonar, type: sonar, position: front, port: 4}
                  - {name: sonar, type: touch, position: back, port: 1}
                """);

        assertProblem(5, 12, "'sensors[1].name'", p);
        assertTrue(p.message().contains("two sensors are named 'sonar'"), p::toString);
    }

    @Test
    void shouldRejectActuatorOnWheelPort() {
        Problem p = onlyProblem("""
                name: scout
                platform: nxt
                drive:
                  wheel_diameter: 0.056
                  track_width: 0.112
                  max_speed: 0.3
                  left: {port: B}
                  right: {port: C}
                actuators:
                  - name: gripper
                    port: B
                    actions:
                      open: {degrees: 90, speed: 180}
                """);

        assertProblem(11, 11, "'actuators[0].port'", p);
        assertTrue(p.message().contains("motor port B is already used by the left wheel"), p::toString);
    }

    @Test
    void shouldRejectTwoActuatorsOnOnePort() {
        Problem p = onlyProblem("""
                name: scout
                platform: nxt
                actuators:
                  - name: gripper
                    port: A
                    actions: {open: {degrees: 90, speed: 180}}
                  - name: arm
                    port: A
                    actions: {raise: {degrees: 45, speed: 90}}
                """);

        assertProblem(8, 11, "'actuators[1].port'", p);
        assertTrue(p.message().contains("already used by actuator 'gripper'"), p::toString);
    }

    @Test
    void shouldRejectTwoActuatorsWithOneName() {
        Problem p = onlyProblem("""
                name: scout
                platform: nxt
                actuators:
                  - name: gripper
                    port: A
                    actions: {open: {degrees: 90, speed: 180}}
                  - name: gripper
                    port: D
                    actions: {close: {degrees: -90, speed: 180}}
                """);

        assertProblem(7, 11, "'actuators[1].name'", p);
    }

    @Test
    void shouldRejectLeftAndRightWheelOnOnePort() {
        Problem p = onlyProblem("""
                name: scout
                platform: nxt
                drive:
                  wheel_diameter: 0.056
                  track_width: 0.112
                  max_speed: 0.3
                  left: {port: B}
                  right: {port: B}
                """);

        assertProblem(8, 10, "'drive.right'", p);
        assertTrue(p.message().contains("port B is already used by the left wheel"), p::toString);
    }

    @Test
    void shouldRejectSensorOnWheelCounterInput() {
        Problem p = onlyProblem("""
                name: rover
                platform: ft-intelligent
                drive:
                  wheel_diameter: 0.056
                  track_width: 0.112
                  max_speed: 0.3
                  left: {port: M1, counter: E1}
                  right: {port: M2, counter: E2}
                sensors:
                  - {name: bumper, type: touch, position: front, port: E1}
                """);

        assertProblem(10, 56, "'sensors[0].port': input port E1", p);
        assertTrue(p.message().contains("left wheel's counter"), p::toString);
    }

    @Test
    void shouldRejectBothWheelsCountingOnOneInput() {
        Problem p = onlyProblem("""
                name: rover
                platform: ft-intelligent
                drive:
                  wheel_diameter: 0.056
                  track_width: 0.112
                  max_speed: 0.3
                  left: {port: M1, counter: E1}
                  right: {port: M2, counter: E1}
                """);

        assertEquals(8, p.line(), p::toString);
        assertTrue(p.message().contains("drive.right"), p::toString);
    }

    @Test
    void shouldRejectActuatorNameWithDot() {
        Problem p = onlyProblem("""
                name: scout
                platform: nxt
                actuators:
                  - name: gripper.left
                    port: A
                    actions: {open: {degrees: 90, speed: 180}}
                """);

        assertProblem(4, 11, "'actuators[0].name': must not contain '.'", p);
    }

    @Test
    void shouldRejectTachoOnPortNoMotorUses() {
        Problem p = onlyProblem("""
                name: scout
                platform: nxt
                drive:
                  wheel_diameter: 0.056
                  track_width: 0.112
                  max_speed: 0.3
                  left: {port: B}
                  right: {port: C}
                sensors:
                  - name: odometer
                    type: tacho
                    position: center
                    port: A
                """);

        assertProblem(13, 11, "'sensors[0].port'", p);
        assertTrue(p.message().contains("B, C"), p::toString);
    }

    @Test
    void shouldRejectEmptySensorPortInsteadOfDroppingTheSensor() {
        DescriptionException e = refused("""
                name: scout
                platform: nxt
                sensors:
                  - {name: sonar, type: sonar, position: front, port: ''}
                """);

        assertTrue(e.problems().stream().anyMatch(p -> p.line() == 4 && p.message().contains("sensors[0].port")), e::getMessage);
    }

    @Test
    void shouldLoadLaserAndGenericRangeSensorsWithTheirDistanceConversions() {
        RobotDescription d = loader.parse("""
                name: rover
                platform: sim
                sensors:
                  - {name: lidar, type: laser, position: front, port: L1, conversion: {scale: 0.001}}
                  - {name: tof, type: range, position: back, port: R1, conversion: {table: [[0, 2.0], [1000, 0.1]]}}
                """, SOURCE);

        SensorSpec lidar = d.sensor("lidar").orElseThrow();
        SensorSpec tof = d.sensor("tof").orElseThrow();
        assertAll(
                () -> assertEquals(SensorType.LASER, lidar.type()),
                () -> assertEquals(1.234, lidar.conversion().apply(1234), 1e-12, "millimetres to metres"),
                () -> assertEquals(SensorType.RANGE, tof.type()),
                () -> assertEquals(1.05, tof.conversion().apply(500), 1e-12, "the table, interpolated"));
    }

    // ---- invalid values ----

    @Test
    void shouldRejectUnknownSensorType() {
        Problem p = onlyProblem("""
                name: scout
                platform: nxt
                sensors:
                  - {name: sonar, type: radar, position: front, port: 4}
                """);

        assertProblem(4, 25, "'sensors[0].type' must be one of touch, light,", p);
        assertTrue(p.message().contains("got 'radar'"), p::toString);
    }

    @Test
    void shouldRejectAnUnknownDriveTypeListingTheKindsThereAre() {
        Problem p = onlyProblem("""
                name: scout
                platform: nxt
                drive: {type: tracked, wheel_diameter: 0.056, track_width: 0.112, max_speed: 0.3, left: {port: B}, right: {port: C}}
                """);

        assertProblem(3, 15, "'drive.type': must be 'differential' (two driven wheels on one axle) or 'legged' (walks by its firmware's own commands)"
                + " or 'vehicle' (a drone, boat or rover moved by its autopilot), got 'tracked'", p);
    }

    @Test
    void shouldRejectNegativeWheelDiameter() {
        Problem p = onlyProblem("""
                name: scout
                platform: nxt
                drive:
                  wheel_diameter: -0.056
                  track_width: 0.112
                  max_speed: 0.3
                  left: {port: B}
                  right: {port: C}
                """);

        assertProblem(4, 19, "'drive.wheel_diameter' must be > 0", p);
        assertTrue(p.message().contains("got '-0.056'"), p::toString);
    }

    @Test
    void shouldRejectTableRowsThatDoNotIncrease() {
        Problem p = onlyProblem("""
                name: scout
                platform: nxt
                sensors:
                  - name: floor
                    type: light
                    position: bottom
                    port: 3
                    conversion:
                      table: [[0, 0.0], [500, 0.5], [400, 0.6]]
                """);

        assertProblem(9, 37, "'sensors[0].conversion.table' raw values must increase", p);
        assertTrue(p.message().contains("got 400.0 after 500.0"), p::toString);
    }

    @Test
    void shouldRejectTableRowsWithRepeatedRawValue() {
        Problem p = onlyProblem("""
                name: scout
                platform: nxt
                sensors:
                  - name: floor
                    type: light
                    position: bottom
                    port: 3
                    conversion:
                      table:
                        - [0, 0.0]
                        - [500, 0.5]
                        - [500, 0.6]
                """);

        assertProblem(12, 11, "'sensors[0].conversion.table' raw values must increase", p);
    }

    // ---- malformed files ----

    @Test
    void shouldReportYamlSyntaxErrorAtItsPosition() {
        Problem p = onlyProblem("""
                name: scout
                platform: nxt
                cycle_hz: 50
                  watchdog: 1
                """);

        assertProblem(4, 11, "not valid YAML", p);
    }

    @Test
    void shouldReportUnclosedFlowMapping() {
        Problem p = onlyProblem("""
                name: scout
                platform: nxt
                body: {length: 0.2
                """);

        assertProblem(4, 1, "not valid YAML", p);
    }

    @Test
    void shouldReportEmptyFile() {
        assertProblem(1, 1, "the file is empty", onlyProblem(""));
    }

    @Test
    void shouldReportFileWithOnlyCommentsAsEmpty() {
        assertProblem(1, 1, "the file is empty", onlyProblem("# nothing here yet\n"));
    }

    @Test
    void shouldReportListAtTopOfFile() {
        assertProblem(1, 1, "expected a mapping of keys to values at the top", onlyProblem("- name: scout\n"));
    }

    @Test
    void shouldReportDuplicateTopLevelKey() {
        Problem p = onlyProblem("""
                name: scout
                platform: nxt
                name: rover
                """);

        assertProblem(3, 1, "key 'name' appears twice", p);
    }

    @Test
    void shouldReportDuplicateNestedKey() {
        Problem p = onlyProblem("""
                name: scout
                platform: nxt
                drive:
                  wheel_diameter: 0.056
                  track_width: 0.112
                  max_speed: 0.3
                  left: {port: B, port: D}
                  right: {port: C}
                """);

        assertProblem(7, 19, "key 'drive.left.port' appears twice", p);
    }

    @Test
    void shouldReportEveryProblemOfOneFileAtOnceInFileOrder() {
        DescriptionException e = refused("""
                name: scout
                platform: nxt
                colour: red
                drive:
                  wheel_diameter: big
                  track_width: 0.112
                  max_speed: 0.3
                  left: {port: B}
                  right: {port: C}
                sensors:
                  - {name: sonar, type: radar, position: front, port: 4}
                  - {name: bumper, type: touch, position: back}
                """);

        List<Problem> problems = e.problems();
        assertEquals(4, problems.size(), e::getMessage);
        assertProblem(3, 1, "unknown key 'colour'", problems.get(0));
        assertProblem(5, 19, "'drive.wheel_diameter' must be a number", problems.get(1));
        assertProblem(11, 25, "'sensors[0].type'", problems.get(2));
        assertProblem(12, 5, "missing key 'sensors[1].port'", problems.get(3));
        assertTrue(e.getMessage().startsWith("4 problems:"), e::getMessage);
        assertTrue(e.getMessage().contains("robot.yaml:12:5: missing key 'sensors[1].port'"), e::getMessage);
    }

    @Test
    void shouldNameFileLineAndColumnInMessageOfSingleProblem() {
        DescriptionException e = refused("""
                name: scout
                platform: nxt
                colour: red
                """);

        assertTrue(e.getMessage().startsWith("robot.yaml:3:1: unknown key 'colour'"), e::getMessage);
    }

    // ---- alias bombs ----

    /** {@code levels} anchors under {@code connection:}, each a list of {@code width} aliases of the one before. */
    private static String aliasBomb(int levels, int width) {
        StringBuilder yaml = new StringBuilder("name: scout\nplatform: nxt\nconnection:\n  a0: &a0 [lol]\n");
        for (int i = 1; i < levels; i++) {
            yaml.append("  a").append(i).append(": &a").append(i).append(" [");
            for (int j = 0; j < width; j++) {
                yaml.append(j == 0 ? "" : ", ").append("*a").append(i - 1);
            }
            yaml.append("]\n");
        }
        return yaml.toString();
    }

    @Test
    void shouldRefuseBillionLaughsWithClearError() {
        String bomb = aliasBomb(10, 10);

        DescriptionException e = assertTimeout(Duration.ofSeconds(5), () -> refused(bomb));

        assertTrue(e.getMessage().contains("aliases"), e::getMessage);
    }

    @Test
    void shouldRefuseNarrowAliasBombThatStaysUnderAliasLimit() {
        // 36 aliases (under the limit of 50) in a 378-byte file, but 3^12 = 531,441 values once expanded.
        String bomb = aliasBomb(13, 3);

        assertTimeout(Duration.ofSeconds(5), () -> refused(bomb));
    }
}
