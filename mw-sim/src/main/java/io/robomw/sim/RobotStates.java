package io.robomw.sim;

import io.robomw.api.Pose;
import io.robomw.sim.physics.Physics;

import java.lang.invoke.MethodHandles;
import java.lang.invoke.VarHandle;
import java.util.Arrays;

/**
 * What every robot of a world changes at every step, in flat arrays indexed by the robot's index
 * (a struct of arrays): its true pose, the angle it turned, its wheel motors' encoders and
 * commanded speeds, and the constants its differential drive needs. A step's pass over the robots
 * then reads and writes a few arrays in order (which the processor prefetches) instead of a few
 * objects of each robot (each a cache miss once a world's robots outgrow the caches: at 10,000
 * robots and 50 Hz the misses of the per-step work cost more than its arithmetic).
 *
 * <p>A <em>plain</em> robot (a differential drive, no touch sensor, no accelerometer, no legs, no
 * other motors) is stepped here entirely ({@link #advance}, {@link #drive}); the others' steps run
 * in {@link SimRobot}, which keeps its pose and drive motors' state here all the same.
 *
 * <h2>Threads</h2>
 * Each robot's slots are written by the world's thread that handles that robot in a pass. Its pose
 * is read by other threads too (viewers, programs) through a sequence lock per robot
 * ({@link #pose(int)}): odd while a step writes it. The arrays are sized while robots are added,
 * before the world runs; they are not replaced while it runs.
 */
final class RobotStates {

    private static final VarHandle VERSION = MethodHandles.arrayElementVarHandle(int[].class);

    private int capacity;
    // the true pose after the last step, the heading in (-π, π] as a Pose holds it, and its cosine and sine as the physics gave them
    double[] x = new double[0];
    double[] y = new double[0];
    double[] heading = new double[0];
    double[] cos = new double[0];
    double[] sin = new double[0];
    /** Per robot: the pose's sequence number (odd while a step writes it). */
    int[] version = new int[0];
    /** The angle turned since the start (the gyro's), radians. */
    double[] turned = new double[0];
    // the differential drive's two motors: encoders (degrees) and commanded speeds (degrees per second)
    double[] encoderLeft = new double[0];
    double[] encoderRight = new double[0];
    double[] commandLeft = new double[0];
    double[] commandRight = new double[0];
    /**
     * The body's linear (metres per second) and angular (radians per second) speed the commanded wheel speeds ask for:
     * worked out when a command is set ({@link #command}), at most once a cycle, rather than at every step (three
     * divisions a robot at 50 Hz, for commands that change at 10 Hz).
     */
    double[] linear = new double[0];
    double[] angular = new double[0];
    // the drive's constants: the body's number in the physics, track width, motor degrees per metre of
    // wheel travel, each motor's direction (1, or -1 when reversed), top wheel speed
    int[] body = new int[0];
    double[] track = new double[0];
    double[] degreesPerMetre = new double[0];
    double[] signLeft = new double[0];
    double[] signRight = new double[0];
    double[] maxSpeed = new double[0];
    /** Whether the robot is stepped here entirely. */
    boolean[] plain = new boolean[0];
    /** Per robot: what the robots of its robot file share (its range sensors' models), so sensing need not reach the robot's object. */
    RobotModel[] model = new RobotModel[0];
    Trajectory[] trajectory = new Trajectory[0];
    /** Per robot: where its range sensors' samples start in {@link #ranges}. */
    int[] rangeStart = new int[0];
    /** Every robot's range sensors' last samples, metres, robot after robot (read by viewers as of some step). */
    double[] ranges = new double[0];
    private int rangesUsed;

    /**
     * Makes room for robot {@code i} (robots are added in index order, each once).
     *
     * @param i           the new robot's index
     * @param rangeCount  how many range sensors it has
     */
    void add(int i, int rangeCount) {
        grow(i);
        rangeStart[i] = rangesUsed;
        if (rangesUsed + rangeCount > ranges.length) {
            ranges = Arrays.copyOf(ranges, Math.max(rangesUsed + rangeCount, 2 * ranges.length));
        }
        rangesUsed += rangeCount;
    }

    /**
     * @param i a robot's index
     * @param k one of its range sensors, by its place among them
     * @return the sensor's last sample, metres
     */
    double range(int i, int k) {
        return ranges[rangeStart[i] + k];
    }

    /**
     * Makes room for {@code n} robots at once, before they are added.
     *
     * @param n how many robots the world will have
     */
    void reserve(int n) {
        if (n > 0) {
            grow(n - 1);
        }
    }

