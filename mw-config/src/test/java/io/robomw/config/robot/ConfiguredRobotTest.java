package io.robomw.config.robot;

import io.robomw.api.Agent;
import io.robomw.api.Pose;
import io.robomw.api.Position;
import io.robomw.api.ReturnType;
import io.robomw.api.SensorType;
import io.robomw.api.UnsupportedActionException;
import io.robomw.api.spi.MotorCommand;
import io.robomw.api.spi.MotorTarget;
import io.robomw.config.description.RobotDescription;
import io.robomw.config.description.RobotDescriptionLoader;
import org.junit.jupiter.api.Test;

import java.util.List;
import java.util.concurrent.atomic.AtomicReference;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

class ConfiguredRobotTest {

    private static final double EPS = 1e-6;

    private final FakePlatform platform = new FakePlatform();
    private final AtomicReference<RobotDescription> description = new AtomicReference<>(scout(0.056, 0.3));
    private final ConfiguredRobot robot = ConfiguredRobot.withComponents(description::get, platform, null);

    /** An NXT robot with wheels on B and C, a sonar in front, a bumper at the back and a gripper on A. */
    private static RobotDescription scout(double wheelDiameter, double maxSpeed) {
        return new RobotDescriptionLoader().parse("""
                name: scout
                platform: nxt
                drive:
                  wheel_diameter: %s
                  track_width: 0.112
                  max_speed: %s
                  left: {port: B}
                  right: {port: C}
                sensors:
                  - {name: sonar, type: sonar, position: front, port: 4, conversion: {scale: 0.01}}
                  - {name: bumper, type: touch, position: back, port: 1}
                actuators:
                  - name: gripper
                    port: A
                    actions:
                      open: {degrees: 90, speed: 180}
                      close: {degrees: -90, speed: 180}
                      rotate: {degrees: argument, speed: 120}
                """.formatted(wheelDiameter, maxSpeed), "scout.yaml");
    }

    private static RobotDescription withoutDrive() {
        return new RobotDescriptionLoader().parse("""
                name: arm
                platform: nxt
                actuators:
                  - {name: gripper, port: A, actions: {open: {degrees: 90, speed: 180}}}
                """, "arm.yaml");
    }

    private static double degrees(double metres, double wheelDiameter) {
        return metres * 360 / (Math.PI * wheelDiameter);
    }

    private MotorCommand onlyCommand() {
        assertEquals(1, platform.commands.size(), () -> "commands sent: " + platform.commands);
        return platform.commands.get(0);
    }

    private static MotorTarget target(MotorCommand command, String port) {
        return command.targets().stream().filter(t -> t.port().equals(port)).findFirst()
                .orElseThrow(() -> new AssertionError("no target for motor " + port + " in " + command));
    }

    private static void assertRotation(double degrees, double degreesPerSecond, MotorTarget target) {
        assertEquals(Math.abs(degrees), target.degrees(), 0.05, () -> "degrees of " + target);
        assertEquals(Math.copySign(degreesPerSecond, degrees), target.degreesPerSecond(), 0.05, () -> "speed of " + target);
    }

    private static void assertPose(double x, double y, double heading, Pose actual) {
        assertEquals(x, actual.x(), EPS, () -> "x of " + actual);
        assertEquals(y, actual.y(), EPS, () -> "y of " + actual);
        assertEquals(0, Pose.normalize(heading - actual.heading()), EPS, () -> "heading of " + actual);
    }

    // ---- motion ----

    @Test
    void shouldRotateBothWheelMotors2046DegreesForOneMetre() {
        robot.move(1.0, 0.2);

        MotorCommand c = onlyCommand();
        assertEquals(2, c.targets().size());
        assertRotation(2046.3, 0.2 * 2046.28, target(c, "B"));
        assertRotation(2046.3, 0.2 * 2046.28, target(c, "C"));
    }

    @Test
    void shouldRunWheelMotorsBackwardsForNegativeDistance() {
        robot.move(-0.5, 0.2);

        assertRotation(-1023.14, 0.2 * 2046.28, target(onlyCommand(), "B"));
    }

