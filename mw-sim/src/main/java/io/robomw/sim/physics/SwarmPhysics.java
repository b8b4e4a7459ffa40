package io.robomw.sim.physics;

import io.robomw.sim.Parallel;

import java.util.Arrays;

/**
 * A physics step of our own for swarms: robot bodies are oriented boxes driven by velocities set
 * from their wheel speeds before every step, everything else is static (walls and box, disc and
 * convex polygon obstacles). Real rigid-body contact: box-box and box-static contacts found through
 * a uniform grid (separating axes, with the incident edge clipped against the reference face for
 * up to two points per contact), resolved by sequential impulses (normal and Coulomb friction,
 * {@value #ITERATIONS} iterations) with a Baumgarte position bias beyond a {@value #SLOP} m slop, so
 * bodies do not sink into each other.
 *
 * <h2>Threads and repeatability</h2>
 * Contact detection runs on the world's worker threads ({@link Parallel}) from {@value #PARALLEL_BODIES}
 * bodies on; it works through the bodies in fixed batches of {@value #BATCH}, each writing its contacts
 * to a buffer of its own, and the buffers are joined in batch order, so the contacts and therefore
 * the sequential solve (on the stepping thread) come in the same order whatever the number of
 * threads: the same commands give the same trajectories bit for bit on 1, 2 or 3 threads. A body's
 * cosine and sine are computed in plain Java arithmetic ({@link Rotation}), so that no processor's
 * or compiler's variant of a sine changes a bit.
 *
 * <h2>What it does not model</h2>
 * No restitution (bodies do not bounce), no continuous collision detection (a body must not move
 * more than about half its own or an obstacle's thickness in one step; the world checks), no
 * warm-starting of impulses between steps, no joints, no sleeping of bodies beyond the
 * {@linkplain #atRest at-rest} flag of a body that did not move; friction is between bodies' sides
 * only (the floor's is in the drive, whose velocities are set every step), mixed as the geometric
 * mean of the two coefficients, with static bodies at {@value #STATIC_FRICTION}, as dyn4j's
 * default.
 *
 * <p>Flat arrays of primitives throughout (struct of arrays); a steady-state step allocates
 * nothing but the worker hand-overs'.
 */
public final class SwarmPhysics implements Physics {

    /** Velocity iterations of the contact solve. */
    public static final int ITERATIONS = 8;
    /** Penetration allowed without correction, metres. */
    public static final double SLOP = 0.002;
    /** Fraction of the penetration beyond the slop corrected per step. */
    public static final double BAUMGARTE = 0.2;
    /** Friction coefficient of static bodies. */
    public static final double STATIC_FRICTION = 0.2;
    /** Bodies per detection batch: fixed, so the order of contacts does not depend on the threads. */
    static final int BATCH = 32;
    /**
     * Bodies from which detection is split between the worker threads: below, a hand-over (30-80 µs
     * on the loaded 2-core machine) costs more than detection itself (about 50 ns a body).
     */
    public static final int PARALLEL_BODIES = 2048;
    /** Largest correction speed from penetration, m/s. */
    private static final double MAX_CORRECTION_SPEED = 2.0;

    private final Parallel parallel;
    private final int parallelBodies;
    private final double minX;
    private final double minY;
    private final double maxX;
    private final double maxY;

    // ---- bodies ----
    private int n;
    private double[] px = new double[0];
    private double[] py = new double[0];
    private double[] angle = new double[0];
    private double[] cs = new double[0];
    private double[] sn = new double[0];
    private double[] vx = new double[0];
    private double[] vy = new double[0];
    private double[] w = new double[0];
    private double[] invMass = new double[0];
    private double[] invInertia = new double[0];
    private double[] halfLength = new double[0];
    private double[] halfWidth = new double[0];
    private double[] friction = new double[0];
    private double[] radius = new double[0];
    private boolean[] rest = new boolean[0];
    private double maxRadius;

    // ---- statics: polygons (vertices and outward normals) and discs ----
    private int statics;
    private int[] staticStart = new int[0];
    /** Vertex count of a polygon; 0 for a disc (whose centre is at staticStart, its radius in {@link #discRadius}). */
    private int[] staticVertices = new int[0];
    private double[] discRadius = new double[0];
    private double[] staticBounds = new double[0];
    private double[] vertX = new double[0];
    private double[] vertY = new double[0];
    private double[] normX = new double[0];
    private double[] normY = new double[0];
    private int verts;

    // ---- the grid: bodies by the cell of their centre, statics by every cell their bounds cover ----
    private boolean gridStale = true;
    private double cell;
    private double inv;
    private int cols;
    private int rows;
    private int[] cellStart = new int[1];
    private int[] cellBodies = new int[0];
    private int[] cellFill = new int[0];
    /**
     * Each body's cell: of the grid as laid out at the last step, written by the body's {@link #move} (on the worker
     * thread that moved it, while its new position is in that processor's cache), so the binning on the stepping thread
     * reads one int a body instead of its position; all of them again whenever the grid is laid out anew.
     */
    private int[] bodyCell = new int[0];
    /** Each body's place in {@link #cellBodies}, from the last binning (detection starts there: the bodies after it in its cell). */
    private int[] bodySlot = new int[0];
    /**
     * Each body's centre and radius in one place, {x, y, r} by body (written where its position is: {@link #addBody},
     * {@link #move}): detection reads a neighbour's in one cache line, and the binning on the stepping thread copies
     * nothing (a cell-ordered copy made there read every body's position just written by another processor).
     */
    private double[] bodyXYR = new double[0];
    /** Whether {@link #bodyCell} holds every body's cell in the grid as it is laid out (false until a step has binned them). */
    private boolean cellsKnown;
    private int[] staticCellStart = new int[1];
    private int[] staticCells = new int[0];
    private int[] staticCellRange = new int[0];
    /**
     * Per cell: whether it or one of its eight neighbours holds a static. A body's bounds (at most a cell wide) lie in the
     * cell of its centre and its neighbours, so a body whose cell has none touches no static.
     */
    private boolean[] staticNear = new boolean[0];

    // ---- contacts of the step, in a fixed order ----
    private ContactBuffer[] batches = new ContactBuffer[0];
    private final ContactBuffer contacts = new ContactBuffer();
    private int[] bodyContactStart = new int[1];
    /**
     * Whether {@link #bodyContactStart} lists the last step's contacts by body: made by the first {@link #contacts} call
     * after a step (a robot with touch sensors asks), not by every step (a pass over every body, on the stepping thread,
     * that a swarm without touch sensors never reads).
     */
    private volatile boolean contactsIndexed;
    private int[] bodyContacts = new int[0];
    private double stepSeconds;

