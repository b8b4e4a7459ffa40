package io.robomw.sim.sensing;

import java.util.Arrays;

/**
 * A uniform grid over the world for range sensing: static segments and discs (walls, obstacles)
 * indexed once, and the four edges of every robot's body re-indexed before each sensing pass.
 * A ray walks the grid cell by cell (Amanatides and Woo's traversal) and tests only what the cells
 * hold, stopping at the first cell boundary beyond its nearest hit, so a reading costs what lies
 * along its beam, not what is in the world: sensing is O(N) per pass for N robots, not O(N²).
 *
 * <p>Thread safety: {@link #castRay} may be called from many threads at once between two calls of
 * {@link #indexRobots}, which must be called by one thread while no ray is cast.
 */
public final class RangeIndex {

    /** The most grid cells an index may have (a world of 1000 m × 1000 m has about 260,000 of at least 2 m). */
    public static final int MAX_CELLS = 16 << 20;

    private final double originX;
    private final double originY;
    private final double cell;
    private final int cols;
    private final int rows;

    // static segments and discs, in compressed-row form per cell
    private final double[] sx1;
    private final double[] sy1;
    private final double[] sx2;
    private final double[] sy2;
    private final double[] cx;
    private final double[] cy;
    private final double[] cr;
    private final int[] staticStart;
    private final int[] staticItems; // >= 0 segment index, < 0: disc -(i+1)

    // robot bodies: 4 corners per robot, x and y interleaved (8 doubles, a cache line's worth, per
    // robot; edge k joins corner k and k + 1), rebuilt by indexRobots
    private double[] corners = new double[0];
    private int robotCount;
    /**
     * Per robot: the first and the last cell its body's bounding box covers (lower-left and upper-right, as row * cols +
     * column): two ints a robot, written by {@link #placeRobot} on the thread that places it and read by
     * {@link #indexPlacedRobots} on another, so as little as it can be.
     */
    private int[] robotCells = new int[0];
    private final int[] robotStart;
    private int[] robotFill = new int[0];
    /**
     * The robots of each cell, in compressed-row form by {@link #robotStart}: a robot whose body lies in that cell alone as
     * its index, one whose body spans several as {@code ~index} (negative), so that a gathering over several cells looks
     * up whether it met a robot already only for the few that span cells.
     */
    private int[] robotItems = new int[0];
    /** Per robot: its centre and the radius of its body's bounding circle, {x, y, r}, for a ray's quick miss. */
    private double[] robotCircles = new double[0];
    /** Each thread's scratch for {@link #castRays}. */
    private final ThreadLocal<Gathered> gathered = ThreadLocal.withInitial(Gathered::new);

    /**
     * @param minX     lower-left corner of the indexed area
     * @param minY     lower-left corner
     * @param width    width of the area
     * @param height   height of the area
     * @param cellSize grid cell size, metres
     * @param segments static segments as {x1, y1, x2, y2}
     * @param discs    static discs as {x, y, r}
     */
    public RangeIndex(double minX, double minY, double width, double height, double cellSize,
                      double[][] segments, double[][] discs) {
        if (!Double.isFinite(minX) || !Double.isFinite(minY) || !(width > 0) || !(height > 0) || !(cellSize > 0)
                || !Double.isFinite(width) || !Double.isFinite(height) || !Double.isFinite(cellSize)) {
            throw new IllegalArgumentException("a range index needs a finite area and cell size, got " + width + " × " + height
                    + " m at (" + minX + ", " + minY + ") in cells of " + cellSize + " m");
        }
        double cellCount = Math.ceil(width / cellSize) * Math.ceil(height / cellSize);
        if (cellCount > MAX_CELLS) {
            throw new IllegalArgumentException("a range index of " + width + " × " + height + " m in cells of " + cellSize + " m would need "
                    + (long) cellCount + " cells, more than " + MAX_CELLS + "; use larger cells or a smaller world");
        }
        for (double[] s : segments) {
            requireFinite(s, "segment");
        }
        for (double[] d : discs) {
            requireFinite(d, "disc");
        }
        this.originX = minX;
        this.originY = minY;
        this.cell = cellSize;
        this.cols = Math.max(1, (int) Math.ceil(width / cellSize));
        this.rows = Math.max(1, (int) Math.ceil(height / cellSize));
        int n = segments.length;
        sx1 = new double[n];
        sy1 = new double[n];
        sx2 = new double[n];
        sy2 = new double[n];
        for (int i = 0; i < n; i++) {
            sx1[i] = segments[i][0];
            sy1[i] = segments[i][1];
            sx2[i] = segments[i][2];
            sy2[i] = segments[i][3];
        }
        cx = new double[discs.length];
        cy = new double[discs.length];
        cr = new double[discs.length];
        for (int i = 0; i < discs.length; i++) {
            cx[i] = discs[i][0];
            cy[i] = discs[i][1];
            cr[i] = discs[i][2];
        }
        int cells = cols * rows;
        int[] count = new int[cells + 1];
        indexStatic(count, null, null);
        prefixSum(count);
        int[] items = new int[count[cells]];
        indexStatic(count, Arrays.copyOf(count, cells), items);
        staticStart = count;
        staticItems = items;
        robotStart = new int[cells + 1];
    }