    private void grow(int i) {
        if (i < capacity) {
            return;
        }
        int m = Math.max(16, Math.max(i + 1, capacity * 2));
        x = Arrays.copyOf(x, m);
        y = Arrays.copyOf(y, m);
        heading = Arrays.copyOf(heading, m);
        cos = Arrays.copyOf(cos, m);
        sin = Arrays.copyOf(sin, m);
        version = Arrays.copyOf(version, m);
        turned = Arrays.copyOf(turned, m);
        encoderLeft = Arrays.copyOf(encoderLeft, m);
        encoderRight = Arrays.copyOf(encoderRight, m);
        commandLeft = Arrays.copyOf(commandLeft, m);
        commandRight = Arrays.copyOf(commandRight, m);
        linear = Arrays.copyOf(linear, m);
        angular = Arrays.copyOf(angular, m);
        body = Arrays.copyOf(body, m);
        track = Arrays.copyOf(track, m);
        degreesPerMetre = Arrays.copyOf(degreesPerMetre, m);
        signLeft = Arrays.copyOf(signLeft, m);
        signRight = Arrays.copyOf(signRight, m);
        maxSpeed = Arrays.copyOf(maxSpeed, m);
        plain = Arrays.copyOf(plain, m);
        model = Arrays.copyOf(model, m);
        trajectory = Arrays.copyOf(trajectory, m);
        rangeStart = Arrays.copyOf(rangeStart, m);
        capacity = m;
    }

    /**
     * Any thread: the pose of one whole step, never x of one step with the heading of the next.
     *
     * @param i a robot's index
     * @return its true pose
     */
    Pose pose(int i) {
        while (true) {
            int v = (int) VERSION.getAcquire(version, i);
            double px = x[i];
            double py = y[i];
            double ph = heading[i];
            VarHandle.loadLoadFence();
            if ((v & 1) == 0 && (int) VERSION.getOpaque(version, i) == v) {
                return new Pose(px, py, ph);
            }
            Thread.onSpinWait(); // a step is writing it: a few stores
        }
    }

    /**
     * Writes robot {@code i}'s pose (behind its sequence lock).
     *
     * @throws IllegalArgumentException naming the values if one is not a finite number (as a Pose would)
     */
    void setPose(int i, double px, double py, double ph, double c, double s) {
        if (!Double.isFinite(px) || !Double.isFinite(py) || !Double.isFinite(ph)) {
            new Pose(px, py, ph); // throws, saying which values are not numbers
        }
        ph = Pose.normalize(ph);
        int v = version[i];
        VERSION.setOpaque(version, i, v + 1);
        VarHandle.storeStoreFence();
        x[i] = px;
        y[i] = py;
        heading[i] = ph;
        VERSION.setRelease(version, i, v + 2);
        cos[i] = c;
        sin[i] = s;
    }

    /**
     * After a physics step: robot {@code i}'s new pose from its body, the angle it turned, and (with
     * a differential drive) its encoders from how the body actually moved (wheels do not slip).
     * The trajectory is the caller's.
     *
     * @param i       the robot's index
     * @param physics the world's physics
     * @param drive   whether it has a differential drive whose encoders follow the motion
     */
    void advance(int i, Physics physics, boolean drive) {
        int b = body[i];
        double x0 = x[i];
        double y0 = y[i];
        double h0 = heading[i];
        double c0 = cos[i];
        double s0 = sin[i];
        double c = physics.cos(b);
        double s = physics.sin(b);
        setPose(i, physics.x(b), physics.y(b), physics.heading(b), c, s);
        double dTheta = Pose.normalize(heading[i] - h0);
        turned[i] += dTheta;
        if (drive) {
            // the way along the heading half-way between the two (the bisector of the two headings'
            // unit vectors: no sine or cosine of the mid angle needed)
            double bx = c0 + c;
            double by = s0 + s;
            double norm = Math.sqrt(bx * bx + by * by);
            double ds = norm == 0 ? 0 : ((x[i] - x0) * bx + (y[i] - y0) * by) / norm;
            double half = dTheta * track[i] / 2;
            double dpm = degreesPerMetre[i];
            encoderLeft[i] += signLeft[i] * (ds - half) * dpm;
            encoderRight[i] += signRight[i] * (ds + half) * dpm;
        }
    }

    /**
     * A plain robot's step after the motion: {@link #advance}, unless its body did not move, and a
     * trajectory sample when one is due.
     */
    void afterStep(int i, Physics physics, boolean record) {
        if (!physics.atRest(body[i])) {
            advance(i, physics, true);
        }
        if (record) {
            trajectory[i].add(x[i], y[i]);
        }
    }

    /**
     * Sets robot {@code i}'s commanded wheel speeds (a differential drive's, degrees per second; its constants set) and
     * the body's speeds they ask for, each wheel's within the drive's top speed.
     *
     * @param i     the robot's index
     * @param left  the left motor's speed
     * @param right the right motor's speed
     */
    void command(int i, double left, double right) {
        commandLeft[i] = left;
        commandRight[i] = right;
        double max = maxSpeed[i];
        double dpm = degreesPerMetre[i];
        double vl = clamp(signLeft[i] * left / dpm, max);
        double vr = clamp(signRight[i] * right / dpm, max);
        linear[i] = (vl + vr) / 2;
        angular[i] = (vr - vl) / track[i];
    }

    /** Sets robot {@code i}'s body velocities from its commanded wheel speeds (a differential drive; see {@link #command}). */
    void drive(int i, Physics physics) {
        physics.drive(body[i], linear[i], angular[i]);
    }

    private static double clamp(double v, double max) {
        return Math.max(-max, Math.min(max, v));
    }
}
