package io.robomw.api;

import org.junit.jupiter.api.Test;

import java.util.SplittableRandom;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

class PoseTest {

    @Test
    void normalizeGivesTheSameAngleInMinusPiExclusiveToPiInclusive() {
        assertEquals(Math.PI, Pose.normalize(-Math.PI), 0, "-π is π");
        assertEquals(Math.PI, Pose.normalize(Math.PI), 0);
        assertEquals(Math.PI, Pose.normalize(3 * Math.PI), 1e-12);
        assertEquals(Math.PI, Pose.normalize(-3 * Math.PI), 1e-12);
        assertEquals(0.25, Pose.normalize(0.25 + 4 * Math.PI), 1e-12);
        assertEquals(-0.25, Pose.normalize(-0.25 - 6 * Math.PI), 1e-12);
        assertTrue(Double.isNaN(Pose.normalize(Double.NaN)));
        SplittableRandom random = new SplittableRandom(36);
        for (int i = 0; i < 100_000; i++) {
            double a = random.nextDouble(-1e4, 1e4);
            double n = Pose.normalize(a);
            assertTrue(n > -Math.PI && n <= Math.PI, a + " gave " + n);
            // the same angle: a whole number of turns apart
            double turns = (a - n) / (2 * Math.PI);
            assertEquals(Math.rint(turns), turns, 1e-9, a + " gave " + n);
        }
    }

    @Test
    void aPoseKeepsItsHeadingNormalized() {
        assertEquals(-Math.PI / 2, new Pose(1, 2, 3 * Math.PI / 2).heading(), 1e-12);
    }
}