    private static void requireFinite(double[] values, String what) {
        for (double v : values) {
            if (!Double.isFinite(v)) {
                throw new IllegalArgumentException("a range index " + what + " needs finite coordinates, got " + Arrays.toString(values));
            }
        }
    }

    private void indexStatic(int[] count, int[] fill, int[] items) {
        for (int i = 0; i < sx1.length; i++) {
            forCells(Math.min(sx1[i], sx2[i]), Math.min(sy1[i], sy2[i]), Math.max(sx1[i], sx2[i]), Math.max(sy1[i], sy2[i]), count, fill, items, i);
        }
        for (int i = 0; i < cx.length; i++) {
            forCells(cx[i] - cr[i], cy[i] - cr[i], cx[i] + cr[i], cy[i] + cr[i], count, fill, items, -(i + 1));
        }
    }

    /** Counts (pass 1: fill == null) or stores (pass 2) an item in every cell its box overlaps. */
    private void forCells(double minX, double minY, double maxX, double maxY, int[] count, int[] fill, int[] items, int item) {
        int c0 = clampCol(minX);
        int c1 = clampCol(maxX);
        int r0 = clampRow(minY);
        int r1 = clampRow(maxY);
        for (int r = r0; r <= r1; r++) {
            for (int c = c0; c <= c1; c++) {
                int k = r * cols + c;
                if (fill == null) {
                    count[k + 1]++;
                } else {
                    items[fill[k]++] = item;
                }
            }
        }
    }

    private static void prefixSum(int[] count) {
        for (int i = 1; i < count.length; i++) {
            count[i] += count[i - 1];
        }
    }

    private int clampCol(double x) {
        return Math.min(cols - 1, Math.max(0, (int) Math.floor((x - originX) / cell)));
    }

    private int clampRow(double y) {
        return Math.min(rows - 1, Math.max(0, (int) Math.floor((y - originY) / cell)));
    }

    /**
     * Re-indexes the robots' bodies as oriented rectangles: {@link #robots}, {@link #placeRobot}
     * for each, then {@link #indexPlacedRobots}.
     *
     * @param count   number of robots
     * @param x       centre x per robot
     * @param y       centre y per robot
     * @param heading heading per robot, radians
     * @param length  body length per robot
     * @param width   body width per robot
     */
    public void indexRobots(int count, double[] x, double[] y, double[] heading, double[] length, double[] width) {
        robots(count);
        for (int i = 0; i < count; i++) {
            placeRobot(i, x[i], y[i], heading[i], length[i], width[i]);
        }
        indexPlacedRobots();
    }

