package io.robomw.sim.sensing;

import org.junit.jupiter.api.Test;

import java.util.SplittableRandom;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * The grid's ray cast gives exactly the nearest hit of a brute-force cast against every wall, disc
 * and robot body, bit for bit: its cell walk misses no shape, testing a body once per ray however
 * many cells it spans loses none, and refusing crossings by sign before dividing changes no result.
 */
class RangeIndexTest {

    @Test
    void shouldFindExactlyTheNearestHitOfABruteForceCastInACrowdedWorld() {
        SplittableRandom random = new SplittableRandom(21);
        int hits = 0;
        int rays = 0;
        for (int world = 0; world < 20; world++) {
            double size = 4 + random.nextDouble() * 6;
            double cell = 0.25 + random.nextDouble() * 0.75;
            double[][] segments = new double[6][];
            for (int i = 0; i < segments.length; i++) {
                segments[i] = new double[] {random.nextDouble() * size, random.nextDouble() * size, random.nextDouble() * size, random.nextDouble() * size};
            }
            double[][] discs = new double[4][];
            for (int i = 0; i < discs.length; i++) {
                discs[i] = new double[] {random.nextDouble() * size, random.nextDouble() * size, 0.05 + random.nextDouble() * 0.3};
            }
            int n = 60 + random.nextInt(60);
            double[] x = new double[n];
            double[] y = new double[n];
            double[] heading = new double[n];
            double[] length = new double[n];
            double[] width = new double[n];
            for (int i = 0; i < n; i++) {
                x[i] = random.nextDouble() * size;
                y[i] = random.nextDouble() * size;
                heading[i] = random.nextDouble(-Math.PI, Math.PI);
                length[i] = 0.05 + random.nextDouble() * 0.6; // some bodies span several cells
                width[i] = 0.05 + random.nextDouble() * 0.4;
            }
            RangeIndex index = new RangeIndex(-1, -1, size + 2, size + 2, cell, segments, discs);
            index.indexRobots(n, x, y, heading, length, width);
            for (int k = 0; k < 400; k++) {
                int self = random.nextInt(n + 1) - 1;
                double ox = self < 0 ? random.nextDouble() * size : x[self];
                double oy = self < 0 ? random.nextDouble() * size : y[self];
                double angle = random.nextDouble(-4, 4);
                double maxRange = 0.2 + random.nextDouble() * 3;
                double expected = bruteForce(ox, oy, angle, maxRange, self, segments, discs, x, y, heading, length, width);
                double got = index.castRay(ox, oy, angle, maxRange, self);
                assertEquals(Double.doubleToRawLongBits(expected), Double.doubleToRawLongBits(got),
                        "world " + world + ", ray " + k + " from (" + ox + ", " + oy + ") at " + angle + ": expected " + expected + ", got " + got);
                rays++;
                if (!Double.isInfinite(got)) {
                    hits++;
                }
            }
        }
        assertTrue(hits > rays / 4 && hits < rays, "most rays hit something and some hit nothing (else the test proves little): " + hits + " of " + rays);
    }