    /**
     * @param parallel the world's worker threads
     * @param minX     the region where bodies are expected (outside it they are still simulated, more slowly)
     * @param minY     its lower edge
     * @param maxX     its right edge
     * @param maxY     its upper edge
     */
    public SwarmPhysics(Parallel parallel, double minX, double minY, double maxX, double maxY) {
        this(parallel, minX, minY, maxX, maxY, PARALLEL_BODIES);
    }

    /**
     * @param parallel       the world's worker threads
     * @param minX           the region where bodies are expected
     * @param minY           its lower edge
     * @param maxX           its right edge
     * @param maxY           its upper edge
     * @param parallelBodies the fewest bodies whose detection is split between the workers (tests split small worlds)
     */
    public SwarmPhysics(Parallel parallel, double minX, double minY, double maxX, double maxY, int parallelBodies) {
        this.parallel = parallel;
        this.parallelBodies = parallelBodies;
        this.minX = minX;
        this.minY = minY;
        this.maxX = maxX;
        this.maxY = maxY;
    }

    // ---------------------------------------------------------------- building

    @Override
    public void addStaticBox(double x, double y, double width, double height, double angle) {
        double c = StrictMath.cos(angle);
        double s = StrictMath.sin(angle);
        double hw = width / 2;
        double hh = height / 2;
        double[][] local = {{hw, -hh}, {hw, hh}, {-hw, hh}, {-hw, -hh}};
        double[][] world = new double[4][];
        for (int i = 0; i < 4; i++) {
            world[i] = new double[] {x + local[i][0] * c - local[i][1] * s, y + local[i][0] * s + local[i][1] * c};
        }
        addStaticPolygon(world);
    }

    @Override
    public void addStaticCircle(double x, double y, double r) {
        int s = newStatic();
        ensureVertices(verts + 1);
        staticStart[s] = verts;
        staticVertices[s] = 0;
        discRadius[s] = r;
        vertX[verts] = x;
        vertY[verts] = y;
        verts++;
        setBounds(s, x - r, y - r, x + r, y + r);
    }

    @Override
    public void addStaticPolygon(double[][] points) {
        int s = newStatic();
        int k = points.length;
        ensureVertices(verts + k);
        staticStart[s] = verts;
        staticVertices[s] = k;
        double x0 = Double.POSITIVE_INFINITY;
        double y0 = Double.POSITIVE_INFINITY;
        double x1 = Double.NEGATIVE_INFINITY;
        double y1 = Double.NEGATIVE_INFINITY;
        for (int i = 0; i < k; i++) {
            double[] a = points[i];
            double[] b = points[(i + 1) % k];
            double ex = b[0] - a[0];
            double ey = b[1] - a[1];
            double len = Math.sqrt(ex * ex + ey * ey);
            vertX[verts + i] = a[0];
            vertY[verts + i] = a[1];
            normX[verts + i] = ey / len;
            normY[verts + i] = -ex / len;
            x0 = Math.min(x0, a[0]);
            y0 = Math.min(y0, a[1]);
            x1 = Math.max(x1, a[0]);
            y1 = Math.max(y1, a[1]);
        }
        verts += k;
        setBounds(s, x0, y0, x1, y1);
    }

    private int newStatic() {
        if (statics == staticStart.length) {
            int m = Math.max(8, statics * 2);
            staticStart = Arrays.copyOf(staticStart, m);
            staticVertices = Arrays.copyOf(staticVertices, m);
            discRadius = Arrays.copyOf(discRadius, m);
            staticBounds = Arrays.copyOf(staticBounds, 4 * m);
        }
        gridStale = true;
        return statics++;
    }

    private void setBounds(int s, double x0, double y0, double x1, double y1) {
        staticBounds[4 * s] = x0;
        staticBounds[4 * s + 1] = y0;
        staticBounds[4 * s + 2] = x1;
        staticBounds[4 * s + 3] = y1;
    }

    private void ensureVertices(int m) {
        if (m > vertX.length) {
            int c = Math.max(m, vertX.length * 2);
            vertX = Arrays.copyOf(vertX, c);
            vertY = Arrays.copyOf(vertY, c);
            normX = Arrays.copyOf(normX, c);
            normY = Arrays.copyOf(normY, c);
        }
    }

    @Override
    public int addBody(double length, double width, double mass, double mu, double x, double y, double heading) {
        if (n == px.length) {
            int m = Math.max(16, n * 2);
            px = Arrays.copyOf(px, m);
            py = Arrays.copyOf(py, m);
            angle = Arrays.copyOf(angle, m);
            cs = Arrays.copyOf(cs, m);
            sn = Arrays.copyOf(sn, m);
            vx = Arrays.copyOf(vx, m);
            vy = Arrays.copyOf(vy, m);
            w = Arrays.copyOf(w, m);
            invMass = Arrays.copyOf(invMass, m);
            invInertia = Arrays.copyOf(invInertia, m);
            halfLength = Arrays.copyOf(halfLength, m);
            halfWidth = Arrays.copyOf(halfWidth, m);
            friction = Arrays.copyOf(friction, m);
            radius = Arrays.copyOf(radius, m);
            rest = Arrays.copyOf(rest, m);
            bodyCell = Arrays.copyOf(bodyCell, m);
            bodySlot = Arrays.copyOf(bodySlot, m);
            bodyXYR = Arrays.copyOf(bodyXYR, 3 * m);
        }
        int i = n++;
        px[i] = x;
        py[i] = y;
        angle[i] = wrap(heading);
        cs[i] = Rotation.cos(angle[i]);
        sn[i] = Rotation.sin(angle[i]);
        invMass[i] = 1 / mass;
        invInertia[i] = 12 / (mass * (length * length + width * width));
        halfLength[i] = length / 2;
        halfWidth[i] = width / 2;
        friction[i] = mu;
        radius[i] = Math.sqrt(length * length + width * width) / 2;
        rest[i] = true;
        if (radius[i] > maxRadius) {
            maxRadius = radius[i];
        }
        bodyXYR[3 * i] = x;
        bodyXYR[3 * i + 1] = y;
        bodyXYR[3 * i + 2] = radius[i];
        gridStale = true;
        return i;
    }