    /**
     * Sets how many robots the next {@link #indexPlacedRobots} indexes (their arrays are kept from
     * one pass to the next). One thread, while no ray is cast and no robot is placed.
     *
     * @param count the number of robots, indexed 0 to count - 1
     */
    public void robots(int count) {
        if (robotCount == count) {
            return;
        }
        corners = new double[count * 8];
        robotCircles = new double[count * 3];
        robotCells = new int[count * 2];
        robotCount = count;
        robotItems = new int[0];
        Arrays.fill(robotStart, 0);
    }

    /**
     * Places one robot's body for the next {@link #indexPlacedRobots}: its four edges and the
     * cells they cover. Robots may be placed from several threads at once, each robot by one thread,
     * while no ray is cast.
     *
     * @param i       the robot's index
     * @param x       its centre x
     * @param y       its centre y
     * @param heading its heading, radians
     * @param length  its body length
     * @param width   its body width
     */
    public void placeRobot(int i, double x, double y, double heading, double length, double width) {
        placeRobot(i, x, y, Math.cos(heading), Math.sin(heading), length, width);
    }

    /**
     * {@link #placeRobot(int, double, double, double, double, double)} with the heading's cosine and
     * sine given (a robot keeps them from its step).
     *
     * @param i      the robot's index
     * @param x      its centre x
     * @param y      its centre y
     * @param c      its heading's cosine
     * @param s      its heading's sine
     * @param length its body length
     * @param width  its body width
     */
    public void placeRobot(int i, double x, double y, double c, double s, double length, double width) {
        double hl = length / 2;
        double hw = width / 2;
        // corners in the order front-left, back-left, back-right, front-right; edge k joins corner k and k + 1
        double x0 = x + hl * c - hw * s;
        double y0 = y + hl * s + hw * c;
        double x1 = x - hl * c - hw * s;
        double y1 = y - hl * s + hw * c;
        double x2 = x - hl * c + hw * s;
        double y2 = y - hl * s - hw * c;
        double x3 = x + hl * c + hw * s;
        double y3 = y + hl * s - hw * c;
        int k = i * 8;
        double[] q = corners;
        q[k] = x0;
        q[k + 1] = y0;
        q[k + 2] = x1;
        q[k + 3] = y1;
        q[k + 4] = x2;
        q[k + 5] = y2;
        q[k + 6] = x3;
        q[k + 7] = y3;
        int m = i * 3;
        double[] circles = robotCircles;
        circles[m] = x;
        circles[m + 1] = y;
        circles[m + 2] = Math.sqrt(hl * hl + hw * hw) * (1 + 1e-9) + 1e-9; // every corner inside, whatever the rounding
        int c0 = clampCol(Math.min(Math.min(x0, x1), Math.min(x2, x3)));
        int c1 = clampCol(Math.max(Math.max(x0, x1), Math.max(x2, x3)));
        int r0 = clampRow(Math.min(Math.min(y0, y1), Math.min(y2, y3)));
        int r1 = clampRow(Math.max(Math.max(y0, y1), Math.max(y2, y3)));
        robotCells[2 * i] = r0 * cols + c0;
        robotCells[2 * i + 1] = r1 * cols + c1;
    }

    /**
     * Indexes the robots placed since {@link #robots}: each in every cell its bounding box covers,
     * in robot order. One thread, while no ray is cast; it allocates only when the index needs more
     * room than before.
     */
    public void indexPlacedRobots() {
        int cells = cols * rows;
        int[] start = robotStart;
        Arrays.fill(start, 0);
        int[] rc = robotCells;
        for (int i = 0; i < robotCount; i++) {
            int first = rc[2 * i];
            int last = rc[2 * i + 1];
            if (first == last) {
                start[first + 1]++; // most bodies lie in one cell
                continue;
            }
            int spanC = spanColumns(first, last);
            for (int k = first; k <= last; k += cols) {
                for (int j = 0; j < spanC; j++) {
                    start[k + j + 1]++;
                }
            }
        }
        prefixSum(start);
        if (robotItems.length < start[cells]) {
            robotItems = new int[start[cells] + start[cells] / 4];
        }
        if (robotFill.length != cells) {
            robotFill = new int[cells];
        }
        int[] fill = robotFill;
        System.arraycopy(start, 0, fill, 0, cells);
        int[] items = robotItems;
        for (int i = 0; i < robotCount; i++) {
            int first = rc[2 * i];
            int last = rc[2 * i + 1];
            if (first == last) {
                items[fill[first]++] = i;
                continue;
            }
            int spanC = spanColumns(first, last);
            for (int k = first; k <= last; k += cols) {
                for (int j = 0; j < spanC; j++) {
                    items[fill[k + j]++] = ~i; // in several cells
                }
            }
        }
    }

