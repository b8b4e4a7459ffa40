package io.robomw.sim.physics;

import io.robomw.sim.Parallel;
import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.Test;

import java.util.ArrayList;
import java.util.List;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * The swarm engine's contacts, body by body: robots stop at walls and obstacles and do not pass
 * through them or each other, push each other as their masses say, rest without jitter, and report
 * where they are touched. Every check is on positions after whole seconds of 50 Hz steps.
 */
class SwarmPhysicsTest {

    private static final double DT = 1.0 / 50;
    /** A 0.12 m square robot of 0.3 kg, friction 0.5. */
    private static final double SIDE = 0.12;

    private final Parallel parallel = new Parallel(1);

    @AfterEach
    void close() {
        parallel.close();
    }

    private SwarmPhysics arena() {
        SwarmPhysics p = new SwarmPhysics(parallel, -1, -1, 5, 5);
        // a 4 × 4 m arena closed by 0.1 m walls: the inner faces at x = 0, x = 4, y = 0, y = 4
        p.addStaticBox(2, -0.05, 4.2, 0.1, 0);
        p.addStaticBox(2, 4.05, 4.2, 0.1, 0);
        p.addStaticBox(-0.05, 2, 0.1, 4, 0);
        p.addStaticBox(4.05, 2, 0.1, 4, 0);
        return p;
    }

    private static int robot(SwarmPhysics p, double x, double y, double heading) {
        return robot(p, x, y, heading, 0.3);
    }

    private static int robot(SwarmPhysics p, double x, double y, double heading, double mass) {
        return p.addBody(SIDE, SIDE, mass, 0.5, x, y, heading);
    }

    /** Steps for the given seconds, each body driven at its {v, w} before every step, as the world does. */
    private static void run(SwarmPhysics p, double seconds, double[]... drives) {
        int steps = (int) Math.round(seconds / DT);
        for (int s = 0; s < steps; s++) {
            for (int b = 0; b < drives.length; b++) {
                p.drive(b, drives[b][0], drives[b][1]);
            }
            p.step(DT);
        }
    }

    private static double[] drive(double v, double w) {
        return new double[] {v, w};
    }

    @Test
    void shouldStopARobotDrivingIntoAWallAtTheWall() {
        SwarmPhysics p = arena();
        int r = robot(p, 3.0, 2.0, 0);
        run(p, 8, drive(0.3, 0));
        double front = p.x(r) + SIDE / 2;
        assertTrue(front <= 4.0 + 0.005, "not through the wall: front at " + front);
        assertTrue(front >= 3.99, "at the wall: front at " + front);
        assertEquals(2.0, p.y(r), 1e-6, "straight into it, no sideways drift");
        assertEquals(1.0, p.cos(r), 1e-9, "not turned by the wall");
    }

    @Test
    void shouldStopARobotAtAnObstacleOfEveryShapeWhateverTheAngle() {
        SwarmPhysics p = new SwarmPhysics(parallel, -1, -1, 5, 5);
        p.addStaticCircle(1, 1, 0.2);
        p.addStaticPolygon(new double[][] {{2.8, 0.8}, {3.2, 0.8}, {3.0, 1.2}});
        p.addStaticBox(1, 3, 0.4, 0.4, 0.5);
        int a = robot(p, 0.3, 1, 0);
        int b = robot(p, 3.0, 0.2, Math.PI / 2);
        int c = robot(p, 1, 2.2, Math.PI / 2 + 0.2);
        run(p, 6, drive(0.3, 0), drive(0.3, 0), drive(0.3, 0));
        // the disc: its centre 0.2 + half a side ahead of the robot's centre, give or take the slop
        assertTrue(p.x(a) + SIDE / 2 <= 0.8 + 0.005 && p.x(a) + SIDE / 2 >= 0.79, "at the disc: " + p.x(a));
        // the triangle's base at y = 0.8
        assertTrue(p.y(b) + SIDE / 2 <= 0.8 + 0.005 && p.y(b) + SIDE / 2 >= 0.79, "at the triangle: " + p.y(b));
        // the turned box: the robot is held off somewhere below it, never inside its inscribed circle
        assertTrue(Math.hypot(p.x(c) - 1, p.y(c) - 3) > 0.2 + SIDE / 2 - 0.01, "outside the box: " + p.x(c) + ", " + p.y(c));
        assertTrue(p.y(c) < 3, "below the box: " + p.y(c));
    }

