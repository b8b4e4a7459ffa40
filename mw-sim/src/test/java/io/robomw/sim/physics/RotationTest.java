package io.robomw.sim.physics;

import org.junit.jupiter.api.Test;

import java.util.SplittableRandom;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

/** The swarm engine's cosine and sine agree with {@link StrictMath}'s within two ulps over a body's angles (or within 2^-59 near their zeros). */
class RotationTest {

    @Test
    void shouldAgreeWithStrictMathWithinTwoUlpsFromMinusPiToPi() {
        SplittableRandom random = new SplittableRandom(1);
        double worst = 0;
        for (int i = 0; i < 2_000_000; i++) {
            double a = i < 1000 ? -Math.PI + i * (2 * Math.PI / 999) : random.nextDouble(-Math.PI, Math.PI);
            worst = Math.max(worst, ulps(Rotation.cos(a), StrictMath.cos(a)));
            worst = Math.max(worst, ulps(Rotation.sin(a), StrictMath.sin(a)));
        }
        assertTrue(worst <= 2, "worst error " + worst + " ulps");
    }

    @Test
    void shouldGiveTheExactValuesAtTheQuarterTurns() {
        assertEquals(1.0, Rotation.cos(0));
        assertEquals(0.0, Rotation.sin(0));
        assertEquals(StrictMath.cos(Math.PI / 2), Rotation.cos(Math.PI / 2), Math.ulp(1.0));
        assertEquals(1.0, Rotation.sin(Math.PI / 2));
        assertEquals(-1.0, Rotation.cos(Math.PI));
        assertEquals(-1.0, Rotation.cos(-Math.PI));
        assertEquals(StrictMath.sin(Math.PI), Rotation.sin(Math.PI), Math.ulp(1.0));
    }

    /**
     * @return how far apart two values are, in ulps of the larger (absolute), but at least in ulps of 1/64: near a zero of the
     *         function an error far below a part in 10^17 of the body's rotation is nothing
     */
    private static double ulps(double a, double b) {
        return Math.abs(a - b) / Math.ulp(Math.max(Math.max(Math.abs(a), Math.abs(b)), 1.0 / 64));
    }
}