    /**
     * @param first a box's lower-left cell (row * cols + column)
     * @param last  its upper-right cell, at or after first's column
     * @return how many columns the box spans
     */
    private int spanColumns(int first, int last) {
        int d = last - first;
        return (d < cols ? d : d % cols) + 1; // within one row the difference is the columns' (no division)
    }

    /**
     * Distance along a ray to the nearest static shape or robot body other than {@code self}.
     *
     * @param ox       ray origin x
     * @param oy       ray origin y
     * @param angle    ray direction, radians
     * @param maxRange longest distance of interest
     * @param self     index of the robot casting the ray (its body is ignored), or -1
     * @return the distance to the nearest hit, or {@link Double#POSITIVE_INFINITY} if none within maxRange
     */
    public double castRay(double ox, double oy, double angle, double maxRange, int self) {
        return castRay(ox, oy, Math.cos(angle), Math.sin(angle), maxRange, self);
    }

    /**
     * {@link #castRay(double, double, double, double, int)} along a direction given by its unit vector.
     *
     * @param ox       ray origin x
     * @param oy       ray origin y
     * @param dx       the direction's x ({@code cos} of its angle)
     * @param dy       the direction's y ({@code sin} of its angle)
     * @param maxRange longest distance of interest
     * @param self     index of the robot casting the ray (its body is ignored), or -1
     * @return the distance to the nearest hit, or {@link Double#POSITIVE_INFINITY} if none within maxRange
     */
    public double castRay(double ox, double oy, double dx, double dy, double maxRange, int self) {
        double fx = (ox - originX) / cell;
        double fy = (oy - originY) / cell;
        int col = (int) Math.floor(fx);
        int row = (int) Math.floor(fy);
        int stepC = dx > 0 ? 1 : -1;
        int stepR = dy > 0 ? 1 : -1;
        double tDeltaX = dx == 0 ? Double.POSITIVE_INFINITY : cell / Math.abs(dx);
        double tDeltaY = dy == 0 ? Double.POSITIVE_INFINITY : cell / Math.abs(dy);
        double tMaxX = dx == 0 ? Double.POSITIVE_INFINITY : ((dx > 0 ? col + 1 - fx : fx - col) * cell) / Math.abs(dx);
        double tMaxY = dy == 0 ? Double.POSITIVE_INFINITY : ((dy > 0 ? row + 1 - fy : fy - row) * cell) / Math.abs(dy);
        double best = Double.POSITIVE_INFINITY;
        // The last few robots tested (a body can lie in several cells along the ray): tested once.
        int seen0 = -1;
        int seen1 = -1;
        int seen2 = -1;
        int seen3 = -1;
        double t = 0;
        while (t <= maxRange) {
            if (col >= 0 && col < cols && row >= 0 && row < rows) {
                int k = row * cols + col;
                for (int j = staticStart[k]; j < staticStart[k + 1]; j++) {
                    int item = staticItems[j];
                    double d = item >= 0 ? segment(ox, oy, dx, dy, sx1[item], sy1[item], sx2[item], sy2[item])
                            : disc(ox, oy, dx, dy, cx[-item - 1], cy[-item - 1], cr[-item - 1]);
                    if (d < best) {
                        best = d;
                    }
                }
                for (int j = robotStart[k]; j < robotStart[k + 1]; j++) {
                    int r = robotItems[j];
                    r = r >= 0 ? r : ~r;
                    if (r == self || r == seen0 || r == seen1 || r == seen2 || r == seen3) {
                        continue; // its own body, or a body already tested in a cell before (it spans several)
                    }
                    seen3 = seen2;
                    seen2 = seen1;
                    seen1 = seen0;
                    seen0 = r;
                    double[] q = corners;
                    int b = r * 8;
                    double x0 = q[b];
                    double y0 = q[b + 1];
                    double x1 = q[b + 2];
                    double y1 = q[b + 3];
                    double x2 = q[b + 4];
                    double y2 = q[b + 5];
                    double x3 = q[b + 6];
                    double y3 = q[b + 7];
                    best = nearer(best, segment(ox, oy, dx, dy, x0, y0, x1, y1));
                    best = nearer(best, segment(ox, oy, dx, dy, x1, y1, x2, y2));
                    best = nearer(best, segment(ox, oy, dx, dy, x2, y2, x3, y3));
                    best = nearer(best, segment(ox, oy, dx, dy, x3, y3, x0, y0));
                }
            } else if ((col < 0 && stepC < 0) || (col >= cols && stepC > 0) || (row < 0 && stepR < 0) || (row >= rows && stepR > 0)) {
                break;
            }
            double exit = Math.min(tMaxX, tMaxY);
            if (best <= exit) {
                break;
            }
            t = exit;
            if (tMaxX < tMaxY) {
                tMaxX += tDeltaX;
                col += stepC;
            } else {
                tMaxY += tDeltaY;
                row += stepR;
            }
        }
        return best <= maxRange ? best : Double.POSITIVE_INFINITY;
    }

