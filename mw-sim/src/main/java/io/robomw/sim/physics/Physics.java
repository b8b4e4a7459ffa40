package io.robomw.sim.physics;

/**
 * The rigid-body physics of a simulated world, as the world and its robots use it: static walls
 * and obstacles, robot bodies (boxes) driven by velocities set from their wheel speeds before every
 * step, the step itself, each body's pose and velocity after it, and the points where a body
 * touches something (for bump and touch sensors). Bodies are numbered from 0 in the order they were
 * added.
 *
 * <p>Two engines implement it ({@code physics: { engine: ... }} in a world file,
 * docs/simulation.md): {@link Dyn4jPhysics}, the dyn4j library's general rigid-body world, and
 * {@link SwarmPhysics}, a step of our own for boxes on a flat floor that splits its work between
 * the world's worker threads.
 *
 * <p>Adding bodies and stepping happen on the stepping thread; between two steps, the per-body
 * queries and {@link #drive} may be called from any thread for different bodies at once (each
 * body by one thread).
 */
public interface Physics {

    /**
     * Adds a static rectangle (a wall or a box obstacle).
     *
     * @param x      centre x, metres
     * @param y      centre y
     * @param width  along its own x axis
     * @param height along its own y axis
     * @param angle  rotation, radians
     */
    void addStaticBox(double x, double y, double width, double height, double angle);

    /**
     * Adds a static disc.
     *
     * @param x      centre x
     * @param y      centre y
     * @param radius radius
     */
    void addStaticCircle(double x, double y, double radius);

    /**
     * Adds a static convex polygon.
     *
     * @param points its vertices, anti-clockwise, {x, y} in world coordinates
     */
    void addStaticPolygon(double[][] points);

    /**
     * Adds a robot's body: a box with its centre at the given pose.
     *
     * @param length   along its heading, metres
     * @param width    across it
     * @param mass     kilograms
     * @param friction its surface's friction coefficient
     * @param x        centre x
     * @param y        centre y
     * @param heading  radians
     * @return the body's number
     */
    int addBody(double length, double width, double mass, double friction, double x, double y, double heading);

    /**
     * Advances every body by one step: contacts, their resolution, integration.
     *
     * @param dt the step, seconds
     */
    void step(double dt);

    /**
     * {@link #step}, but what moves each body by its velocity may be left to the caller, so that the
     * world moves a body in the same pass over its robots that reads the body's new pose (one pass
     * over the bodies' arrays instead of two, and on the worker threads). When this returns
     * {@code true}, the caller must call {@link #move} once for every body, before any query of that
     * body and before the next step; until then a body's pose, velocity and {@link #atRest} flag are
     * those before the move. Engines that cannot leave it move every body here and return
     * {@code false}.
     *
     * @param dt the step, seconds
     * @return whether every body still has to be {@linkplain #move moved}
     */
    default boolean stepLeavingMoves(double dt) {
        step(dt);
        return false;
    }

    /**
     * Moves one body by its velocity, once after {@link #stepLeavingMoves} returned {@code true}: the
     * last part of that step for this body (the same arithmetic as {@link #step} does). Any thread,
     * each body by one thread. The default (an engine that moves every body in its step) does nothing.
     *
     * @param body a body's number
     */
    default void move(int body) {
    }

    /**
     * @param body a body's number
     * @return its centre's x
     */
    double x(int body);

    /**
     * @param body a body's number
     * @return its centre's y
     */
    double y(int body);

    /**
     * @param body a body's number
     * @return the cosine of its heading
     */
    double cos(int body);

    /**
     * @param body a body's number
     * @return the sine of its heading
     */
    double sin(int body);

    /**
     * @param body a body's number
     * @return its heading, radians in [-π, π], anti-clockwise from x (by default from its cosine and sine)
     */
    default double heading(int body) {
        return Math.atan2(sin(body), cos(body));
    }

    /**
     * @param body a body's number
     * @return its linear velocity's x, m/s
     */
    double vx(int body);

    /**
     * @param body a body's number
     * @return its linear velocity's y, m/s
     */
    double vy(int body);

    /**
     * @param body a body's number
     * @return whether it did not move in the last step (its pose is unchanged)
     */
    boolean atRest(int body);

    /**
     * Sets a body's velocities for the next step, as its drive commands them.
     *
     * @param body a body's number
     * @param v    forward speed along its heading, m/s
     * @param w    angular speed, rad/s, anti-clockwise
     */
    void drive(int body, double v, double w);

    /**
     * Sets a body's velocities for the next step in the world's frame, for bodies pushed sideways
     * as well as along their heading (a vehicle in wind or a current).
     *
     * @param body a body's number
     * @param vx   velocity along x, m/s
     * @param vy   velocity along y, m/s
     * @param w    angular speed, rad/s, anti-clockwise
     */
    void setVelocity(int body, double vx, double vy, double w);

    /**
     * Reports where a body touched something in the last step.
     *
     * @param body a body's number
     * @param sink receives each contact point in the body's own frame (x forwards, y left)
     */
    void contacts(int body, ContactSink sink);

    /** Receives contact points. */
    @FunctionalInterface
    interface ContactSink {
        /**
         * @param localX the point's x in the body's frame, forwards
         * @param localY its y, to the left
         */
        void point(double localX, double localY);
    }
}