    @Test
    void shouldStopTwoEqualRobotsPushingHeadOnAndLetAHeavierOneWin() {
        SwarmPhysics p = arena();
        int a = robot(p, 1.5, 2, 0);
        int b = robot(p, 2.5, 2, Math.PI);
        run(p, 6, drive(0.3, 0), drive(0.3, 0));
        assertEquals(2.0, (p.x(a) + p.x(b)) / 2, 1e-6, "equal pushes: they meet and stay in the middle");
        double gap = p.x(b) - p.x(a) - SIDE;
        assertTrue(gap <= 0 && gap > -0.01, "touching, not through each other: gap " + gap);

        SwarmPhysics q = arena();
        int heavy = robot(q, 1.5, 2, 0, 0.9);
        int light = robot(q, 2.5, 2, Math.PI, 0.3);
        run(q, 3, drive(0.3, 0), drive(0.3, 0));
        double meet = q.x(light);
        run(q, 2, drive(0.3, 0), drive(0.3, 0));
        // momentum: (0.9 · 0.3 − 0.3 · 0.3) / 1.2 = 0.15 m/s towards the light one's side
        assertEquals(0.30, q.x(light) - meet, 0.02, "the heavier robot pushes the lighter one back at 0.15 m/s");
        assertTrue(q.x(light) - q.x(heavy) - SIDE > -0.01, "never through each other");
    }

    @Test
    void shouldPushAnIdleRobotSideways() {
        SwarmPhysics p = arena();
        int pusher = robot(p, 1.0, 2, 0);
        int pushed = robot(p, 1.5, 2, Math.PI / 2);
        run(p, 6, drive(0.3, 0), drive(0, 0));
        // 0.38 m to contact at 0.3 m/s, then both at 0.15 m/s for the rest of the 6 s
        assertTrue(p.x(pushed) > 1.5 + 0.5, "pushed along the pusher's heading: " + p.x(pushed));
        assertEquals(2.0, p.y(pushed), 0.01, "not sideways off the pusher's line");
        assertTrue(p.x(pushed) - p.x(pusher) - SIDE > -0.01, "never through each other");
        assertEquals(0.0, p.cos(pushed), 0.02, "pushed square-on, it does not turn");
    }

    @Test
    void shouldRestAgainstAWallWithoutJitterOrDriftForTenSeconds() {
        SwarmPhysics p = arena();
        int pressing = robot(p, 3.5, 1.0, 0);
        int idle = robot(p, 2.0, SIDE / 2 - 0.001, 0.0);
        int slanted = robot(p, 3.5, 3.5, Math.PI / 4);
        run(p, 4, drive(0.2, 0), drive(0, 0), drive(0.2, 0));
        double[] start = {p.x(pressing), p.y(pressing), p.x(idle), p.y(idle), p.x(slanted), p.y(slanted), Math.atan2(p.sin(slanted), p.cos(slanted))};
        double worst = 0;
        for (int s = 0; s < 500; s++) {
            run(p, DT, drive(0.2, 0), drive(0, 0), drive(0.2, 0));
            worst = Math.max(worst, Math.abs(p.x(pressing) - start[0]) + Math.abs(p.y(pressing) - start[1]));
            worst = Math.max(worst, Math.abs(p.x(idle) - start[2]) + Math.abs(p.y(idle) - start[3]));
        }
        assertTrue(worst < 1e-4, "pressing and idle robots stay put within 0.1 mm over 10 s: " + worst);
        // pressed into the corner at 45°, the slanted robot ends wedged against both walls, still in the arena
        assertTrue(p.x(slanted) < 4 && p.y(slanted) < 4, "inside the arena: " + p.x(slanted) + ", " + p.y(slanted));
        assertTrue(p.x(idle) == start[2] && p.atRest(idle), "an idle robot touching a wall does not move at all");
    }

    @Test
    void shouldReportContactsOnTheSideThatTouches() {
        SwarmPhysics p = arena();
        int r = robot(p, 3.5, 2, 0);
        int other = robot(p, 3.5, 2.5, 0);
        run(p, 3, drive(0.3, 0), drive(0, 0));
        List<double[]> points = new ArrayList<>();
        p.contacts(r, (x, y) -> points.add(new double[] {x, y}));
        assertEquals(2, points.size(), "a face against the wall: two points");
        for (double[] q : points) {
            assertEquals(SIDE / 2, q[0], 0.005, "on its front");
        }
        List<double[]> none = new ArrayList<>();
        p.contacts(other, (x, y) -> none.add(new double[] {x, y}));
        assertTrue(none.isEmpty(), "the robot 0.5 m away touches nothing");
    }

    @Test
    void shouldStepBitForBitTheSameOnOneTwoAndThreeThreads() {
        double[][] one = crowd(1);
        double[][] two = crowd(2);
        double[][] three = crowd(3);
        for (int k = 0; k < one.length; k++) {
            assertTrue(java.util.Arrays.equals(one[k], two[k]), "2 threads, array " + k);
            assertTrue(java.util.Arrays.equals(one[k], three[k]), "3 threads, array " + k);
        }
        assertTrue(one[3][0] > 2000, "the crowd pushed and shoved (else the solve's order proves nothing): " + one[3][0] + " contacts");
    }