    private static double wrap(double a) {
        if (a > Math.PI || a < -Math.PI) {
            a = a - 2 * Math.PI * Math.floor((a + Math.PI) / (2 * Math.PI));
        }
        return a;
    }

    // ---------------------------------------------------------------- queries

    @Override
    public double x(int body) {
        return px[body];
    }

    @Override
    public double y(int body) {
        return py[body];
    }

    @Override
    public double cos(int body) {
        return cs[body];
    }

    @Override
    public double sin(int body) {
        return sn[body];
    }

    /** @return the body's angle as the engine integrates it, in [-π, π] (its cosine and sine are computed from it) */
    @Override
    public double heading(int body) {
        return angle[body];
    }

    @Override
    public double vx(int body) {
        return vx[body];
    }

    @Override
    public double vy(int body) {
        return vy[body];
    }

    @Override
    public boolean atRest(int body) {
        return rest[body];
    }

    @Override
    public void drive(int body, double v, double omega) {
        vx[body] = v * cs[body];
        vy[body] = v * sn[body];
        w[body] = omega;
    }

    @Override
    public void setVelocity(int body, double vx, double vy, double omega) {
        this.vx[body] = vx;
        this.vy[body] = vy;
        w[body] = omega;
    }

    @Override
    public void contacts(int body, ContactSink sink) {
        if (!contactsIndexed) {
            indexContactsOnce();
        }
        if (body + 1 >= bodyContactStart.length) {
            return; // added since the last step: it has touched nothing yet
        }
        ContactBuffer c = contacts;
        double x = px[body];
        double y = py[body];
        double co = cs[body];
        double si = sn[body];
        for (int k = bodyContactStart[body]; k < bodyContactStart[body + 1]; k++) {
            int ci = bodyContacts[k];
            for (int p = 0; p < c.points[ci]; p++) {
                double dx = c.pointX[2 * ci + p] - x;
                double dy = c.pointY[2 * ci + p] - y;
                sink.point(dx * co + dy * si, -dx * si + dy * co);
            }
        }
    }

    /** @return the contacts of the last step (for tests and diagnosis) */
    public int contactCount() {
        return contacts.size;
    }

    // ---------------------------------------------------------------- the step

    @Override
    public void step(double dt) {
        stepLeavingMoves(dt);
        for (int i = 0; i < n; i++) {
            move(i);
        }
    }

    /**
     * The step but the bodies' moves: contacts, their resolution, each body's list of contacts; the
     * caller then {@linkplain #move moves} every body (the world does it in its pass over the robots,
     * on the worker threads, where it reads the new poses).
     *
     * @return {@code true}: every body must be moved
     */
    @Override
    public boolean stepLeavingMoves(double dt) {
        stepSeconds = dt;
        if (gridStale) {
            layOutGrid();
        }
        binBodies();
        int batchCount = (n + BATCH - 1) / BATCH;
        if (batches.length < batchCount) {
            ContactBuffer[] more = Arrays.copyOf(batches, batchCount);
            for (int b = batches.length; b < batchCount; b++) {
                more[b] = new ContactBuffer();
            }
            batches = more;
        }
        if (n >= parallelBodies) {
            parallel.forEachBatch(batchCount, this::detect);
        } else {
            for (int b = 0; b < batchCount; b++) {
                detect(b);
            }
        }
        contacts.clear();
        for (int b = 0; b < batchCount; b++) {
            contacts.append(batches[b]);
        }
        solve();
        contactsIndexed = false;
        return true;
    }

    /** Chooses the grid's cells (at least a body's diameter wide) and puts each static in the cells it covers. */
    private void layOutGrid() {
        double width = Math.max(maxX - minX, 1e-3);
        double height = Math.max(maxY - minY, 1e-3);
        double byBodies = n == 0 ? 0 : Math.sqrt(width * height / n) / 2;
        cell = Math.max(Math.max(2 * maxRadius, byBodies), 1e-3);
        while ((width / cell + 1) * (height / cell + 1) > 4.0 * Math.max(n, 1024)) {
            cell *= 1.5;
        }
        inv = 1 / cell;
        cellsKnown = false;
        // an empty guard column on either side and an empty guard row on top: detection reads a body's neighbour cells
        // without asking whether it is at an edge (see detect)
        cols = (int) Math.ceil(width * inv) + 3;
        rows = (int) Math.ceil(height * inv) + 2;
        int cells = cols * rows;
        cellStart = new int[cells + 1];
        staticCellRange = new int[4 * statics];
        int[] count = new int[cells + 1];
        for (int s = 0; s < statics; s++) {
            int x0 = col(staticBounds[4 * s]);
            int y0 = row(staticBounds[4 * s + 1]);
            int x1 = col(staticBounds[4 * s + 2]);
            int y1 = row(staticBounds[4 * s + 3]);
            staticCellRange[4 * s] = x0;
            staticCellRange[4 * s + 1] = y0;
            staticCellRange[4 * s + 2] = x1;
            staticCellRange[4 * s + 3] = y1;
            for (int cy = y0; cy <= y1; cy++) {
                for (int cx = x0; cx <= x1; cx++) {
                    count[cy * cols + cx + 1]++;
                }
            }
        }
        for (int c = 0; c < cells; c++) {
            count[c + 1] += count[c];
        }
        staticCellStart = count.clone();
        staticNear = new boolean[cells];
        for (int cy = 0; cy < rows; cy++) {
            for (int cx = 0; cx < cols; cx++) {
                if (count[cy * cols + cx + 1] == count[cy * cols + cx]) {
                    continue;
                }
                for (int ny = Math.max(0, cy - 1); ny <= Math.min(rows - 1, cy + 1); ny++) {
                    for (int nx = Math.max(0, cx - 1); nx <= Math.min(cols - 1, cx + 1); nx++) {
                        staticNear[ny * cols + nx] = true;
                    }
                }
            }
        }
        staticCells = new int[count[cells]];
        int[] fill = Arrays.copyOf(count, cells);
        for (int s = 0; s < statics; s++) {
            for (int cy = staticCellRange[4 * s + 1]; cy <= staticCellRange[4 * s + 3]; cy++) {
                for (int cx = staticCellRange[4 * s]; cx <= staticCellRange[4 * s + 2]; cx++) {
                    staticCells[fill[cy * cols + cx]++] = s;
                }
            }
        }
        gridStale = false;
    }

    // (int) rounds towards zero: a coordinate up to a cell before the region's edge also lands in the
    // first cell, where the clamp would put it anyway; nothing lands in the guard cells (column 0, the last column, the
    // last row), which stay empty

