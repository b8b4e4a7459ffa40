package io.robomw.sim.legged;

import io.robomw.config.description.CommandTemplate;
import io.robomw.config.description.LeggedDrive;
import org.junit.jupiter.api.Test;

import java.util.Optional;
import java.util.Set;

import static org.junit.jupiter.api.Assertions.assertAll;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertNotEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

/** The gait model on its own, stepped by hand at 100 Hz. */
class QuadrupedTest {

    private static final double DT = 0.01;

    static LeggedDrive drive(double jitter, double slip) {
        CommandTemplate t = CommandTemplate.parse("x", Set.of());
        return new LeggedDrive(0.2, 1.2, t, t, Optional.empty(), Optional.empty(), Optional.empty(), new LeggedDrive.Gait(2.5, jitter, slip));
    }

    /** @return metres walked (the integral of the forward velocity) over the steps */
    private static double run(Quadruped dog, int steps) {
        double walked = 0;
        for (int i = 0; i < steps; i++) {
            walked += dog.linearVelocity() * DT;
            dog.advance(DT);
        }
        return walked;
    }

    @Test
    void shouldWalkForItsCommandedTimeAtItsCommandedSpeedWithoutImperfections() {
        Quadruped dog = new Quadruped(drive(0, 0), 1);

        Quadruped.Motion walk = dog.walk(0.5, 0.1);
        double walked = run(dog, 600);

        assertAll(
                () -> assertTrue(walk.ended() && walk.completed()),
                () -> assertEquals(0.5, walked, 1e-9),
                () -> assertEquals(0, dog.linearVelocity()));
    }

    @Test
    void shouldLoseTheSlipAndVaryByTheJitterStepByStepRepeatably() {
        Quadruped a = new Quadruped(drive(0.03, 0.02), 42);
        Quadruped b = new Quadruped(drive(0.03, 0.02), 42);
        Quadruped c = new Quadruped(drive(0.03, 0.02), 43);
        a.walk(0.5, 0.1);
        b.walk(0.5, 0.1);
        c.walk(0.5, 0.1);

        double wa = run(a, 600);
        double wb = run(b, 600);
        double wc = run(c, 600);

        assertEquals(wa, wb, 0, "the same seed walks the same, bit for bit");
        assertNotEquals(wa, wc, "another seed another walk");
        assertEquals(0.49, wa, 0.013, "2 % slip, jitter σ ≈ 4 mm");
    }

    /**
     * The statistics the full-stack tolerances are derived from (AiboFullStackTest, aibo.yaml's
     * gait: 2.5 steps a second, each {@code 1 + 0.03·N(0, 1)} times as fast, 2 % slip): over 400
     * seeds, a 0.5 m walk at 0.1 m/s (12.5 steps) covers 0.49 m with σ = 0.03 × 0.5 / √12.5 = 4.2 mm,
     * and a quarter turn at 1 rad/s (3.9 steps) 0.98 × π/2 rad (and up to one 10 ms physics step
     * more) with σ = 0.03 × π/2 / √3.9 = 0.024 rad.
     */
    @Test
    void shouldSpreadWalksAndTurnsAsTheGaitModelPredictsOverManySeeds() {
        int seeds = 400;
        double[] walks = new double[seeds];
        double[] turns = new double[seeds];
        for (int seed = 0; seed < seeds; seed++) {
            Quadruped w = new Quadruped(drive(0.03, 0.02), seed);
            w.walk(0.5, 0.1);
            walks[seed] = run(w, 600);
            Quadruped t = new Quadruped(drive(0.03, 0.02), seed);
            t.turn(Math.PI / 2, 1.0);
            double turned = 0;
            for (int i = 0; i < 300; i++) {
                turned += t.angularVelocity() * DT;
                t.advance(DT);
            }
            turns[seed] = turned;
        }
        double[] walk = meanAndDeviation(walks);
        double[] turn = meanAndDeviation(turns);
        String seen = String.format(java.util.Locale.ROOT, "walk %.4f m σ %.2f mm, turn %.4f rad σ %.4f rad", walk[0], walk[1] * 1000, turn[0], turn[1]);

        assertAll(
                () -> assertEquals(0.49, walk[0], 0.001, seen),
                () -> assertEquals(0.0042, walk[1], 0.0012, seen),
                // A motion ends at the first 10 ms step at or after its time: π/2 s runs 1.58 s.
                () -> assertEquals(0.98 * (Math.PI / 2 + 0.005), turn[0], 0.006, seen),
                () -> assertEquals(0.024, turn[1], 0.007, seen));
    }