    @Test
    void shouldGiveExactlyTheDistancesOfOneRayAtATimeWhenARobotsRaysAreCastTogether() {
        SplittableRandom random = new SplittableRandom(22);
        int hits = 0;
        int rays = 0;
        for (int world = 0; world < 20; world++) {
            double size = 4 + random.nextDouble() * 6;
            double cell = 0.25 + random.nextDouble() * 0.75;
            double[][] segments = new double[6][];
            for (int i = 0; i < segments.length; i++) {
                segments[i] = new double[] {random.nextDouble() * size, random.nextDouble() * size, random.nextDouble() * size, random.nextDouble() * size};
            }
            double[][] discs = {{random.nextDouble() * size, random.nextDouble() * size, 0.05 + random.nextDouble() * 0.3},
                    {random.nextDouble() * size, random.nextDouble() * size, 0.05 + random.nextDouble() * 0.3}};
            int n = 100 + random.nextInt(200);
            double[] x = new double[n];
            double[] y = new double[n];
            double[] heading = new double[n];
            double[] length = new double[n];
            double[] width = new double[n];
            for (int i = 0; i < n; i++) {
                x[i] = random.nextDouble() * size;
                y[i] = random.nextDouble() * size;
                heading[i] = random.nextDouble(-Math.PI, Math.PI);
                length[i] = 0.05 + random.nextDouble() * 0.4;
                width[i] = 0.05 + random.nextDouble() * 0.3;
            }
            RangeIndex index = new RangeIndex(-1, -1, size + 2, size + 2, cell, segments, discs);
            index.indexRobots(n, x, y, heading, length, width);
            double[] ox = new double[12];
            double[] oy = new double[12];
            double[] dx = new double[12];
            double[] dy = new double[12];
            double[] max = new double[12];
            double[] out = new double[12];
            double[] within = new double[12];
            RangeIndex.Gathered scratch = new RangeIndex.Gathered();
            for (int k = 0; k < 300; k++) {
                int self = random.nextInt(n);
                int count = 1 + random.nextInt(12);
                // mostly short rays around the robot, sometimes long ones (cast one by one)
                double longest = random.nextInt(10) == 0 ? 4 : 0.8;
                double reach = 0;
                for (int j = 0; j < count; j++) {
                    double a = random.nextDouble(-4, 4);
                    ox[j] = x[self] + 0.05 * Math.cos(a);
                    oy[j] = y[self] + 0.05 * Math.sin(a);
                    dx[j] = Math.cos(a);
                    dy[j] = Math.sin(a);
                    max[j] = 0.1 + random.nextDouble() * longest;
                    reach = Math.max(reach, 0.05 + max[j]);
                }
                index.castRays(ox, oy, dx, dy, max, count, self, out);
                // and gathered from the circle about the robot's centre that holds them (as a robot with sensors all round is sensed)
                index.castRaysWithin(x[self], y[self], reach, ox, oy, dx, dy, max, count, self, within, scratch);
                for (int j = 0; j < count; j++) {
                    double one = index.castRay(ox[j], oy[j], dx[j], dy[j], max[j], self);
                    assertEquals(Double.doubleToRawLongBits(one), Double.doubleToRawLongBits(out[j]),
                            "world " + world + ", batch " + k + ", ray " + j + ": one at a time " + one + ", together " + out[j]);
                    assertEquals(Double.doubleToRawLongBits(one), Double.doubleToRawLongBits(within[j]),
                            "world " + world + ", batch " + k + ", ray " + j + ": one at a time " + one + ", within the robot's reach " + within[j]);
                    rays++;
                    hits += Double.isInfinite(one) ? 0 : 1;
                }
            }
        }
        assertTrue(hits > rays / 4 && hits < rays, "many rays hit something and some hit nothing (else the test proves little): " + hits + " of " + rays);
    }

    /** Every shape tried, with the textbook crossing (divide, then test). */
    private static double bruteForce(double ox, double oy, double angle, double maxRange, int self, double[][] segments, double[][] discs,
                                     double[] x, double[] y, double[] heading, double[] length, double[] width) {
        double dx = Math.cos(angle);
        double dy = Math.sin(angle);
        double best = Double.POSITIVE_INFINITY;
        for (double[] s : segments) {
            best = nearer(best, crossing(ox, oy, dx, dy, s[0], s[1], s[2], s[3]));
        }
        for (double[] d : discs) {
            best = nearer(best, RangeIndex.disc(ox, oy, dx, dy, d[0], d[1], d[2]));
        }
        for (int i = 0; i < x.length; i++) {
            if (i == self) {
                continue;
            }
            double c = Math.cos(heading[i]);
            double s = Math.sin(heading[i]);
            double hl = length[i] / 2;
            double hw = width[i] / 2;
            double[] cx = {x[i] + hl * c - hw * s, x[i] - hl * c - hw * s, x[i] - hl * c + hw * s, x[i] + hl * c + hw * s};
            double[] cy = {y[i] + hl * s + hw * c, y[i] - hl * s + hw * c, y[i] - hl * s - hw * c, y[i] + hl * s - hw * c};
            for (int e = 0; e < 4; e++) {
                best = nearer(best, crossing(ox, oy, dx, dy, cx[e], cy[e], cx[(e + 1) % 4], cy[(e + 1) % 4]));
            }
        }
        return best <= maxRange ? best : Double.POSITIVE_INFINITY;
    }

    private static double nearer(double best, double d) {
        return d < best ? d : best;
    }

    private static double crossing(double ox, double oy, double dx, double dy, double ax, double ay, double bx, double by) {
        double ex = bx - ax;
        double ey = by - ay;
        double denom = dx * ey - dy * ex;
        if (denom == 0) {
            return Double.POSITIVE_INFINITY;
        }
        double wx = ax - ox;
        double wy = ay - oy;
        double t = (wx * ey - wy * ex) / denom;
        double u = (wx * dy - wy * dx) / denom;
        return t >= 0 && u >= 0 && u <= 1 ? t : Double.POSITIVE_INFINITY;
    }
}
