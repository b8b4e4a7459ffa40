package io.robomw.config.legged;

import io.robomw.api.Clock;
import io.robomw.api.Pose;

/**
 * The pose of a robot that walks by its firmware's commands, estimated from what it was commanded
 * (dead reckoning): a legged robot reports no wheel travel to integrate, so each walking command
 * is taken as a segment at its commanded velocities, timed on the platform's clock.
 *
 * <ul>
 *   <li>A command that completes counts whole: the distance or angle it was asked for, exactly.</li>
 *   <li>A command ended early (interrupted by a newer one, stopped, failed, or a {@code drive}
 *   whose watchdog expired) counts for the time it ran, up to the moment its end was seen.</li>
 *   <li>A {@code drive} repeated to refresh it continues the same segment chain, so the watchdog
 *   ending the chain ends the latest segment.</li>
 * </ul>
 * What the feet really did (jitter, slip, a wall) is not seen: the estimate drifts as a real
 * legged robot's does. Thread-safe: every method holds the object's lock.
 */
final class DeadReckoning {

    private final Clock clock;
    private Pose base = Pose.ORIGIN;
    private Segment current;
    private long chains;

    /**
     * One commanded walking motion at constant velocities.
     *
     * @param linear        metres per second, signed
     * @param angular       radians per second, signed
     * @param startNanos    when it began, on the clock
     * @param plannedNanos  how long it was commanded for; {@link Long#MAX_VALUE} for a continuous one
     * @param chain         the chain of refreshes it belongs to
     */
    record Segment(double linear, double angular, long startNanos, long plannedNanos, long chain) {
        boolean continuous() {
            return plannedNanos == Long.MAX_VALUE;
        }
    }

    /**
     * @param clock the platform's clock
     */
    DeadReckoning(Clock clock) {
        this.clock = clock;
    }

    /**
     * Starts a walking motion now, ending the one before (a newer command on the legs ends it).
     *
     * @param linear         metres per second
     * @param angular        radians per second
     * @param plannedSeconds how long it is commanded for, or {@link Double#POSITIVE_INFINITY}
     *                       for a continuous {@code drive}
     * @return the segment, to report its end with
     */
    synchronized Segment begin(double linear, double angular, double plannedSeconds) {
        long now = clock.nanoTime();
        boolean continuous = Double.isInfinite(plannedSeconds);
        long chain = continuous && current != null && current.continuous() ? current.chain() : ++chains;
        closeAt(now);
        long planned = continuous ? Long.MAX_VALUE : Math.round(plannedSeconds * 1e9);
        current = new Segment(linear, angular, now, planned, chain);
        return current;
    }

    /** The legs stopped now (a stop, or an action on the legs such as sit): ends the current motion. */
    synchronized void halt() {
        closeAt(clock.nanoTime());
    }

    /**
     * The platform reported the segment's command done: it counts whole.
     *
     * @param s the segment
     */
    synchronized void completed(Segment s) {
        if (current == s && !s.continuous()) {
            closeAt(s.startNanos() + s.plannedNanos());
        }
    }

    /**
     * The segment's command ended early: the chain it belongs to counts until now.
     *
     * @param s the segment
     */
    synchronized void ended(Segment s) {
        if (current != null && current.chain() == s.chain()) {
            closeAt(clock.nanoTime());
        }
    }

    /** @return the estimate now */
    synchronized Pose pose() {
        return current == null ? base : advance(base, current, clock.nanoTime());
    }

    /**
     * @param pose the robot's pose now; a motion under way continues from it
     */
    synchronized void reset(Pose pose) {
        long now = clock.nanoTime();
        if (current != null) {
            closeAt(now);
        }
        base = pose;
    }

    private void closeAt(long endNanos) {
        if (current == null) {
            return;
        }
        base = advance(base, current, endNanos);
        current = null;
    }

    /** The pose after running a segment from its start until {@code untilNanos} (at most its planned length). */
    static Pose advance(Pose from, Segment s, long untilNanos) {
        long ran = Math.max(0, untilNanos - s.startNanos());
        if (!s.continuous()) {
            ran = Math.min(ran, s.plannedNanos());
        }
        double t = ran / 1e9;
        double dTheta = s.angular() * t;
        double ds = s.linear() * t;
        double h = from.heading();
        double x;
        double y;
        if (Math.abs(dTheta) < 1e-12) {
            x = from.x() + ds * Math.cos(h);
            y = from.y() + ds * Math.sin(h);
        } else {
            double r = s.linear() / s.angular();
            x = from.x() + r * (Math.sin(h + dTheta) - Math.sin(h));
            y = from.y() - r * (Math.cos(h + dTheta) - Math.cos(h));
        }
        return new Pose(x, y, h + dTheta);
    }
}
