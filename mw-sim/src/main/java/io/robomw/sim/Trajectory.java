package io.robomw.sim;

import java.util.Arrays;

/**
 * A robot's path, as (x, y) points appended by the simulation thread and read by renderers.
 * Appends are published through a volatile size, so a reader sees a consistent prefix.
 */
public final class Trajectory {

    private static final int MAX_POINTS = 1 << 20;

    private volatile double[] points = new double[16];
    private volatile int size;

    void add(double x, double y) {
        int n = size;
        if (n / 2 >= MAX_POINTS) {
            return;
        }
        double[] p = points;
        if (n + 2 > p.length) {
            p = Arrays.copyOf(p, p.length * 2);
            points = p;
        }
        p[n] = x;
        p[n + 1] = y;
        size = n + 2;
    }

    /** @return the points so far as {x0, y0, x1, y1, ...} */
    public double[] snapshot() {
        int n = size;
        return Arrays.copyOf(points, n);
    }
}