    private int col(double x) {
        int c = (int) ((x - minX) * inv) + 1;
        return c < 1 ? 1 : Math.min(c, cols - 2);
    }

    private int row(double y) {
        int r = (int) ((y - minY) * inv);
        return r < 0 ? 0 : Math.min(r, rows - 2);
    }

    /**
     * Sorts the bodies by the cell of their centre (a counting sort, in body order within a cell), from the cells their
     * moves found ({@link #bodyCell}), or found here after the grid was laid out anew.
     */
    private void binBodies() {
        int cells = cols * rows;
        if (cellBodies.length < n) {
            cellBodies = new int[px.length];
        }
        if (cellFill.length != cells) {
            cellFill = new int[cells];
        }
        int[] start = cellStart;
        Arrays.fill(start, 0);
        if (!cellsKnown) {
            for (int i = 0; i < n; i++) {
                bodyCell[i] = cellOf(px[i], py[i]);
            }
            cellsKnown = true;
        }
        for (int i = 0; i < n; i++) {
            start[bodyCell[i] + 1]++;
        }
        for (int c = 0; c < cells; c++) {
            start[c + 1] += start[c];
        }
        int[] fill = cellFill;
        System.arraycopy(start, 0, fill, 0, cells);
        int[] slot = bodySlot;
        for (int i = 0; i < n; i++) {
            int k = fill[bodyCell[i]]++;
            cellBodies[k] = i;
            slot[i] = k;
        }
    }

    /** @return the grid cell of a point (see {@link #col}, {@link #row}) */
    private int cellOf(double x, double y) {
        return row(y) * cols + col(x);
    }

    /**
     * Finds the contacts of the bodies of one batch: each with the bodies after it in its own cell and
     * with every body of the four cells after its own (east, and the three to the north), so that each
     * pair of neighbouring bodies is tested once; and with the statics of its cells.
     *
     * <p>Those cells are two runs of the cell-ordered body list: its own cell and the east one are
     * neighbours in it, and so are the three to the north. So each body looks at two ranges rather
     * than five cells (at one robot a square metre, most cells are empty: per cell, the tests of
     * where it is and whether it is empty cost more than its bodies); the guard cells around the
     * grid, always empty, spare the tests of the edges. The same pairs in the same order as cell by
     * cell: the contacts, and so the solver's order, are unchanged.
     */
    private void detect(int batch) {
        ContactBuffer out = batches[batch];
        out.clear();
        int from = batch * BATCH;
        int to = Math.min(n, from + BATCH);
        int[] start = cellStart;
        int[] cellOf = bodyCell;
        int[] slot = bodySlot;
        int north = cols;
        for (int i = from; i < to; i++) {
            int c = cellOf[i]; // as binBodies found it
            // the bodies after i in its own cell (a cell lists its bodies in ascending order), then the east cell's
            boolean cornersDone = near(out, i, slot[i] + 1, start[c + 2], false);
            // the three cells to the north, west to east
            cornersDone = near(out, i, start[c + north - 1], start[c + north + 2], cornersDone);
            if (statics > 0 && staticNear[c]) {
                detectStatics(out, i, out.scratchA, cornersDone);
            }
        }
        out.prepare(this);
    }

    /**
     * Tests body {@code i} against the bodies at {@code from} to {@code to} (exclusive) of the cell-ordered list: a
     * pair whose bounding circles overlap is collided as boxes.
     *
     * @param cornersDone whether {@code i}'s corners are in {@code out.scratchA} already
     * @return whether they are now
     */
    private boolean near(ContactBuffer out, int i, int from, int to, boolean cornersDone) {
        int[] members = cellBodies;
        double[] xyr = bodyXYR;
        double xi = xyr[3 * i];
        double yi = xyr[3 * i + 1];
        double ri = xyr[3 * i + 2];
        for (int k = from; k < to; k++) {
            int j = members[k];
            double dx = xyr[3 * j] - xi;
            double dy = xyr[3 * j + 1] - yi;
            double r = ri + xyr[3 * j + 2];
            if (dx * dx + dy * dy >= r * r) {
                continue;
            }
            if (!cornersDone) {
                corners(i, out.scratchA);
                cornersDone = true;
            }
            corners(j, out.scratchB);
            collidePolygons(out, i, j, out.scratchA, 4, out.scratchB, 4, j);
        }
        return cornersDone;
    }

    private void detectStatics(ContactBuffer out, int i, double[] a, boolean cornersDone) {
        double r = radius[i];
        double bx0 = px[i] - r;
        double by0 = py[i] - r;
        double bx1 = px[i] + r;
        double by1 = py[i] + r;
        int x0 = col(bx0);
        int y0 = row(by0);
        int x1 = col(bx1);
        int y1 = row(by1);
        for (int cy = y0; cy <= y1; cy++) {
            for (int cx = x0; cx <= x1; cx++) {
                int c = cy * cols + cx;
                for (int k = staticCellStart[c], end = staticCellStart[c + 1]; k < end; k++) {
                    int s = staticCells[k];
                    // each static once: from the first of the body's cells that it covers
                    if (cx != Math.max(x0, staticCellRange[4 * s]) || cy != Math.max(y0, staticCellRange[4 * s + 1])) {
                        continue;
                    }
                    if (staticBounds[4 * s] > bx1 || staticBounds[4 * s + 2] < bx0
                            || staticBounds[4 * s + 1] > by1 || staticBounds[4 * s + 3] < by0) {
                        continue;
                    }
                    int count = staticVertices[s];
                    if (count == 0) {
                        collideDisc(out, i, s);
                    } else {
                        if (!cornersDone) {
                            corners(i, a);
                            cornersDone = true;
                        }
                        collidePolygons(out, i, -1 - s, a, 4, null, count, staticStart[s]);
                    }
                }
            }
        }
    }

    /** A body's corners, anti-clockwise from front right: {x0, y0, x1, y1, ...}. */
    private void corners(int i, double[] out) {
        double c = cs[i];
        double s = sn[i];
        double hl = halfLength[i];
        double hw = halfWidth[i];
        double x = px[i];
        double y = py[i];
        // local (hl, -hw), (hl, hw), (-hl, hw), (-hl, -hw)
        double lx = hl * c;
        double ly = hl * s;
        double wx = -hw * s;
        double wy = hw * c;
        out[0] = x + lx - wx;
        out[1] = y + ly - wy;
        out[2] = x + lx + wx;
        out[3] = y + ly + wy;
        out[4] = x - lx + wx;
        out[5] = y - ly + wy;
        out[6] = x - lx - wx;
        out[7] = y - ly - wy;
    }