    /** Most cells a gathered cast looks at per ray (beyond, each ray walks the grid on its own: long rays, small cells). */
    private static final int GATHER_CELLS_PER_RAY = 6;

    /**
     * The rays of one robot's sensors at once: what lies in the cells around all of them is
     * gathered once (each static shape and robot body once, however many cells it spans), and
     * each ray is tested against that, a body first by its bounding circle. The same distances as
     * {@link #castRay(double, double, double, double, double, int)} for each ray, bit for bit (the
     * same crossing of the same shapes; the nearest is the nearest in any order); rays long for
     * the grid's cells are cast one by one. May be called from many threads at once, as castRay.
     *
     * @param ox       each ray's origin x
     * @param oy       each ray's origin y
     * @param dx       each ray's direction's x (a unit vector)
     * @param dy       each ray's direction's y
     * @param maxRange each ray's longest distance of interest
     * @param count    how many rays (the first {@code count} of each array)
     * @param self     index of the robot casting them (its body is ignored), or -1
     * @param out      each ray's distance to its nearest hit, or {@link Double#POSITIVE_INFINITY} if none within its maxRange
     */
    public void castRays(double[] ox, double[] oy, double[] dx, double[] dy, double[] maxRange, int count, int self, double[] out) {
        castRays(ox, oy, dx, dy, maxRange, count, self, out, gathered.get());
    }