    @Test
    void shouldRefuseSpeedAboveMaxSpeedNamingRobotAndLimit() {
        UnsupportedActionException e = assertThrows(UnsupportedActionException.class, () -> robot.move(1.0, 0.5));

        assertEquals("scout", e.robot());
        assertTrue(e.getMessage().contains("max_speed"), e::getMessage);
        assertEquals(List.of(), platform.commands, "nothing is sent");
    }

    @Test
    void shouldRefuseTurnWhoseWheelSpeedExceedsMaxSpeed() {
        // 6 rad/s on a 0.112 m track: each wheel at 0.336 m/s, above 0.3.
        UnsupportedActionException e = assertThrows(UnsupportedActionException.class, () -> robot.turn(Math.PI, 6));

        assertTrue(e.getMessage().contains("max_speed"), e::getMessage);
        assertEquals(List.of(), platform.commands);
    }

    @Test
    void shouldRefuseArcWhoseOuterWheelExceedsMaxSpeed() {
        // centre at 0.28 m/s on a 0.2 m radius: outer wheel at 0.28 * 0.256 / 0.2 = 0.358 m/s.
        UnsupportedActionException e = assertThrows(UnsupportedActionException.class, () -> robot.arc(0.2, Math.PI / 2, 0.28));

        assertTrue(e.getMessage().contains("max_speed"), e::getMessage);
        assertEquals(List.of(), platform.commands);
    }

    @Test
    void shouldTurnWheelsInOppositeDirectionsForLeftTurn() {
        robot.turn(Math.PI / 2, 1.0);

        MotorCommand c = onlyCommand();
        assertRotation(-180, degrees(0.056, 0.056), target(c, "B"));
        assertRotation(180, degrees(0.056, 0.056), target(c, "C"));
    }

    @Test
    void shouldSendContinuousSpeedsWithWatchdogForDrive() {
        robot.drive(0.2, 0);

        MotorCommand c = onlyCommand();
        assertTrue(target(c, "B").continuous());
        assertEquals(0.2 * 2046.28, target(c, "B").degreesPerSecond(), 0.05);
        assertEquals(0.2 * 2046.28, target(c, "C").degreesPerSecond(), 0.05);
        assertEquals(description.get().watchdogTimeout(), c.watchdogTimeout());
    }

    @Test
    void shouldSpinOnTheSpotWhenDrivingWithZeroLinearSpeed() {
        robot.drive(0, 1.0);

        MotorCommand c = onlyCommand();
        assertEquals(-degrees(0.056, 0.056), target(c, "B").degreesPerSecond(), 0.05);
        assertEquals(degrees(0.056, 0.056), target(c, "C").degreesPerSecond(), 0.05);
    }

    @Test
    void shouldStopAllMotorsOnStop() {
        robot.stop();

        assertEquals(1, platform.stops);
    }

    @Test
    void shouldStopRobotWithoutDrive() {
        description.set(withoutDrive());

        robot.stop();

        assertEquals(1, platform.stops);
    }

    @Test
    void shouldMoveWheelsWhoseMotorsHaveNoEncoders() {
        platform.encoders = false;

        robot.move(1.0, 0.2);

        assertRotation(2046.3, 0.2 * 2046.28, target(onlyCommand(), "B"));
    }

    @Test
    void shouldStopRobotWhoseMotorsHaveNoEncoders() {
        platform.encoders = false;

        robot.stop();

        assertEquals(1, platform.stops);
    }

    @Test
    void shouldRefusePoseWhenWheelMotorsHaveNoEncoders() {
        platform.encoders = false;

        UnsupportedActionException e = assertThrows(UnsupportedActionException.class, robot::pose);

        assertTrue(e.getMessage().contains("encoders"), e::getMessage);
    }

    @Test
    void shouldRefuseAltitudeChangeOfGroundRobot() {
        UnsupportedActionException e = assertThrows(UnsupportedActionException.class, () -> robot.changeAltitude(1.0, 0.2));

        assertEquals("scout", e.robot());
        assertTrue(e.getMessage().contains("AIR"), e::getMessage);
        assertEquals(List.of(), platform.commands);
    }

    // ---- actions ----