    /** The outward normal of edge e (from corner e to e + 1) of body i's box. */
    private double boxNormalX(int i, int e) {
        return switch (e) {
            case 0 -> cs[i];
            case 1 -> -sn[i];
            case 2 -> -cs[i];
            default -> sn[i];
        };
    }

    private double boxNormalY(int i, int e) {
        return switch (e) {
            case 0 -> sn[i];
            case 1 -> cs[i];
            case 2 -> -sn[i];
            default -> -cs[i];
        };
    }

    // A polygon for the collision routine: either a body's box (vertices in a scratch array, normals
    // from its rotation) or a static polygon (vertices and normals in the static arrays, from an offset).

    private double vx(double[] v, int base, int k) {
        return v != null ? v[2 * k] : vertX[base + k];
    }

    private double vy(double[] v, int base, int k) {
        return v != null ? v[2 * k + 1] : vertY[base + k];
    }

    private double nx(double[] v, int base, int k) {
        return v != null ? boxNormalX(base, k) : normX[base + k];
    }

    private double ny(double[] v, int base, int k) {
        return v != null ? boxNormalY(base, k) : normY[base + k];
    }

    /**
     * The greatest separation of polygon 2 from the edges of polygon 1 (negative: overlap along every
     * edge normal of 1); the edge in {@code edgeOut[0]}.
     */
    private double maxSeparation(double[] v1, int base1, int n1, double[] v2, int base2, int n2, int[] edgeOut) {
        double best = Double.NEGATIVE_INFINITY;
        int bestEdge = 0;
        for (int e = 0; e < n1; e++) {
            double nxe = nx(v1, base1, e);
            double nye = ny(v1, base1, e);
            double ox = vx(v1, base1, e);
            double oy = vy(v1, base1, e);
            double min = Double.POSITIVE_INFINITY;
            for (int k = 0; k < n2; k++) {
                double d = nxe * (vx(v2, base2, k) - ox) + nye * (vy(v2, base2, k) - oy);
                if (d < min) {
                    min = d;
                }
            }
            if (min > best) {
                best = min;
                bestEdge = e;
            }
        }
        edgeOut[0] = bestEdge;
        return best;
    }

    /**
     * Two convex polygons, body {@code i}'s box (vertices {@code a}) and either body {@code j}'s box
     * (vertices {@code b}, {@code base2} = j) or static {@code -1 - other} ({@code b} null, its
     * vertices from {@code base2}): separating axes, then the incident edge clipped against the
     * reference face's sides, up to two points.
     */
    private void collidePolygons(ContactBuffer out, int i, int other, double[] a, int n1, double[] b, int n2, int base2) {
        int[] edge = out.edge;
        double sepA = maxSeparation(a, i, n1, b, base2, n2, edge);
        if (sepA > 0) {
            return;
        }
        int edgeA = edge[0];
        double sepB = maxSeparation(b, base2, n2, a, i, n1, edge);
        if (sepB > 0) {
            return;
        }
        int edgeB = edge[0];
        // reference polygon: the one whose face separates most (A unless B's is clearly better)
        boolean flip = sepB > sepA + 0.1 * SLOP;
        double[] rv = flip ? b : a;
        int rBase = flip ? base2 : i;
        int rn = flip ? n2 : n1;
        int re = flip ? edgeB : edgeA;
        double[] iv = flip ? a : b;
        int iBase = flip ? i : base2;
        int in = flip ? n1 : n2;
        double refNx = nx(rv, rBase, re);
        double refNy = ny(rv, rBase, re);
        // incident edge: the one of the other polygon most against the reference normal
        int ie = 0;
        double minDot = Double.POSITIVE_INFINITY;
        for (int k = 0; k < in; k++) {
            double d = refNx * nx(iv, iBase, k) + refNy * ny(iv, iBase, k);
            if (d < minDot) {
                minDot = d;
                ie = k;
            }
        }
        int ie2 = ie + 1 == in ? 0 : ie + 1;
        double[] cp = out.clip;
        cp[0] = vx(iv, iBase, ie);
        cp[1] = vy(iv, iBase, ie);
        cp[2] = vx(iv, iBase, ie2);
        cp[3] = vy(iv, iBase, ie2);
        int re2 = re + 1 == rn ? 0 : re + 1;
        double v1x = vx(rv, rBase, re);
        double v1y = vy(rv, rBase, re);
        double v2x = vx(rv, rBase, re2);
        double v2y = vy(rv, rBase, re2);
        double tx = v2x - v1x;
        double ty = v2y - v1y;
        double len = Math.sqrt(tx * tx + ty * ty);
        tx /= len;
        ty /= len;
        // keep t·p >= t·v1 and t·p <= t·v2
        if (!clip(cp, -tx, -ty, -(tx * v1x + ty * v1y)) || !clip(cp, tx, ty, tx * v2x + ty * v2y)) {
            return;
        }
        double front = refNx * v1x + refNy * v1y;
        double nxAB = flip ? -refNx : refNx;
        double nyAB = flip ? -refNy : refNy;
        int points = 0;
        double p0x = 0;
        double p0y = 0;
        double d0 = 0;
        double p1x = 0;
        double p1y = 0;
        double d1 = 0;
        for (int k = 0; k < 2; k++) {
            double qx = cp[2 * k];
            double qy = cp[2 * k + 1];
            double sep = refNx * qx + refNy * qy - front;
            if (sep <= 0) {
                // midway between the incident point and the reference face
                double mx = qx - refNx * sep / 2;
                double my = qy - refNy * sep / 2;
                if (points == 0) {
                    p0x = mx;
                    p0y = my;
                    d0 = -sep;
                } else {
                    p1x = mx;
                    p1y = my;
                    d1 = -sep;
                }
                points++;
            }
        }
        if (points > 0) {
            out.add(i, other, nxAB, nyAB, points, p0x, p0y, d0, p1x, p1y, d1, mix(i, other));
        }
    }

    /**
     * Clips the segment in {@code cp} to the half plane n·p <= offset.
     *
     * @return whether two points are left
     */
    private static boolean clip(double[] cp, double nx, double ny, double offset) {
        double d0 = nx * cp[0] + ny * cp[1] - offset;
        double d1 = nx * cp[2] + ny * cp[3] - offset;
        if (d0 <= 0 && d1 <= 0) {
            return true;
        }
        if (d0 > 0 && d1 > 0) {
            return false;
        }
        double t = d0 / (d0 - d1);
        double x = cp[0] + t * (cp[2] - cp[0]);
        double y = cp[1] + t * (cp[3] - cp[1]);
        if (d0 > 0) {
            cp[0] = x;
            cp[1] = y;
        } else {
            cp[2] = x;
            cp[3] = y;
        }
        return true;
    }