    /**
     * {@link #castRays(double[], double[], double[], double[], double[], int, int, double[])} with the calling thread's
     * scratch given (a caller that keeps one per thread saves the ThreadLocal look-up, once a robot).
     *
     * @param ox       each ray's origin x
     * @param oy       each ray's origin y
     * @param dx       each ray's direction's x (a unit vector)
     * @param dy       each ray's direction's y
     * @param maxRange each ray's longest distance of interest
     * @param count    how many rays (the first {@code count} of each array)
     * @param self     index of the robot casting them (its body is ignored), or -1
     * @param out      each ray's distance to its nearest hit, or {@link Double#POSITIVE_INFINITY} if none within its maxRange
     * @param g        scratch no other thread uses meanwhile
     */
    public void castRays(double[] ox, double[] oy, double[] dx, double[] dy, double[] maxRange, int count, int self, double[] out,
            Gathered g) {
        double minX = Double.POSITIVE_INFINITY;
        double minY = Double.POSITIVE_INFINITY;
        double maxX = Double.NEGATIVE_INFINITY;
        double maxY = Double.NEGATIVE_INFINITY;
        for (int k = 0; k < count; k++) {
            double ex = ox[k] + dx[k] * maxRange[k];
            double ey = oy[k] + dy[k] * maxRange[k];
            minX = Math.min(minX, Math.min(ox[k], ex));
            minY = Math.min(minY, Math.min(oy[k], ey));
            maxX = Math.max(maxX, Math.max(ox[k], ex));
            maxY = Math.max(maxY, Math.max(oy[k], ey));
        }
        int c0 = clampCol(minX);
        int c1 = clampCol(maxX);
        int r0 = clampRow(minY);
        int r1 = clampRow(maxY);
        if (!(count > 0) || (long) (c1 - c0 + 1) * (r1 - r0 + 1) > (long) GATHER_CELLS_PER_RAY * count + 9) {
            for (int k = 0; k < count; k++) {
                out[k] = castRay(ox[k], oy[k], dx[k], dy[k], maxRange[k], self);
            }
            return;
        }
        // The rays' reach: a circle about the middle of their box that holds every point of every ray. A body whose
        // bounding circle lies beyond it is hit by none (its crossings would all be past the rays' ranges), so it is not
        // gathered; the margin keeps that true whatever the rounding. The farthest origin plus the longest range: one
        // square root, not one a ray (no smaller than any ray's own sum, rounding being monotonic; the same when the
        // rays are equally long, as a robot's usually are).
        double mx = (minX + maxX) / 2;
        double my = (minY + maxY) / 2;
        double farthest = 0;
        double longest = 0;
        for (int k = 0; k < count; k++) {
            double ex = ox[k] - mx;
            double ey = oy[k] - my;
            farthest = Math.max(farthest, ex * ex + ey * ey);
            longest = Math.max(longest, maxRange[k]);
        }
        double reach = (Math.sqrt(farthest) + longest) * (1 + 1e-9) + 1e-9;
        castGathered(ox, oy, dx, dy, maxRange, count, self, out, g, c0, c1, r0, r1, mx, my, reach);
    }

    /**
     * {@link #castRays(double[], double[], double[], double[], double[], int, int, double[], Gathered)} with a circle
     * given that holds every point of every ray: a robot's sensors' farthest reach from its centre, known once for its
     * robot file. Its box and its circle stand for the rays' own (no minimum and maximum of every ray's ends, no
     * farthest origin): they take in every body the rays' own would and maybe more, so the distances are the same, bit
     * for bit. Worth it when the circle is about as tight as the rays' box, as for sensors all round a robot.
     *
     * @param centreX  the circle's centre x
     * @param centreY  the circle's centre y
     * @param radius   its radius: no point of a ray (origin plus up to its maxRange along it) is farther from the centre
     * @param ox       each ray's origin x
     * @param oy       each ray's origin y
     * @param dx       each ray's direction's x (a unit vector)
     * @param dy       each ray's direction's y
     * @param maxRange each ray's longest distance of interest
     * @param count    how many rays (the first {@code count} of each array)
     * @param self     index of the robot casting them (its body is ignored), or -1
     * @param out      each ray's distance to its nearest hit, or {@link Double#POSITIVE_INFINITY} if none within its maxRange
     * @param g        scratch no other thread uses meanwhile
     */
    public void castRaysWithin(double centreX, double centreY, double radius, double[] ox, double[] oy, double[] dx, double[] dy,
            double[] maxRange, int count, int self, double[] out, Gathered g) {
        // the margin keeps every point of every ray inside whatever the rounding of their origins
        double reach = radius * (1 + 1e-9) + 1e-9;
        int c0 = clampCol(centreX - reach);
        int c1 = clampCol(centreX + reach);
        int r0 = clampRow(centreY - reach);
        int r1 = clampRow(centreY + reach);
        if (!(count > 0) || (long) (c1 - c0 + 1) * (r1 - r0 + 1) > (long) GATHER_CELLS_PER_RAY * count + 9) {
            for (int k = 0; k < count; k++) {
                out[k] = castRay(ox[k], oy[k], dx[k], dy[k], maxRange[k], self);
            }
            return;
        }
        castGathered(ox, oy, dx, dy, maxRange, count, self, out, g, c0, c1, r0, r1, centreX, centreY, reach);
    }

