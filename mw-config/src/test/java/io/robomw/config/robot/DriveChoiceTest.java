package io.robomw.config.robot;

import io.robomw.api.Pose;
import io.robomw.api.UnsupportedActionException;
import io.robomw.config.description.RobotDescription;
import io.robomw.config.description.RobotDescriptionLoader;
import io.robomw.config.drive.DifferentialDriveControl;
import io.robomw.config.drive.DriveControl;
import io.robomw.config.drive.Drives;
import io.robomw.config.legged.LeggedDriveControl;
import org.junit.jupiter.api.Test;

import java.util.concurrent.atomic.AtomicReference;

import static org.junit.jupiter.api.Assertions.assertAll;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertInstanceOf;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/** One drive implementation per kind, chosen once per description in force. */
class DriveChoiceTest {

    private static final String WHEELS = """
            name: scout
            platform: nxt
            drive: { wheel_diameter: %s, track_width: 0.112, max_speed: 0.3, left: {port: B}, right: {port: C} }
            """;
    private static final String LEGS = """
            name: dog
            platform: aibo
            drive:
              type: legged
              max_speed: 0.2
              max_turn_rate: 1.2
              commands: { move: "walk(${distance})", turn: "turn(${angle})" }
            """;
    private static final String ARM = """
            name: arm
            platform: nxt
            actuators:
              - {name: gripper, port: A, actions: {open: {degrees: 90, speed: 180}}}
            """;

    private static RobotDescription parse(String yaml) {
        return new RobotDescriptionLoader().parse(yaml, "robot.yaml");
    }

    private static RobotDescription wheels(double diameter) {
        return parse(WHEELS.formatted(diameter));
    }

    @Test
    void shouldChooseTheImplementationOfTheDescriptionsDriveKind() {
        assertAll(
                () -> assertInstanceOf(DifferentialDriveControl.class, Drives.choose(wheels(0.056), new FakePlatform(), null)),
                () -> assertInstanceOf(LeggedDriveControl.class, Drives.choose(parse(LEGS), new FakeHighLevelPlatform(), null)));
    }

    @Test
    void shouldRefuseEveryMotionAndThePoseOfARobotWithoutDriveSayingSo() {
        DriveControl none = Drives.choose(parse(ARM), new FakePlatform(), null);

        UnsupportedActionException move = assertThrows(UnsupportedActionException.class, () -> none.move(1, 0.1));
        UnsupportedActionException pose = assertThrows(UnsupportedActionException.class, none::pose);

        assertAll(
                () -> assertEquals("robot 'arm' cannot move(1.000, 0.100): its description has no drive", move.getMessage()),
                () -> assertTrue(pose.getMessage().contains("no drive to estimate a pose from"), pose.getMessage()),
                () -> assertThrows(UnsupportedActionException.class, () -> none.drive(0.1, 0)));
    }

    @Test
    void shouldRefuseTheFlyingVerbsOnGroundDrivesSayingTheRobotIsNotAnAirOne() {
        DriveControl wheels = Drives.choose(wheels(0.056), new FakePlatform(), null);
        DriveControl legs = Drives.choose(parse(LEGS), new FakeHighLevelPlatform(), null);

        for (DriveControl d : new DriveControl[] {wheels, legs}) {
            UnsupportedActionException climb = assertThrows(UnsupportedActionException.class, () -> d.changeAltitude(1, 0.5));
            UnsupportedActionException takeOff = assertThrows(UnsupportedActionException.class, () -> d.takeOff(2));
            UnsupportedActionException land = assertThrows(UnsupportedActionException.class, d::land);
            assertAll(
                    () -> assertTrue(climb.getMessage().contains("changeAltitude(1.000, 0.500): it is a [GROUND] robot, not an AIR one"), climb.getMessage()),
                    () -> assertTrue(takeOff.getMessage().contains("takeOff(2.000): it is a [GROUND] robot, not an AIR one"), takeOff.getMessage()),
                    () -> assertTrue(land.getMessage().contains("land(): it is a [GROUND] robot, not an AIR one"), land.getMessage()));
        }
    }

    @Test
    void shouldAskThePlatformAboutEncodersOncePerDescriptionNotInEveryVerb() {
        FakePlatform platform = new FakePlatform();
        AtomicReference<RobotDescription> description = new AtomicReference<>(wheels(0.056));
        ConfiguredRobot robot = ConfiguredRobot.withComponents(description::get, platform, null);

        for (int i = 0; i < 100; i++) {
            robot.drive(0.1, 0);
            robot.pose();
        }
        robot.move(0.1, 0.1);
        assertEquals(2, platform.encoderQuestions, "once per wheel, for the one description in force");

        description.set(wheels(0.112));
        robot.drive(0.1, 0);
        robot.drive(0.1, 0);
        assertEquals(4, platform.encoderQuestions, "chosen again once for the reloaded description");
    }

    @Test
    void shouldContinueThePoseWhenAReloadBringsADriveOfTheSameKind() {
        FakePlatform platform = new FakePlatform();
        DriveControl before = Drives.choose(wheels(0.056), platform, null);
        before.resetPose(new Pose(1, 2, 0));
        platform.motorDegrees.put("B", 360 / Math.PI / 0.056); // one metre on the 56 mm wheels
        platform.motorDegrees.put("C", 360 / Math.PI / 0.056);

        DriveControl after = Drives.choose(wheels(0.112), platform, before);
        Pose moved = after.pose();

        assertAll(
                () -> assertEquals(2, moved.x(), 1e-9, "the metre driven before the reload counts with the wheels it was driven on"),
                () -> assertEquals(2, moved.y(), 1e-9),
                () -> assertInstanceOf(DifferentialDriveControl.class, after));
    }
}