    /** Body i's box against static disc s. */
    private void collideDisc(ContactBuffer out, int i, int s) {
        int v = staticStart[s];
        double r = discRadius[s];
        double dx = vertX[v] - px[i];
        double dy = vertY[v] - py[i];
        double c = cs[i];
        double si = sn[i];
        double lx = dx * c + dy * si;
        double ly = -dx * si + dy * c;
        double hl = halfLength[i];
        double hw = halfWidth[i];
        double nlx;
        double nly;
        double depth;
        double qx;
        double qy;
        if (Math.abs(lx) <= hl && Math.abs(ly) <= hw) {
            // the centre inside the box: out through the nearest face
            double fx = hl - Math.abs(lx);
            double fy = hw - Math.abs(ly);
            if (fx < fy) {
                nlx = lx >= 0 ? 1 : -1;
                nly = 0;
                depth = r + fx;
                qx = nlx * hl;
                qy = ly;
            } else {
                nlx = 0;
                nly = ly >= 0 ? 1 : -1;
                depth = r + fy;
                qx = lx;
                qy = nly * hw;
            }
        } else {
            qx = Math.max(-hl, Math.min(hl, lx));
            qy = Math.max(-hw, Math.min(hw, ly));
            double ex = lx - qx;
            double ey = ly - qy;
            double dist = Math.sqrt(ex * ex + ey * ey);
            if (dist >= r) {
                return;
            }
            nlx = ex / dist;
            nly = ey / dist;
            depth = r - dist;
        }
        double nwx = nlx * c - nly * si;
        double nwy = nlx * si + nly * c;
        // the point midway between the box's surface and the disc's
        double mx = qx + nlx * depth / 2;
        double my = qy + nly * depth / 2;
        double wx = px[i] + mx * c - my * si;
        double wy = py[i] + mx * si + my * c;
        out.add(i, -1 - s, nwx, nwy, 1, wx, wy, depth, 0, 0, 0, mix(i, -1 - s));
    }

    private double mix(int i, int other) {
        double f = other >= 0 ? friction[other] : STATIC_FRICTION;
        return Math.sqrt(friction[i] * f);
    }

    /** Sequential impulses over every contact, in their fixed order. */
    private void solve() {
        ContactBuffer c = contacts;
        int m = c.size;
        for (int it = 0; it < ITERATIONS; it++) {
            for (int k = 0; k < m; k++) {
                int a = c.bodyA[k];
                int b = c.bodyB[k];
                boolean dynamicB = b >= 0;
                double nx = c.normalX[k];
                double ny = c.normalY[k];
                double tx = ny;
                double ty = -nx;
                double imA = invMass[a];
                double iiA = invInertia[a];
                double imB = dynamicB ? invMass[b] : 0;
                double iiB = dynamicB ? invInertia[b] : 0;
                double vax = vx[a];
                double vay = vy[a];
                double wa = w[a];
                double vbx = dynamicB ? vx[b] : 0;
                double vby = dynamicB ? vy[b] : 0;
                double wb = dynamicB ? w[b] : 0;
                for (int p = 0; p < c.points[k]; p++) {
                    int q = 2 * k + p;
                    double rax = c.rAx[q];
                    double ray = c.rAy[q];
                    double rbx = c.rBx[q];
                    double rby = c.rBy[q];
                    // relative velocity of B's point against A's
                    double dvx = vbx - wb * rby - vax + wa * ray;
                    double dvy = vby + wb * rbx - vay - wa * rax;
                    // friction first, within the normal impulse of the last pass
                    double vt = dvx * tx + dvy * ty;
                    double lt = -vt * c.tangentMass[q];
                    double maxF = c.mu[k] * c.normalImpulse[q];
                    double oldT = c.tangentImpulse[q];
                    double newT = Math.max(-maxF, Math.min(maxF, oldT + lt));
                    lt = newT - oldT;
                    c.tangentImpulse[q] = newT;
                    double fx = lt * tx;
                    double fy = lt * ty;
                    vax -= imA * fx;
                    vay -= imA * fy;
                    wa -= iiA * (rax * fy - ray * fx);
                    vbx += imB * fx;
                    vby += imB * fy;
                    wb += iiB * (rbx * fy - rby * fx);
                }
                // normal: both points at once when there are two (a face on a face), so that the
                // impulse is shared between them as the lever arms say rather than in solve order
                if (c.points[k] == 2 && c.block[k]) {
                    int q = 2 * k;
                    double r1ax = c.rAx[q];
                    double r1ay = c.rAy[q];
                    double r1bx = c.rBx[q];
                    double r1by = c.rBy[q];
                    double r2ax = c.rAx[q + 1];
                    double r2ay = c.rAy[q + 1];
                    double r2bx = c.rBx[q + 1];
                    double r2by = c.rBy[q + 1];
                    double vn1 = (vbx - wb * r1by - vax + wa * r1ay) * nx + (vby + wb * r1bx - vay - wa * r1ax) * ny;
                    double vn2 = (vbx - wb * r2by - vax + wa * r2ay) * nx + (vby + wb * r2bx - vay - wa * r2ax) * ny;
                    double a1 = c.normalImpulse[q];
                    double a2 = c.normalImpulse[q + 1];
                    double k11 = c.k11[k];
                    double k22 = c.k22[k];
                    double k12 = c.k12[k];
                    // the velocities (less the bias) were there no impulse yet: find impulses x >= 0 with K x + b >= 0, complementary
                    double b1 = vn1 - c.bias[q] - (k11 * a1 + k12 * a2);
                    double b2 = vn2 - c.bias[q + 1] - (k12 * a1 + k22 * a2);
                    double det = k11 * k22 - k12 * k12;
                    double x1 = -(k22 * b1 - k12 * b2) / det;
                    double x2 = -(k11 * b2 - k12 * b1) / det;
                    if (!(x1 >= 0 && x2 >= 0)) {
                        x1 = -b1 / k11;
                        x2 = 0;
                        if (!(x1 >= 0 && k12 * x1 + b2 >= 0)) {
                            x1 = 0;
                            x2 = -b2 / k22;
                            if (!(x2 >= 0 && k12 * x2 + b1 >= 0)) {
                                x1 = 0;
                                x2 = 0;
                            }
                        }
                    }
                    double d1 = x1 - a1;
                    double d2 = x2 - a2;
                    c.normalImpulse[q] = x1;
                    c.normalImpulse[q + 1] = x2;
                    double p1x = d1 * nx;
                    double p1y = d1 * ny;
                    double p2x = d2 * nx;
                    double p2y = d2 * ny;
                    vax -= imA * (p1x + p2x);
                    vay -= imA * (p1y + p2y);
                    wa -= iiA * (r1ax * p1y - r1ay * p1x + r2ax * p2y - r2ay * p2x);
                    vbx += imB * (p1x + p2x);
                    vby += imB * (p1y + p2y);
                    wb += iiB * (r1bx * p1y - r1by * p1x + r2bx * p2y - r2by * p2x);
                } else {
                    for (int p = 0; p < c.points[k]; p++) {
                        int q = 2 * k + p;
                        double rax = c.rAx[q];
                        double ray = c.rAy[q];
                        double rbx = c.rBx[q];
                        double rby = c.rBy[q];
                        double dvx = vbx - wb * rby - vax + wa * ray;
                        double dvy = vby + wb * rbx - vay - wa * rax;
                        double vn = dvx * nx + dvy * ny;
                        double ln = (-vn + c.bias[q]) * c.normalMass[q];
                        double oldN = c.normalImpulse[q];
                        double newN = Math.max(0, oldN + ln);
                        ln = newN - oldN;
                        c.normalImpulse[q] = newN;
                        double jx = ln * nx;
                        double jy = ln * ny;
                        vax -= imA * jx;
                        vay -= imA * jy;
                        wa -= iiA * (rax * jy - ray * jx);
                        vbx += imB * jx;
                        vby += imB * jy;
                        wb += iiB * (rbx * jy - rby * jx);
                    }
                }
                vx[a] = vax;
                vy[a] = vay;
                w[a] = wa;
                if (dynamicB) {
                    vx[b] = vbx;
                    vy[b] = vby;
                    w[b] = wb;
                }
            }
        }
    }