    /**
     * The gathered cast of {@link #castRays}: what lies in cells {@code c0..c1} of rows {@code r0..r1} (each static and
     * robot once; a robot only if its bounding circle reaches the circle ({@code mx}, {@code my}, {@code reach}), which
     * holds every point of every ray), then each ray against that.
     */
    private void castGathered(double[] ox, double[] oy, double[] dx, double[] dy, double[] maxRange, int count, int self, double[] out,
            Gathered g, int c0, int c1, int r0, int r1, double mx, double my, double reach) {
        g.begin(sx1.length + cx.length, robotCount);
        int stamp = g.stamp;
        int[] staticSeen = g.staticSeen;
        int[] robotSeen = g.robotSeen;
        double[] circles = robotCircles;
        for (int r = r0; r <= r1; r++) {
            for (int c = c0; c <= c1; c++) {
                int k = r * cols + c;
                for (int j = staticStart[k]; j < staticStart[k + 1]; j++) {
                    int item = staticItems[j];
                    int slot = item >= 0 ? item : sx1.length - item - 1;
                    if (staticSeen[slot] != stamp) {
                        staticSeen[slot] = stamp;
                        g.addStatic(item);
                    }
                }
                for (int j = robotStart[k]; j < robotStart[k + 1]; j++) {
                    int b = robotItems[j];
                    if (b < 0) {
                        // a body in several cells: gathered at the first of them met, passed over at the others
                        b = ~b;
                        if (robotSeen[b] == stamp) {
                            continue;
                        }
                        robotSeen[b] = stamp;
                    }
                    if (b != self) {
                        int m = b * 3;
                        double vx = circles[m] - mx;
                        double vy = circles[m + 1] - my;
                        double near = reach + circles[m + 2];
                        if (vx * vx + vy * vy <= near * near) {
                            g.addRobot(b);
                        }
                    }
                }
            }
        }
        int[] statics = g.statics;
        int staticCount = g.staticCount;
        int[] bodies = g.robots;
        int bodyCount = g.robotCount;
        double[] q = corners;
        // the statics ray by ray, then each body against every ray (its corners loaded once); the nearest is the nearest in any order
        for (int k = 0; k < count; k++) {
            double rx = ox[k];
            double ry = oy[k];
            double ux = dx[k];
            double uy = dy[k];
            double best = Double.POSITIVE_INFINITY;
            for (int j = 0; j < staticCount; j++) {
                int item = statics[j];
                double d = item >= 0 ? segment(rx, ry, ux, uy, sx1[item], sy1[item], sx2[item], sy2[item])
                        : disc(rx, ry, ux, uy, cx[-item - 1], cy[-item - 1], cr[-item - 1]);
                best = nearer(best, d);
            }
            out[k] = best;
        }
        for (int j = 0; j < bodyCount; j++) {
            int b = bodies[j];
            int m = b * 3;
            double bx = circles[m];
            double by = circles[m + 1];
            double rad = circles[m + 2];
            for (int k = 0; k < count; k++) {
                double rx = ox[k];
                double ry = oy[k];
                double ux = dx[k];
                double uy = dy[k];
                double vx = bx - rx;
                double vy = by - ry;
                double along = vx * ux + vy * uy;
                double across = vx * uy - vy * ux;
                if (along < -rad || along > maxRange[k] + rad || across > rad || across < -rad) {
                    continue; // the ray passes the body's bounding circle by
                }
                int base = b * 8;
                double x0 = q[base];
                double y0 = q[base + 1];
                double x1 = q[base + 2];
                double y1 = q[base + 3];
                double x2 = q[base + 4];
                double y2 = q[base + 5];
                double x3 = q[base + 6];
                double y3 = q[base + 7];
                double best = out[k];
                best = nearer(best, segment(rx, ry, ux, uy, x0, y0, x1, y1));
                best = nearer(best, segment(rx, ry, ux, uy, x1, y1, x2, y2));
                best = nearer(best, segment(rx, ry, ux, uy, x2, y2, x3, y3));
                best = nearer(best, segment(rx, ry, ux, uy, x3, y3, x0, y0));
                out[k] = best;
            }
        }
        for (int k = 0; k < count; k++) {
            out[k] = out[k] <= maxRange[k] ? out[k] : Double.POSITIVE_INFINITY;
        }
    }