    private static double[] meanAndDeviation(double[] xs) {
        double mean = java.util.Arrays.stream(xs).average().orElseThrow();
        double var = java.util.Arrays.stream(xs).map(x -> (x - mean) * (x - mean)).sum() / (xs.length - 1);
        return new double[] {mean, Math.sqrt(var)};
    }

    @Test
    void shouldEndTheCurrentMotionWhenANewOneStarts() {
        Quadruped dog = new Quadruped(drive(0, 0), 1);
        Quadruped.Motion walk = dog.walk(1, 0.1);
        run(dog, 10);

        Quadruped.Motion turn = dog.turn(Math.PI / 2, 1);

        assertTrue(walk.ended());
        assertFalse(walk.completed(), "interrupted");
        assertEquals(turn, dog.current());
        assertEquals(1.0, dog.angularVelocity(), 1e-12);
    }

    @Test
    void shouldStopADriveThatIsNotRepeatedWithinTheWatchdog() {
        Quadruped dog = new Quadruped(drive(0, 0), 1);
        dog.watchdogInterval(0.5);
        Quadruped.Motion drive = dog.drive(0.1, 0);
        run(dog, 40);
        drive = dog.drive(0.1, 0);
        run(dog, 45);
        assertFalse(drive.ended(), "repeated at 0.4 s, so running at 0.85 s");

        run(dog, 10);

        assertTrue(drive.ended());
        assertFalse(drive.completed(), "the watchdog ended it");
        assertFalse(dog.walking());
    }

    @Test
    void shouldSwingTheLegsInATrotOnlyWhileWalking() {
        Quadruped dog = new Quadruped(drive(0, 0), 1);
        double standing = dog.joint("legLF1").angle();
        run(dog, 10);
        assertEquals(standing, dog.joint("legLF1").angle(), "still legs while standing");

        dog.walk(1, 0.1);
        run(dog, 10);

        double lf = dog.joint("legLF1").angle() - 5;
        double rh = dog.joint("legRH1").angle() + 5;
        double rf = dog.joint("legRF1").angle() - 5;
        assertAll(
                () -> assertNotEquals(0, lf, 1e-6, "the left front shoulder swings"),
                () -> assertEquals(lf, rh, 1e-9, "LF and RH, one diagonal, swing together"),
                () -> assertEquals(-lf, rf, 1e-9, "RF swings the other way"));
    }

    @Test
    void shouldTakeAPostureAndMoveAJointAlongItsTrajectory() {
        Quadruped dog = new Quadruped(drive(0, 0), 1);

        Quadruped.Motion sit = dog.posture(Quadruped.Posture.SIT, 1.5);
        Quadruped.Motion pan = dog.moveJoint("headPan", 120, 0.4);
        run(dog, 20);
        double halfway = dog.joint("headPan").angle();
        run(dog, 150);

        assertAll(
                () -> assertEquals(46.5, halfway, 1e-6, "half of the way to 93°, the joint's limit"),
                () -> assertEquals(93, dog.joint("headPan").angle(), 1e-9, "clamped to the range"),
                () -> assertTrue(pan.completed() && sit.completed()),
                () -> assertEquals(Quadruped.Posture.SIT, dog.posture()),
                () -> assertEquals(Math.toRadians(35), dog.pitch(), 1e-9),
                () -> assertEquals(-100, dog.joint("legLH1").angle(), 1e-9, "the hind hips fold to sit"));
    }
}