    /** Moves a body by its velocity: the end of its step (see {@link #stepLeavingMoves}); its cosine and sine from one reduction of its angle. */
    @Override
    public void move(int i) {
        double x = vx[i];
        double y = vy[i];
        double o = w[i];
        if (x == 0 && y == 0 && o == 0) {
            rest[i] = true;
            return;
        }
        double dt = stepSeconds;
        rest[i] = false;
        double nx = px[i] + x * dt;
        double ny = py[i] + y * dt;
        px[i] = nx;
        py[i] = ny;
        bodyXYR[3 * i] = nx;
        bodyXYR[3 * i + 1] = ny;
        if (cellsKnown) {
            bodyCell[i] = cellOf(nx, ny); // the grid's as the step laid it out: the next binning's
        }
        if (o != 0) {
            double a = wrap(angle[i] + o * dt);
            angle[i] = a;
            int q = Rotation.quadrant(a);
            double r = Rotation.reduce(a, q);
            double ks = Rotation.kernelSin(r);
            double kc = Rotation.kernelCos(r);
            switch (q & 3) {
                case 0 -> {
                    cs[i] = kc;
                    sn[i] = ks;
                }
                case 1 -> {
                    cs[i] = -ks;
                    sn[i] = kc;
                }
                case 2 -> {
                    cs[i] = -kc;
                    sn[i] = -ks;
                }
                default -> {
                    cs[i] = ks;
                    sn[i] = -kc;
                }
            }
        }
    }

    /** {@link #indexContacts}, by the first of the threads asking for contacts after a step. */
    private synchronized void indexContactsOnce() {
        if (!contactsIndexed) {
            indexContacts();
            contactsIndexed = true;
        }
    }

    /** Lists each body's contacts (a counting sort of the contacts by body, in contact order). */
    private void indexContacts() {
        if (bodyContactStart.length < n + 1) {
            bodyContactStart = new int[px.length + 1];
        }
        int[] start = bodyContactStart;
        Arrays.fill(start, 0, n + 1, 0);
        ContactBuffer c = contacts;
        for (int k = 0; k < c.size; k++) {
            start[c.bodyA[k] + 1]++;
            if (c.bodyB[k] >= 0) {
                start[c.bodyB[k] + 1]++;
            }
        }
        for (int i = 0; i < n; i++) {
            start[i + 1] += start[i];
        }
        int total = start[n];
        if (bodyContacts.length < total) {
            bodyContacts = new int[Math.max(total, bodyContacts.length * 2)];
        }
        for (int k = c.size - 1; k >= 0; k--) {
            bodyContacts[--start[c.bodyA[k] + 1]] = k;
            if (c.bodyB[k] >= 0) {
                bodyContacts[--start[c.bodyB[k] + 1]] = k;
            }
        }
        System.arraycopy(start, 1, start, 0, n);
        start[n] = total;
    }

    /** Contacts in flat arrays (two points' worth per contact), with the solver's per-point values. */
    static final class ContactBuffer {
        int size;
        int[] bodyA = new int[16];
        int[] bodyB = new int[16];
        int[] points = new int[16];
        double[] normalX = new double[16];
        double[] normalY = new double[16];
        double[] mu = new double[16];
        double[] pointX = new double[32];
        double[] pointY = new double[32];
        double[] depth = new double[32];
        double[] rAx = new double[32];
        double[] rAy = new double[32];
        double[] rBx = new double[32];
        double[] rBy = new double[32];
        double[] normalMass = new double[32];
        double[] tangentMass = new double[32];
        double[] bias = new double[32];
        double[] normalImpulse = new double[32];
        double[] tangentImpulse = new double[32];
        /** Of a two-point contact: the normal's 2 × 2 effective mass matrix, and whether it is well conditioned. */
        double[] k11 = new double[16];
        double[] k22 = new double[16];
        double[] k12 = new double[16];
        boolean[] block = new boolean[16];
        /** Scratch of the detecting thread. */
        final double[] scratchA = new double[8];
        final double[] scratchB = new double[8];
        final double[] clip = new double[4];
        final int[] edge = new int[1];

        void clear() {
            size = 0;
        }

