package io.robomw.sim.world;

import java.util.ArrayList;
import java.util.Arrays;
import java.util.List;
import java.util.SplittableRandom;

/**
 * Where a swarm entry's robots start: clear of each other by construction, clear of everything
 * placed before them (obstacles, the robots placed one by one, earlier swarms), and the same for
 * the same seed on every machine.
 *
 * <h2>How</h2>
 * The area is cut into square cells, each wide enough for one robot's bounding circle (its body's
 * diagonal) plus {@value #GAP_METRES} m; a cell is free when it does not meet the bounding box of
 * anything placed before. The cells are as large as the area allows for the count (about
 * {@code sqrt(area / count)}: one robot per cell, spread over the whole area), or, where things
 * placed before take too many of them, the largest between those and the smallest that leave
 * enough free (found by halving the difference). The seed then picks {@code count} free cells (a partial
 * Fisher-Yates shuffle), and each robot starts anywhere in its cell where its circle stays inside it,
 * at a random heading (or the entry's). The robots are numbered in the cells' row-major order, so
 * robots with nearby numbers start near each other. Two robots' circles lie in different cells, so
 * they cannot overlap; the world's overlap check ({@link Placements}) still checks every robot.
 *
 * <p>Not thread-safe; one per world load.
 */
final class SwarmPlacer {

    /** The least clearance between two robots of a swarm (between their bounding circles), metres. */
    static final double GAP_METRES = 0.01;
    /** The most cells an area is cut into (16 times the most robots of a swarm). */
    static final double MAX_CELLS = 16.0 * WorldLoader.MAX_SWARM;

    /** Bounding boxes of what was placed before, {x0, y0, x1, y1} each. */
    private final List<double[]> blocked = new ArrayList<>();

    /**
     * Something swarms must keep clear of.
     *
     * @param x0 its bounding box's left edge
     * @param y0 its lower edge
     * @param x1 its right edge
     * @param y1 its upper edge
     */
    void block(double x0, double y0, double x1, double y1) {
        blocked.add(new double[] {x0, y0, x1, y1});
    }

    /**
     * A robot's body swarms must keep clear of: its bounding circle's box.
     *
     * @param x      its centre x
     * @param y      its centre y
     * @param length its body's length
     * @param width  its body's width
     */
    void blockRobot(double x, double y, double length, double width) {
        double r = Math.hypot(length, width) / 2;
        block(x - r, y - r, x + r, y + r);
    }

    /**
     * The outcome of a placement: the robots' starts, or how many would have fitted.
     *
     * @param x       centre x of each robot, or {@code null} if they do not fit
     * @param y       centre y of each
     * @param heading start heading of each, radians in [-π, π)
     * @param cell    the side of the cells, metres (of the smallest tried when they do not fit)
     * @param fitting the most robots the area holds at the smallest cells
     */
    record Placement(double[] x, double[] y, double[] heading, double cell, int fitting) {
        /** @return whether every robot found a place */
        boolean placed() {
            return x != null;
        }
    }

    /**
     * Places a swarm and blocks its robots for the swarms after it.
     *
     * @param count   how many robots
     * @param areaX   the area's lower-left corner x
     * @param areaY   its lower-left corner y
     * @param areaW   its width
     * @param areaH   its height
     * @param length  each robot's body length
     * @param width   each robot's body width
     * @param seed    the seed of the cells, places and headings
     * @param heading every robot's start heading, or NaN for a random one each
     * @return where they start, or how many would fit
     */
    Placement place(int count, double areaX, double areaY, double areaW, double areaH, double length, double width, long seed,
                    double heading) {
        // the smallest cells that fit a robot, or, in a vast area, cells few enough to list
        double smallest = Math.max(Math.hypot(length, width) + GAP_METRES, Math.sqrt(areaW * areaH / MAX_CELLS));
        double cell = Math.max(smallest, Math.sqrt(areaW * areaH / count));
        int[] free = freeCells(cell, areaX, areaY, areaW, areaH);
        if (free.length < count && cell > smallest) {
            // the largest cells between the smallest and these that leave room enough (by halves)
            int[] fits = freeCells(smallest, areaX, areaY, areaW, areaH);
            if (fits.length < count) {
                return new Placement(null, null, null, smallest, fits.length);
            }
            double small = smallest;
            double large = cell;
            for (int i = 0; i < 12; i++) {
                double mid = (small + large) / 2;
                int[] f = freeCells(mid, areaX, areaY, areaW, areaH);
                if (f.length >= count) {
                    small = mid;
                    fits = f;
                } else {
                    large = mid;
                }
            }
            cell = small;
            free = fits;
        }
        if (free.length < count) {
            return new Placement(null, null, null, cell, free.length);
        }
        int cols = (int) Math.floor(areaW / cell);
        int rows = (int) Math.floor(areaH / cell);
        double left = areaX + (areaW - cols * cell) / 2;
        double bottom = areaY + (areaH - rows * cell) / 2;
        SplittableRandom random = new SplittableRandom(seed);
        for (int k = 0; k < count; k++) {
            int j = k + random.nextInt(free.length - k);
            int t = free[k];
            free[k] = free[j];
            free[j] = t;
        }
        int[] chosen = Arrays.copyOf(free, count);
        Arrays.sort(chosen);
        double radius = Math.hypot(length, width) / 2;
        double play = cell - 2 * radius - GAP_METRES;
        double[] x = new double[count];
        double[] y = new double[count];
        double[] h = new double[count];
        for (int k = 0; k < count; k++) {
            int c = chosen[k];
            double x0 = left + (c % cols) * cell + radius + GAP_METRES / 2;
            double y0 = bottom + (c / cols) * cell + radius + GAP_METRES / 2;
            x[k] = x0 + random.nextDouble() * play;
            y[k] = y0 + random.nextDouble() * play;
            h[k] = Double.isNaN(heading) ? random.nextDouble(-Math.PI, Math.PI) : heading;
            blockRobot(x[k], y[k], length, width);
        }
        return new Placement(x, y, h, cell, count);
    }

    /** @return the row-major numbers of the cells of this side that are clear of everything blocked */
    private int[] freeCells(double cell, double areaX, double areaY, double areaW, double areaH) {
        int cols = (int) Math.floor(areaW / cell);
        int rows = (int) Math.floor(areaH / cell);
        if (cols <= 0 || rows <= 0) {
            return new int[0];
        }
        double left = areaX + (areaW - cols * cell) / 2;
        double bottom = areaY + (areaH - rows * cell) / 2;
        boolean[] taken = new boolean[cols * rows];
        for (double[] b : blocked) {
            // the cells the box meets (touching an edge is not meeting it)
            int c0 = (int) Math.max(0, Math.floor((b[0] - left) / cell));
            int c1 = (int) Math.min(cols - 1, Math.ceil((b[2] - left) / cell) - 1);
            int r0 = (int) Math.max(0, Math.floor((b[1] - bottom) / cell));
            int r1 = (int) Math.min(rows - 1, Math.ceil((b[3] - bottom) / cell) - 1);
            for (int r = r0; r <= r1; r++) {
                for (int c = c0; c <= c1; c++) {
                    taken[r * cols + c] = true;
                }
            }
        }
        int n = 0;
        for (boolean t : taken) {
            n += t ? 0 : 1;
        }
        int[] free = new int[n];
        n = 0;
        for (int i = 0; i < taken.length; i++) {
            if (!taken[i]) {
                free[n++] = i;
            }
        }
        return free;
    }
}