    @Test
    void shouldListActionsAsActuatorDotAction() {
        assertEquals(List.of("gripper.close", "gripper.open", "gripper.rotate"), robot.actions());
    }

    @Test
    void shouldRotateActuatorByItsActionDegrees() {
        robot.perform("gripper.open");

        MotorCommand c = onlyCommand();
        assertEquals(1, c.targets().size());
        assertRotation(90, 180, target(c, "A"));
    }

    @Test
    void shouldRotateActuatorBackwardsForNegativeActionDegrees() {
        robot.perform("gripper.close");

        assertRotation(-90, 180, target(onlyCommand(), "A"));
    }

    @Test
    void shouldRotateActuatorByArgumentInRadians() {
        robot.perform("gripper.rotate", Math.PI / 2);

        assertRotation(90, 120, target(onlyCommand(), "A"));
    }

    @Test
    void shouldRefuseArgumentForFixedAction() {
        UnsupportedActionException e = assertThrows(UnsupportedActionException.class, () -> robot.perform("gripper.open", 1.0));

        assertTrue(e.getMessage().contains("no arguments"), e::getMessage);
        assertEquals(List.of(), platform.commands);
    }

    @Test
    void shouldRefuseMissingArgumentForArgumentAction() {
        UnsupportedActionException e = assertThrows(UnsupportedActionException.class, () -> robot.perform("gripper.rotate"));

        assertTrue(e.getMessage().contains("one angle"), e::getMessage);
        assertEquals(List.of(), platform.commands);
    }

    @Test
    void shouldRefuseUnknownActionListingKnownOnes() {
        UnsupportedActionException e = assertThrows(UnsupportedActionException.class, () -> robot.perform("gripper.fly"));

        assertTrue(e.getMessage().contains("gripper.open"), e::getMessage);
        assertEquals(List.of(), platform.commands);
    }

    @Test
    void shouldRefuseUnknownActuator() {
        UnsupportedActionException e = assertThrows(UnsupportedActionException.class, () -> robot.perform("arm.raise"));

        assertTrue(e.getMessage().contains("no actuator 'arm'"), e::getMessage);
    }

    // ---- perception ----

    @Test
    void shouldConvertSonarReadingToCentimeters() {
        platform.raw.put("sonar", 42.0);

        assertEquals(42, robot.getValue(Position.FRONT, SensorType.SONAR, ReturnType.CENTIMETERS), 1e-9);
    }

    @Test
    void shouldReadAnyRangeFinderAtAPositionAsRange() {
        platform.raw.put("sonar", 42.0);

        assertEquals(42, robot.getValue(Position.FRONT, SensorType.RANGE, ReturnType.CENTIMETERS), 1e-9);
    }

    @Test
    void shouldRefuseARangeReadingWhereThereIsNoRangeFinderListingWhatTheRobotHas() {
        UnsupportedActionException e = assertThrows(UnsupportedActionException.class,
                () -> robot.getValue(Position.BACK, SensorType.RANGE, ReturnType.METERS));

        assertEquals("robot 'scout' cannot getValue(BACK, RANGE, METERS): it has no range finder (SONAR, INFRARED, LASER, RANGE sensor) at BACK;"
                + " its sensors are sonar (SONAR at FRONT), bumper (TOUCH at BACK)", e.getMessage());
    }

    @Test
    void shouldRefuseARangeReadingInAnAngleUnitBeforeReading() {
        UnsupportedActionException e = assertThrows(UnsupportedActionException.class,
                () -> robot.getValueAsync(Position.FRONT, SensorType.RANGE, ReturnType.RADIANS));

        assertTrue(e.getMessage().contains("a SONAR sensor measures DISTANCE"), e.getMessage());
    }

    @Test
    void shouldReadSensorByName() {
        platform.raw.put("sonar", 42.0);

        assertEquals(0.42, robot.getValue("sonar", ReturnType.METERS), 1e-12);
    }

    @Test
    void shouldRefuseMissingSensorNamingRobotAndListingSensors() {
        UnsupportedActionException e = assertThrows(UnsupportedActionException.class,
                () -> robot.getValue(Position.BACK, SensorType.SONAR, ReturnType.METERS));

        assertEquals("scout", e.robot());
        assertTrue(e.getMessage().contains("sonar (SONAR at FRONT)"), e::getMessage);
        assertTrue(e.getMessage().contains("bumper (TOUCH at BACK)"), e::getMessage);
    }

