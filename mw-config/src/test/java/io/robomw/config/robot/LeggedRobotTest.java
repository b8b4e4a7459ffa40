package io.robomw.config.robot;

import io.robomw.api.CommandPreemptedException;
import io.robomw.api.Pose;
import io.robomw.api.RobotException;
import io.robomw.api.UnsupportedActionException;
import io.robomw.api.spi.CommandPriority;
import io.robomw.api.spi.HighLevelCommand;
import io.robomw.config.description.RobotDescription;
import io.robomw.config.description.RobotDescriptionLoader;
import org.junit.jupiter.api.Test;

import java.time.Duration;
import java.util.List;
import java.util.Map;
import java.util.Set;
import java.util.concurrent.CompletableFuture;

import static org.junit.jupiter.api.Assertions.assertAll;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/** The Configuration Layer's legged drive, through the robot a program sees, on a platform that takes high-level commands. */
class LeggedRobotTest {

    private static final double EPS = 1e-9;

    private static final String DOG = """
            name: dog
            platform: aibo
            watchdog: 0.4
            drive:
              type: legged
              max_speed: 0.2
              max_turn_rate: 1.2
              commands:
                move: "robot.walk(${distance}, ${speed})"
                turn: "robot.turn(${angle}, ${speed})"
                drive: "robot.drive(${linear}, ${angular})"
                stop: "robot.stop()"
            actions:
              sit: { command: "robot.sit()", duration: 1.5, uses: [legs] }
              head.pan: { command: "headPan.val = ${angle:deg} time:${duration:ms}", arguments: [angle], duration: 0.4, uses: [head] }
            """;

    private final FakeHighLevelPlatform platform = new FakeHighLevelPlatform();
    private final RobotDescription description = new RobotDescriptionLoader().parse(DOG, "dog.yaml");
    private final ConfiguredRobot robot = ConfiguredRobot.withComponents(() -> description, platform, null);

    private void advance(double seconds) {
        platform.clock.advanceNanos(Math.round(seconds * 1e9));
    }

    private static void assertPose(double x, double y, double heading, Pose p) {
        assertAll(() -> assertEquals(x, p.x(), 1e-6, () -> "x of " + p),
                () -> assertEquals(y, p.y(), 1e-6, () -> "y of " + p),
                () -> assertEquals(heading, p.heading(), 1e-6, () -> "heading of " + p));
    }

    @Test
    void shouldSendAMoveAsTheFirmwaresWalkCommandNotAsWheelRotations() {
        robot.moveAsync(0.5, 0.1);

        HighLevelCommand c = platform.last();
        assertAll(
                () -> assertEquals("move", c.name()),
                () -> assertEquals("robot.walk(0.5, 0.1)", c.text()),
                () -> assertEquals(Map.of("distance", 0.5, "speed", 0.1, "duration", 5.0), c.arguments()),
                () -> assertEquals(Set.of("legs"), c.actuators()),
                () -> assertEquals(Duration.ofSeconds(5), c.expectedDuration()),
                () -> assertFalse(c.continuous()),
                () -> assertEquals(CommandPriority.NORMAL, c.priority()),
                () -> assertEquals("robot.stop()", c.stopText()));
    }

    @Test
    void shouldSendATurnWithItsSignedAngle() {
        robot.turnAsync(-Math.PI / 2, 1.0);

        assertEquals("robot.turn(-1.570796, 1)", platform.last().text());
        assertEquals(Duration.ofNanos(Math.round(Math.PI / 2 * 1e9)), platform.last().expectedDuration());
    }

    @Test
    void shouldRefuseSpeedsAboveTheGaitsLimitsBeforeSendingAnything() {
        UnsupportedActionException fast = assertThrows(UnsupportedActionException.class, () -> robot.move(0.5, 0.3));
        UnsupportedActionException spin = assertThrows(UnsupportedActionException.class, () -> robot.turn(1, 2));
        UnsupportedActionException drift = assertThrows(UnsupportedActionException.class, () -> robot.drive(0.1, -1.5));

        assertAll(
                () -> assertTrue(fast.getMessage().contains("0.300 m/s is above its maximum of 0.200 m/s (drive.max_speed)"), fast.getMessage()),
                () -> assertTrue(spin.getMessage().contains("drive.max_turn_rate"), spin.getMessage()),
                () -> assertTrue(drift.getMessage().contains("angular speed -1.500"), drift.getMessage()),
                () -> assertEquals(List.of(), platform.commands));
    }

    @Test
    void shouldRefuseAnArcTheFirmwareHasNoCommandFor() {
        UnsupportedActionException e = assertThrows(UnsupportedActionException.class, () -> robot.arc(0.5, 1, 0.1));

        assertTrue(e.getMessage().contains("drive.commands.arc"), e.getMessage());
        assertEquals(List.of(), platform.commands);
    }

    @Test
    void shouldSendDriveAsAContinuousCommandUnderTheWatchdog() {
        robot.drive(0.1, 0.5);

        HighLevelCommand c = platform.last();
        assertAll(
                () -> assertEquals("robot.drive(0.1, 0.5)", c.text()),
                () -> assertTrue(c.continuous()),
                () -> assertEquals(Duration.ofMillis(400), c.watchdogTimeout()));
    }

