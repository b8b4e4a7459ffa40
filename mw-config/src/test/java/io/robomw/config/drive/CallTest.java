package io.robomw.config.drive;

import io.robomw.api.UnsupportedActionException;
import org.junit.jupiter.api.Test;

import static org.junit.jupiter.api.Assertions.assertAll;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;

/** Every argument check names the robot, the call, the value by its name and the rule, in one format. */
class CallTest {

    private final Call move = Call.of("scout", "move(%.3f, %.3f)", 1.0, 0.5);

    @Test
    void shouldNameTheValueItsMaximumAndTheKeyThatSetsIt() {
        UnsupportedActionException e = assertThrows(UnsupportedActionException.class,
                () -> move.atMost(0.5, 0.3, "wheel speed", "m/s", "drive.max_speed"));

        assertAll(
                () -> assertEquals("robot 'scout' cannot move(1.000, 0.500): wheel speed 0.500 m/s is above its maximum of 0.300 m/s (drive.max_speed)",
                        e.getMessage()),
                () -> assertEquals("scout", e.robot()),
                () -> assertEquals("move(1.000, 0.500)", e.action()));
    }

    @Test
    void shouldCheckTheMagnitudeOfASignedValueAndPrintItsSign() {
        UnsupportedActionException e = assertThrows(UnsupportedActionException.class,
                () -> move.atMost(-1.5, 1.2, "angular speed", "rad/s", "drive.max_turn_rate"));

        assertEquals("robot 'scout' cannot move(1.000, 0.500): angular speed -1.500 rad/s is above its maximum of 1.200 rad/s (drive.max_turn_rate)",
                e.getMessage());
    }

    @Test
    void shouldAcceptAValueAtItsMaximumAndReturnIt() {
        assertAll(
                () -> assertEquals(0.3, move.atMost(0.3, 0.3, "speed", "m/s", "drive.max_speed")),
                () -> assertEquals(0.3 + 1e-12, move.positiveAtMost(0.3 + 1e-12, 0.3, "speed", "m/s", "drive.max_speed"), "rounding of the caller's arithmetic"),
                () -> assertEquals(-2.0, move.finite(-2.0, "distance")));
    }

    @Test
    void shouldRefuseValuesThatAreNotNumbersOrNotPositive() {
        assertAll(
                () -> assertEquals("robot 'scout' cannot move(1.000, 0.500): distance must be a finite number, got NaN",
                        assertThrows(UnsupportedActionException.class, () -> move.finite(Double.NaN, "distance")).getMessage()),
                () -> assertEquals("robot 'scout' cannot move(1.000, 0.500): speed must be a number > 0, got 0.0",
                        assertThrows(UnsupportedActionException.class, () -> move.positive(0, "speed")).getMessage()),
                () -> assertEquals("robot 'scout' cannot move(1.000, 0.500): speed must be a number > 0, got Infinity",
                        assertThrows(UnsupportedActionException.class, () -> move.positive(Double.POSITIVE_INFINITY, "speed")).getMessage()));
    }
}
