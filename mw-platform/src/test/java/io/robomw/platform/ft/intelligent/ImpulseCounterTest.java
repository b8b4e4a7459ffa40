package io.robomw.platform.ft.intelligent;

import org.junit.jupiter.api.Test;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * The impulse counter on hand-written polls: 16 transitions per turn at 620 °/s is 27.6
 * transitions a second at full speed, one every 36 ms.
 */
class ImpulseCounterTest {

    private static final double TICKS_PER_SECOND = 620.0 * 16 / 360;

    private final ImpulseCounter counter = new ImpulseCounter(16, 620);

    /** A poll the interface took between 2.5 ms either side of a nominal on-time. */
    private void poll(boolean changed, int driven, double onMillis) {
        counter.poll(changed, driven, driven == 0 ? 1 : driven, Math.max(0, onMillis - 5) / 1000, (onMillis + 5) / 1000);
    }

    @Test
    void shouldCountEveryTransitionOfAWheelPolledEveryTenMilliseconds() {
        boolean level = false;
        double position = 0.5;
        int transitions = 0;
        for (int i = 0; i < 200; i++) {
            double next = position + 0.010 * TICKS_PER_SECOND;
            boolean changed = Math.floor(next) != Math.floor(position);
            transitions += changed ? 1 : 0;
            position = next;
            poll(changed, 1, 10);
        }
        assertEquals(position, counter.ticks(), 0.5, "within half a tick of the wheel after " + transitions + " transitions");
        assertEquals(0, counter.recovered());
    }

    @Test
    void shouldCountThePairOfTransitionsALatePollCouldNotShow() {
        poll(false, 1, 100);

        assertEquals(2, counter.recovered(), "100 ms at full speed is 2.8 ticks: the unchanged switch means two transitions, not none");
        assertTrue(counter.ticks() > 2 && counter.ticks() < 3.5, "between the second and third edge: " + counter.ticks());
    }

    @Test
    void shouldCountThreeTransitionsWhenALatePollShowsTheSwitchChanged() {
        poll(true, 1, 120);

        assertEquals(2, counter.recovered());
        assertTrue(counter.ticks() > 3 && counter.ticks() < 4, "past the third edge: " + counter.ticks());
    }

    @Test
    void shouldInventNoTransitionsForAMotorThatWasOff() {
        poll(false, 0, 500);

        assertEquals(0.5, counter.ticks(), 1e-9);
        assertEquals(0, counter.recovered());
    }

    @Test
    void shouldCrossEdgesBackwardsForAMotorDrivenBackwards() {
        poll(true, -1, 20);
        poll(false, -1, 20);
        poll(true, -1, 20);

        assertTrue(counter.ticks() < -1 && counter.ticks() > -2, "two edges below the start: " + counter.ticks());
    }

    @Test
    void shouldMoveBetweenEdgesWithTheOnTime() {
        poll(true, 1, 20);
        double justPast = counter.ticks();
        poll(false, 1, 10);

        assertTrue(counter.ticks() > justPast, "the motor was on: the wheel moved on within its tick, from " + justPast + " to " + counter.ticks());
        assertTrue(counter.ticks() <= 2, "but not past an edge the switch did not show");
    }

    @Test
    void shouldCrossAnEdgeInTheDirectionTheMotorLastTurnedWhenCoasting() {
        counter.poll(true, 0, -1, 0, 0);

        assertEquals(0, counter.ticks(), 1e-9, "just below the edge it crossed going backwards");
    }
}