    @Test
    void shouldGiveBitForBitTheSameBodiesWhenTheCallerMovesThemInAnyOrder() {
        double[][] whole = crowd(2);
        double[][] left = crowd(2, true);
        for (int k = 0; k < whole.length; k++) {
            assertTrue(java.util.Arrays.equals(whole[k], left[k]), "bodies moved by the caller, backwards: array " + k);
        }
        assertTrue(whole[3][0] > 2000, "the crowd pushed and shoved: " + whole[3][0] + " contacts");
    }

    @Test
    void shouldKeepEachBodysCosineAndSineThoseOfItsAngle() {
        SwarmPhysics p = arena();
        int a = robot(p, 1, 1, 0.3);
        int b = robot(p, 3, 3, -2.9);
        for (int s = 0; s < 400; s++) {
            p.drive(a, 0.1, 1.7);
            p.drive(b, 0.1, -2.3);
            p.step(DT);
            for (int r : new int[] {a, b}) {
                assertEquals(Double.doubleToRawLongBits(Rotation.cos(p.heading(r))), Double.doubleToRawLongBits(p.cos(r)), "cos, step " + s);
                assertEquals(Double.doubleToRawLongBits(Rotation.sin(p.heading(r))), Double.doubleToRawLongBits(p.sin(r)), "sin, step " + s);
                assertEquals(1.0, p.cos(r) * p.cos(r) + p.sin(r) * p.sin(r), 1e-12);
            }
        }
        p.drive(a, 0, 0);
        p.step(DT);
        assertTrue(p.atRest(a) && !p.atRest(b), "a body without velocity is at rest, a turning one is not");
    }

    private static double[][] crowd(int threads) {
        return crowd(threads, false);
    }

    /**
     * 1500 robots packed 0.15 m apart, each turning at its own seeded rate, detection split between
     * the given threads however few the bodies: their poses after 4 s and the contacts seen.
     *
     * @param leaveMoves whether each step leaves the bodies' moves to the caller, which moves them last to first
     */
    private static double[][] crowd(int threads, boolean leaveMoves) {
        try (Parallel workers = new Parallel(threads)) {
            SwarmPhysics p = new SwarmPhysics(workers, -1, -1, 7, 7, 0);
            p.addStaticBox(3, -0.05, 6.2, 0.1, 0);
            p.addStaticBox(3, 6.05, 6.2, 0.1, 0);
            p.addStaticBox(-0.05, 3, 0.1, 6, 0);
            p.addStaticBox(6.05, 3, 0.1, 6, 0);
            p.addStaticCircle(3, 3, 0.3);
            int n = 1500;
            java.util.SplittableRandom random = new java.util.SplittableRandom(5);
            double[] turn = new double[n];
            for (int i = 0; i < n; i++) {
                robot(p, 0.1 + 0.15 * (i % 39), 0.1 + 0.15 * (i / 39), random.nextDouble(-3, 3));
                turn[i] = random.nextDouble(-1.5, 1.5);
            }
            long contacts = 0;
            for (int s = 0; s < 200; s++) {
                for (int i = 0; i < n; i++) {
                    p.drive(i, 0.3, turn[i]);
                }
                if (leaveMoves) {
                    assertTrue(p.stepLeavingMoves(DT), "the swarm engine leaves the moves");
                    for (int i = n - 1; i >= 0; i--) {
                        p.move(i);
                    }
                } else {
                    p.step(DT);
                }
                contacts += p.contactCount();
            }
            double[] x = new double[n];
            double[] y = new double[n];
            double[] c = new double[n];
            for (int i = 0; i < n; i++) {
                x[i] = p.x(i);
                y[i] = p.y(i);
                c[i] = p.cos(i);
            }
            return new double[][] {x, y, c, {contacts}};
        }
    }

    @Test
    void shouldDriveAndTurnExactlyAsCommandedInTheOpen() {
        SwarmPhysics p = arena();
        int r = robot(p, 1, 1, 0);
        run(p, 2, drive(0.25, 0));
        assertEquals(1.5, p.x(r), 1e-9);
        run(p, Math.PI / 2, drive(0, 1.0));
        assertEquals(Math.PI / 2, Math.atan2(p.sin(r), p.cos(r)), 0.02 + 1e-9, "a quarter turn, to a step's worth");
        assertEquals(1.5, p.x(r), 1e-9, "on the spot");
    }
}
