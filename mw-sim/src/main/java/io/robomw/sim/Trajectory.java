package io.robomw.sim;

import io.robomw.sim.world.WorldDescription.Keep;
import io.robomw.sim.world.WorldDescription.TrajectorySettings;

/**
 * A robot's path, sampled at a fixed interval of simulated time (the world's
 * {@link TrajectorySettings}), with bounded memory: at most {@code maxPoints} points, each stored
 * as two {@code float}s (8 bytes; 0.06 mm resolution at 1000 m from the origin, far below a pixel
 * of any picture). When it holds that many, {@link Keep#WHOLE} drops every other point and keeps
 * every second sample from then on (the path always spans the whole run), {@link Keep#RECENT}
 * drops the oldest point. The length of the path is summed over every sample, whatever is kept, so
 * {@link #length()} does not depend on the limit.
 *
 * <p>Samples are added by the world's threads and read by renderers and viewers on their own:
 * every method is synchronized (a sample is taken every few steps per robot, so the lock is
 * uncontended and costs nanoseconds).
 */
public final class Trajectory {

    private static final int INITIAL_POINTS = 8;

    private final int maxPoints;
    private final boolean recent;
    /** x, y pairs; in RECENT mode a ring whose oldest point is at {@code head} once full. */
    private float[] points;
    private int count;
    private int head;
    /** WHOLE mode: a sample is kept when its number is a multiple of this. */
    private long stride = 1;
    private long samples;
    private double length;
    private double lastX;
    private double lastY;

    Trajectory(TrajectorySettings settings) {
        this.maxPoints = settings.maxPoints();
        this.recent = settings.keep() == Keep.RECENT;
        this.points = new float[2 * Math.min(INITIAL_POINTS, maxPoints)];
    }

    /**
     * Adds the next sample.
     *
     * @param x its x, metres
     * @param y its y, metres
     */
    synchronized void add(double x, double y) {
        long n = samples++;
        if (n > 0) {
            // Not Math.hypot: its care against overflow (steps of 1e154 m) costs a StrictMath call per
            // robot per sample; the sum may differ from hypot's in the last bits, nothing else does.
            double dx = x - lastX;
            double dy = y - lastY;
            length += Math.sqrt(dx * dx + dy * dy);
        }
        lastX = x;
        lastY = y;
        if (maxPoints == 0) {
            return;
        }
        if (recent) {
            if (count < maxPoints) {
                append(x, y);
            } else {
                points[2 * head] = (float) x;
                points[2 * head + 1] = (float) y;
                head = head + 1 == maxPoints ? 0 : head + 1;
            }
            return;
        }
        if (n % stride != 0) {
            return;
        }
        if (count == maxPoints) {
            thin();
            if (n % stride != 0) {
                return;
            }
        }
        append(x, y);
    }

    private void append(double x, double y) {
        if (2 * count == points.length) {
            points = java.util.Arrays.copyOf(points, 2 * Math.min(maxPoints, Math.max(1, 2 * count)));
        }
        points[2 * count] = (float) x;
        points[2 * count + 1] = (float) y;
        count++;
    }

    /** Keeps the points of even sample numbers of the new stride (every other point, the first included). */
    private void thin() {
        int kept = 0;
        for (int i = 0; i < count; i += 2) {
            points[2 * kept] = points[2 * i];
            points[2 * kept + 1] = points[2 * i + 1];
            kept++;
        }
        count = kept;
        stride *= 2;
    }

    /** @return the points kept, oldest first, as {x0, y0, x1, y1, ...} */
    public synchronized double[] snapshot() {
        double[] out = new double[2 * count];
        int start = recent && count == maxPoints ? head : 0;
        for (int i = 0; i < count; i++) {
            int k = start + i < count ? start + i : start + i - count;
            out[2 * i] = points[2 * k];
            out[2 * i + 1] = points[2 * k + 1];
        }
        return out;
    }

    /** @return how many points are kept now */
    public synchronized int size() {
        return count;
    }

    /**
     * @return how many points it has room for now (its storage grows by doubling up to the world's
     *         {@code max_points}, 8 bytes a point): what a full trajectory would add to the heap is
     *         {@code 8 × (max_points − capacity())} bytes
     */
    public synchronized int capacity() {
        return points.length / 2;
    }

    /** @return the samples taken so far (kept or not) */
    public synchronized long samples() {
        return samples;
    }

    /**
     * @return samples between two kept points: 1 until a {@link Keep#WHOLE} trajectory is first
     *         thinned, then 2, 4, ...
     */
    public synchronized long stride() {
        return stride;
    }

    /** @return the length of the sampled path so far (every sample, kept or not), metres */
    public synchronized double length() {
        return length;
    }

    /**
     * @param x a point's x (the robot's pose now)
     * @param y its y
     * @return the length of the sampled path plus the way from its latest sample to that point, metres
     */
    public synchronized double lengthTo(double x, double y) {
        return samples == 0 ? 0 : length + Math.hypot(x - lastX, y - lastY);
    }
}
