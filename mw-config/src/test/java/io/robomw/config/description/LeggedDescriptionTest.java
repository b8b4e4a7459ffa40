package io.robomw.config.description;

import io.robomw.api.Position;
import io.robomw.api.SensorType;
import io.robomw.config.description.DescriptionException.Problem;
import org.junit.jupiter.api.Test;

import java.util.List;
import java.util.Map;
import java.util.Set;

import static org.junit.jupiter.api.Assertions.assertAll;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/** The {@code drive: {type: legged}} block and the {@code actions:} section of a robot file. */
class LeggedDescriptionTest {

    private static final String SOURCE = "dog.yaml";

    private static final String DOG = """
            name: dog
            platform: aibo
            connection: { host: 127.0.0.1 }
            drive:
              type: legged
              max_speed: 0.2
              max_turn_rate: 1.2
              commands:
                move: "robot.walk(${distance}, ${speed})"
                turn: "robot.turn(${angle}, ${speed})"
                arc: "robot.arc(${radius}, ${angle}, ${speed})"
                drive: "robot.drive(${linear}, ${angular})"
                stop: "robot.stop()"
              gait: { step_frequency: 2.5, jitter: 0.03, slip: 0.02 }
            sensors:
              - { name: head_far, type: infrared, position: front, port: distanceFar, conversion: { scale: 0.001 } }
              - { name: neck, type: joint, position: center, port: neck }
              - { name: accel_x, type: accelerometer, position: center, port: accelX }
            actions:
              sit: { command: "robot.sit()", duration: 1.5, uses: [legs] }
              head.pan: { command: "headPan.val = ${angle:deg} time:${duration:ms}", arguments: [angle], duration: 0.4, uses: [head] }
            """;

    private final RobotDescriptionLoader loader = new RobotDescriptionLoader();

    private List<Problem> problems(String yaml) {
        return assertThrows(DescriptionException.class, () -> loader.parse(yaml, SOURCE)).problems();
    }

    private static void assertProblem(int line, String fragment, List<Problem> problems) {
        assertEquals(1, problems.size(), () -> "expected one problem, got " + problems);
        Problem p = problems.get(0);
        assertAll(
                () -> assertEquals(SOURCE, p.file()),
                () -> assertEquals(line, p.line(), () -> "line of " + p),
                () -> assertTrue(p.message().contains(fragment), () -> "expected '" + fragment + "' in " + p));
    }

    @Test
    void shouldReadTheLeggedDriveWithItsTemplatesAndGait() {
        RobotDescription d = loader.parse(DOG, SOURCE);

        LeggedDrive legged = d.leggedDrive().orElseThrow();
        assertAll(
                () -> assertTrue(d.drive().isEmpty(), "no differential drive"),
                () -> assertEquals(List.of(), d.motorPorts(), "a legged drive has no motor ports"),
                () -> assertEquals(0.2, legged.maxSpeed()),
                () -> assertEquals(1.2, legged.maxTurnRate()),
                () -> assertEquals("robot.walk(0.5, 0.1)", legged.move().render(Map.of("distance", 0.5, "speed", 0.1))),
                () -> assertEquals("robot.stop()", legged.stop().orElseThrow().text()),
                () -> assertEquals(new LeggedDrive.Gait(2.5, 0.03, 0.02), legged.gait()),
                () -> assertEquals(SensorType.JOINT, d.sensor("neck").orElseThrow().type()),
                () -> assertEquals(SensorType.ACCELEROMETER, d.sensor("accel_x").orElseThrow().type()),
                () -> assertEquals(Position.FRONT, d.sensor("head_far").orElseThrow().position()));
    }

    @Test
    void shouldReadHighLevelActionsInFileOrder() {
        RobotDescription d = loader.parse(DOG, SOURCE);

        assertEquals(List.of("sit", "head.pan"), d.highLevelActions().stream().map(HighLevelAction::name).toList());
        HighLevelAction pan = d.highLevelAction("head.pan").orElseThrow();
        assertAll(
                () -> assertEquals(List.of("angle"), pan.arguments()),
                () -> assertEquals(0.4, pan.durationSeconds()),
                () -> assertEquals(Set.of("head"), pan.uses()),
                () -> assertEquals("headPan.val = 30 time:400", pan.command().render(Map.of("angle", Math.toRadians(30), "duration", 0.4))));
    }

    @Test
    void shouldNameTheLineOfAPlaceholderTheCommandDoesNotHave() {
        String yaml = DOG.replace("robot.turn(${angle}, ${speed})", "robot.turn(${distance}, ${speed})");

        assertProblem(10, "'distance', which this command does not have", problems(yaml));
    }

    @Test
    void shouldRequireTheMoveAndTurnTemplates() {
        String yaml = DOG.replace("    turn: \"robot.turn(${angle}, ${speed})\"\n", "");

        assertProblem(9, "missing key 'drive.commands.turn'", problems(yaml));
    }

    @Test
    void shouldRefuseWheelKeysInALeggedDrive() {
        String yaml = DOG.replace("  max_turn_rate: 1.2\n", "  max_turn_rate: 1.2\n  left: { port: B }\n");

        assertProblem(8, "unknown key 'drive.left'", problems(yaml));
    }

    @Test
    void shouldRefuseAnActionThatUsesNoActuatorGroup() {
        String yaml = DOG.replace("sit: { command: \"robot.sit()\", duration: 1.5, uses: [legs] }", "sit: { command: \"robot.sit()\", duration: 1.5 }");

        assertProblem(20, "name the actuator groups", problems(yaml));
    }

    @Test
    void shouldRefuseAnActionArgumentItsTemplateCannotNameAndAZeroDuration() {
        String yaml = DOG.replace("arguments: [angle], duration: 0.4", "arguments: [Angle], duration: 0");

        List<Problem> problems = problems(yaml);
        assertEquals(3, problems.size(), problems::toString);
        assertTrue(problems.stream().anyMatch(p -> p.message().contains("lower-case words")), problems::toString);
        assertTrue(problems.stream().anyMatch(p -> p.message().contains("'angle', which this command does not have")), problems::toString);
        assertTrue(problems.stream().anyMatch(p -> p.message().contains("duration") && p.message().contains("> 0 seconds")), problems::toString);
    }

    @Test
    void shouldRefuseAnUnknownDriveType() {
        String yaml = DOG.replace("type: legged", "type: hexapod").replace("""
                  max_turn_rate: 1.2
                """, "");

        assertTrue(problems(yaml).stream().anyMatch(p -> p.message().contains("'differential'") && p.message().contains("'legged'")));
    }
}