    /**
     * One thread's scratch for {@link #castRays}: what was gathered, and stamps that say what was gathered already. Used
     * by one thread at a time, on any index.
     */
    public static final class Gathered {
        int stamp;
        int[] staticSeen = new int[0];
        int[] robotSeen = new int[0];
        int[] statics = new int[16];
        int staticCount;
        int[] robots = new int[16];
        int robotCount;

        void begin(int staticItems, int robotItems) {
            if (staticSeen.length < staticItems) {
                staticSeen = new int[staticItems];
            }
            if (robotSeen.length < robotItems) {
                robotSeen = new int[robotItems];
            }
            if (++stamp == 0) {
                java.util.Arrays.fill(staticSeen, 0);
                java.util.Arrays.fill(robotSeen, 0);
                stamp = 1;
            }
            staticCount = 0;
            robotCount = 0;
        }

        void addStatic(int item) {
            if (staticCount == statics.length) {
                statics = java.util.Arrays.copyOf(statics, 2 * staticCount);
            }
            statics[staticCount++] = item;
        }

        void addRobot(int b) {
            if (robotCount == robots.length) {
                robots = java.util.Arrays.copyOf(robots, 2 * robotCount);
            }
            robots[robotCount++] = b;
        }
    }

    /** @return {@code d} if it is nearer than {@code best}, else {@code best} (which a NaN never replaces) */
    private static double nearer(double best, double d) {
        return d < best ? d : best;
    }

    /**
     * Ray (o + t·d, |d| = 1) against segment ab: t ≥ 0 of the crossing, or +∞. A crossing behind the
     * ray or beside the segment is refused by the signs of the two numerators and the denominator
     * before any division: their product is negative exactly when the quotient is (the quotients of
     * coordinates in metres are far from underflowing to -0), so the result is the same as dividing
     * first, bit for bit.
     */
    static double segment(double ox, double oy, double dx, double dy, double ax, double ay, double bx, double by) {
        double ex = bx - ax;
        double ey = by - ay;
        double denom = dx * ey - dy * ex;
        if (denom == 0) {
            return Double.POSITIVE_INFINITY;
        }
        double wx = ax - ox;
        double wy = ay - oy;
        double tn = wx * ey - wy * ex;
        double un = wx * dy - wy * dx;
        if (tn * denom < 0 || un * denom < 0) {
            return Double.POSITIVE_INFINITY;
        }
        double t = tn / denom;
        double u = un / denom;
        return t >= 0 && u >= 0 && u <= 1 ? t : Double.POSITIVE_INFINITY;
    }

    /** Ray against a disc: the first t ≥ 0 on its boundary, or +∞ (0 when starting inside). */
    static double disc(double ox, double oy, double dx, double dy, double x, double y, double r) {
        double px = ox - x;
        double py = oy - y;
        double b = px * dx + py * dy;
        double c = px * px + py * py - r * r;
        if (c <= 0) {
            return 0;
        }
        double disc = b * b - c;
        if (disc < 0) {
            return Double.POSITIVE_INFINITY;
        }
        double t = -b - Math.sqrt(disc);
        return t >= 0 ? t : Double.POSITIVE_INFINITY;
    }
}