    @Test
    void shouldListAndPerformHighLevelActions() {
        assertEquals(List.of("sit", "head.pan"), robot.actions());

        robot.performAsync("head.pan", Math.toRadians(-45));

        HighLevelCommand c = platform.last();
        assertAll(
                () -> assertEquals("head.pan", c.name()),
                () -> assertEquals("headPan.val = -45 time:400", c.text()),
                () -> assertEquals(Set.of("head"), c.actuators()),
                () -> assertEquals("", c.stopText(), "a head action needs no stop of the legs"),
                () -> assertEquals(Duration.ofMillis(400), c.expectedDuration()));
    }

    @Test
    void shouldRefuseAnActionTheRobotLacksOrWithTheWrongArgumentsBeforeSendingAnything() {
        assertThrows(UnsupportedActionException.class, () -> robot.perform("roll.over"));
        UnsupportedActionException args = assertThrows(UnsupportedActionException.class, () -> robot.perform("head.pan"));
        assertThrows(UnsupportedActionException.class, () -> robot.perform("head.pan", Double.NaN));

        assertTrue(args.getMessage().contains("takes 1 argument(s) [angle]"), args.getMessage());
        assertEquals(List.of(), platform.commands);
    }

    @Test
    void shouldCountACompletedWalkWholeInThePose() {
        CompletableFuture<Void> walk = robot.moveAsync(0.5, 0.1);
        advance(2);
        assertPose(0.2, 0, 0, robot.pose());

        advance(2.9);
        platform.futures.get(0).complete(null);
        walk.join();

        assertPose(0.5, 0, 0, robot.pose());
    }

    @Test
    void shouldCountAnInterruptedWalkForTheTimeItRan() {
        robot.moveAsync(0.5, 0.1);
        advance(1);
        robot.turnAsync(Math.PI / 2, 1.0);
        platform.futures.get(0).completeExceptionally(new CommandPreemptedException("move", "turn"));
        advance(Math.PI / 2);
        platform.futures.get(1).complete(null);

        assertPose(0.1, 0, Math.PI / 2, robot.pose());
    }

    @Test
    void shouldEndADriveWhenItsRefreshStopsAndTheWatchdogEndsIt() {
        robot.drive(0.1, 0);
        advance(0.3);
        robot.drive(0.1, 0);
        platform.futures.get(1).complete(null);
        advance(0.5);
        platform.futures.get(0).completeExceptionally(new RobotException("watchdog stopped 'drive'"));
        advance(1);

        assertPose(0.08, 0, 0, robot.pose());
    }

    @Test
    void shouldNotEndANewerDriveWhenAnEarlierDrivesWatchdogEndIsHeardLate() {
        robot.drive(0.1, 0);
        advance(1);
        robot.moveAsync(0.1, 0.1);
        advance(1);
        robot.drive(0.1, 0);
        advance(1);
        platform.futures.get(0).completeExceptionally(new RobotException("watchdog stopped 'drive'"));
        advance(1);

        assertPose(0.4, 0, 0, robot.pose());
    }

    @Test
    void shouldEndTheWalkInThePoseWhenStoppedOrSitting() {
        robot.moveAsync(0.5, 0.1);
        advance(1);
        robot.stop();
        advance(1);
        assertPose(0.1, 0, 0, robot.pose());
        assertEquals(1, platform.stops);

        robot.moveAsync(0.5, 0.1);
        advance(1);
        robot.performAsync("sit");
        advance(1);

        assertPose(0.2, 0, 0, robot.pose());
        assertEquals("robot.stop()", platform.last().stopText(), "an action on the legs stops them when it is interrupted");
    }

    @Test
    void shouldResetThePoseAndGoOnFromIt() {
        robot.resetPose(new Pose(1, 2, Math.PI / 2));
        robot.moveAsync(0.2, 0.1);
        advance(2);

        assertPose(1, 2.2, Math.PI / 2, robot.pose());
    }

    @Test
    void shouldCancelThePlatformsCommandWhenTheFutureOfAWalkOrAnActionIsCancelled() {
        CompletableFuture<Void> walk = robot.moveAsync(0.5, 0.1);
        CompletableFuture<Void> turn = robot.turnAsync(1.0, 1.0);
        CompletableFuture<Void> sit = robot.performAsync("sit");

        walk.cancel(true);
        turn.cancel(true);
        sit.cancel(true);

        assertAll(
                () -> assertTrue(platform.futures.get(0).isCancelled(), "the walk's command"),
                () -> assertTrue(platform.futures.get(1).isCancelled(), "the turn's command"),
                () -> assertTrue(platform.futures.get(2).isCancelled(), "the action's command"));
    }

    @Test
    void shouldRefuseALeggedDriveOnAPlatformWithoutHighLevelCommands() {
        ConfiguredRobot onMotors = ConfiguredRobot.withComponents(() -> description, new FakePlatform(), null);

        UnsupportedActionException e = assertThrows(UnsupportedActionException.class, () -> onMotors.move(0.1, 0.1));

        assertTrue(e.getMessage().contains("does not take high-level commands"), e.getMessage());
    }
}