        private void grow(int m) {
            if (m <= bodyA.length) {
                return;
            }
            int c = Math.max(m, bodyA.length * 2);
            bodyA = Arrays.copyOf(bodyA, c);
            bodyB = Arrays.copyOf(bodyB, c);
            points = Arrays.copyOf(points, c);
            normalX = Arrays.copyOf(normalX, c);
            normalY = Arrays.copyOf(normalY, c);
            mu = Arrays.copyOf(mu, c);
            k11 = Arrays.copyOf(k11, c);
            k22 = Arrays.copyOf(k22, c);
            k12 = Arrays.copyOf(k12, c);
            block = Arrays.copyOf(block, c);
            pointX = Arrays.copyOf(pointX, 2 * c);
            pointY = Arrays.copyOf(pointY, 2 * c);
            depth = Arrays.copyOf(depth, 2 * c);
            rAx = Arrays.copyOf(rAx, 2 * c);
            rAy = Arrays.copyOf(rAy, 2 * c);
            rBx = Arrays.copyOf(rBx, 2 * c);
            rBy = Arrays.copyOf(rBy, 2 * c);
            normalMass = Arrays.copyOf(normalMass, 2 * c);
            tangentMass = Arrays.copyOf(tangentMass, 2 * c);
            bias = Arrays.copyOf(bias, 2 * c);
            normalImpulse = Arrays.copyOf(normalImpulse, 2 * c);
            tangentImpulse = Arrays.copyOf(tangentImpulse, 2 * c);
        }

        void add(int a, int b, double nx, double ny, int count, double x0, double y0, double d0, double x1, double y1, double d1,
                 double friction) {
            grow(size + 1);
            int k = size++;
            bodyA[k] = a;
            bodyB[k] = b;
            normalX[k] = nx;
            normalY[k] = ny;
            points[k] = count;
            mu[k] = friction;
            pointX[2 * k] = x0;
            pointY[2 * k] = y0;
            depth[2 * k] = d0;
            pointX[2 * k + 1] = x1;
            pointY[2 * k + 1] = y1;
            depth[2 * k + 1] = d1;
        }

        /** The solver's per-point values: lever arms, effective masses, position bias; impulses from zero. */
        void prepare(SwarmPhysics w) {
            double dt = w.stepSeconds;
            for (int k = 0; k < size; k++) {
                int a = bodyA[k];
                int b = bodyB[k];
                double imA = w.invMass[a];
                double iiA = w.invInertia[a];
                double imB = b >= 0 ? w.invMass[b] : 0;
                double iiB = b >= 0 ? w.invInertia[b] : 0;
                double nx = normalX[k];
                double ny = normalY[k];
                double tx = ny;
                double ty = -nx;
                for (int p = 0; p < points[k]; p++) {
                    int q = 2 * k + p;
                    double rax = pointX[q] - w.px[a];
                    double ray = pointY[q] - w.py[a];
                    double rbx = b >= 0 ? pointX[q] - w.px[b] : 0;
                    double rby = b >= 0 ? pointY[q] - w.py[b] : 0;
                    rAx[q] = rax;
                    rAy[q] = ray;
                    rBx[q] = rbx;
                    rBy[q] = rby;
                    double rnA = rax * ny - ray * nx;
                    double rnB = rbx * ny - rby * nx;
                    normalMass[q] = 1 / (imA + imB + iiA * rnA * rnA + iiB * rnB * rnB);
                    double rtA = rax * ty - ray * tx;
                    double rtB = rbx * ty - rby * tx;
                    tangentMass[q] = 1 / (imA + imB + iiA * rtA * rtA + iiB * rtB * rtB);
                    bias[q] = Math.min(MAX_CORRECTION_SPEED, BAUMGARTE / dt * Math.max(0, depth[q] - SLOP));
                    normalImpulse[q] = 0;
                    tangentImpulse[q] = 0;
                }
                block[k] = false;
                if (points[k] == 2) {
                    int q = 2 * k;
                    double rn1A = rAx[q] * ny - rAy[q] * nx;
                    double rn1B = rBx[q] * ny - rBy[q] * nx;
                    double rn2A = rAx[q + 1] * ny - rAy[q + 1] * nx;
                    double rn2B = rBx[q + 1] * ny - rBy[q + 1] * nx;
                    double a11 = imA + imB + iiA * rn1A * rn1A + iiB * rn1B * rn1B;
                    double a22 = imA + imB + iiA * rn2A * rn2A + iiB * rn2B * rn2B;
                    double a12 = imA + imB + iiA * rn1A * rn2A + iiB * rn1B * rn2B;
                    k11[k] = a11;
                    k22[k] = a22;
                    k12[k] = a12;
                    // two points too close together make the matrix singular: then one at a time
                    block[k] = a11 * a11 < 1000 * (a11 * a22 - a12 * a12);
                }
            }
        }

        /** Appends another buffer's contacts (after this one's). */
        void append(ContactBuffer o) {
            int m = o.size;
            if (m == 0) {
                return;
            }
            grow(size + m);
            System.arraycopy(o.bodyA, 0, bodyA, size, m);
            System.arraycopy(o.bodyB, 0, bodyB, size, m);
            System.arraycopy(o.points, 0, points, size, m);
            System.arraycopy(o.normalX, 0, normalX, size, m);
            System.arraycopy(o.normalY, 0, normalY, size, m);
            System.arraycopy(o.mu, 0, mu, size, m);
            System.arraycopy(o.k11, 0, k11, size, m);
            System.arraycopy(o.k22, 0, k22, size, m);
            System.arraycopy(o.k12, 0, k12, size, m);
            System.arraycopy(o.block, 0, block, size, m);
            int s2 = 2 * size;
            int m2 = 2 * m;
            System.arraycopy(o.pointX, 0, pointX, s2, m2);
            System.arraycopy(o.pointY, 0, pointY, s2, m2);
            System.arraycopy(o.depth, 0, depth, s2, m2);
            System.arraycopy(o.rAx, 0, rAx, s2, m2);
            System.arraycopy(o.rAy, 0, rAy, s2, m2);
            System.arraycopy(o.rBx, 0, rBx, s2, m2);
            System.arraycopy(o.rBy, 0, rBy, s2, m2);
            System.arraycopy(o.normalMass, 0, normalMass, s2, m2);
            System.arraycopy(o.tangentMass, 0, tangentMass, s2, m2);
            System.arraycopy(o.bias, 0, bias, s2, m2);
            System.arraycopy(o.normalImpulse, 0, normalImpulse, s2, m2);
            System.arraycopy(o.tangentImpulse, 0, tangentImpulse, s2, m2);
            size += m;
        }
    }
}