    @Test
    void shouldRefuseUnknownSensorNameListingSensors() {
        UnsupportedActionException e = assertThrows(UnsupportedActionException.class, () -> robot.getValue("radar", ReturnType.METERS));

        assertTrue(e.getMessage().contains("'radar'"), e::getMessage);
        assertTrue(e.getMessage().contains("sonar (SONAR at FRONT)"), e::getMessage);
    }

    @Test
    void shouldRefuseUnitThatDoesNotFitSensorWithoutReadingIt() {
        assertThrows(UnsupportedActionException.class, () -> robot.getValueAsync(Position.FRONT, SensorType.SONAR, ReturnType.DEGREES));
    }

    // ---- messaging and agents ----

    @Test
    void shouldRefuseSendMessageSayingWhichArtifactAddsMessagingWhenNoProviderIsOnTheClassPath() {
        UnsupportedActionException e = assertThrows(UnsupportedActionException.class,
                () -> robot.sendMessage("scout", "localhost", "secret", "news", "hello", "greet"));

        assertEquals("scout", e.robot());
        assertTrue(e.getMessage().contains("io.robomw:mw-agents"), e.getMessage());
    }

    @Test
    void shouldRefuseSendAgentWithoutAgentRuntime() {
        Agent agent = new Agent() {
            private static final long serialVersionUID = 1L;

            @Override
            public void run() {
            }
        };

        UnsupportedActionException e = assertThrows(UnsupportedActionException.class, () -> robot.sendAgent("localhost", agent));

        assertEquals("scout", e.robot());
        assertTrue(e.getMessage().contains("io.robomw:mw-agents"), e.getMessage());
    }

    // ---- pose ----

    @Test
    void shouldStartPoseAtOrigin() {
        assertPose(0, 0, 0, robot.pose());
    }

    @Test
    void shouldFollowMotorDegreesWithPose() {
        robot.pose();
        platform.motorDegrees.put("B", degrees(1, 0.056));
        platform.motorDegrees.put("C", degrees(1, 0.056));

        assertPose(1, 0, 0, robot.pose());
    }

    @Test
    void shouldTurnPoseWhenMotorsTurnOpposite() {
        robot.pose();
        platform.motorDegrees.put("B", -180.0);
        platform.motorDegrees.put("C", 180.0);

        assertPose(0, 0, Math.PI / 2, robot.pose());
    }

    @Test
    void shouldIntegrateFromResetPose() {
        robot.resetPose(new Pose(1, 2, Math.PI / 2));
        platform.motorDegrees.put("B", degrees(1, 0.056));
        platform.motorDegrees.put("C", degrees(1, 0.056));

        assertPose(1, 3, Math.PI / 2, robot.pose());
    }

    // ---- reload ----

    @Test
    void shouldUseReloadedWheelDiameterForNextCommand() {
        robot.move(1.0, 0.2);
        description.set(scout(0.112, 0.3));

        robot.move(1.0, 0.2);

        assertEquals(2, platform.commands.size());
        assertRotation(1023.14, 0.2 * 1023.14, target(platform.commands.get(1), "B"));
    }

    @Test
    void shouldUseReloadedMaxSpeedForNextCommand() {
        description.set(scout(0.056, 0.6));

        robot.move(1.0, 0.5);

        assertRotation(2046.3, 0.5 * 2046.28, target(onlyCommand(), "B"));
    }

    @Test
    void shouldKeepOdometryTravelAcrossReloadOfMaxSpeed() {
        robot.pose();
        platform.motorDegrees.put("B", degrees(1, 0.056));
        platform.motorDegrees.put("C", degrees(1, 0.056));
        description.set(scout(0.056, 0.6));

        assertPose(1, 0, 0, robot.pose());
    }

    // ---- lifecycle ----

    @Test
    void shouldClosePlatformOnClose() {
        robot.close();

        assertTrue(platform.closed);
    }
}
