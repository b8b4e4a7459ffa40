package io.robomw.config.legged;

import io.robomw.api.Clock;
import io.robomw.api.Pose;
import io.robomw.config.drive.MotionEnd;
import io.robomw.config.drive.MotionListener;
import io.robomw.config.drive.Movement;

import java.util.Queue;
import java.util.concurrent.ConcurrentLinkedQueue;

/**
 * The pose of a robot that walks by its firmware's commands, estimated from what it was commanded
 * (dead reckoning), as a listener of its drive's motions: a legged robot reports no wheel travel
 * to integrate, so each walking command is taken as a segment at its commanded velocities, timed
 * on the platform's clock.
 *
 * <ul>
 *   <li>A command that completes counts whole: the distance or angle it was asked for, exactly.</li>
 *   <li>A command ended early (interrupted by a newer one, stopped, failed, or a {@code drive}
 *   whose watchdog expired) counts for the time it ran, up to the moment its end was heard.</li>
 *   <li>A {@code drive} repeated to refresh it continues the same chain of segments, so the
 *   watchdog ending the chain (it ends an earlier refresh's command) ends the latest segment.</li>
 * </ul>
 * What the feet really did (jitter, slip, a wall) is not seen: the estimate drifts as a real
 * legged robot's does.
 *
 * <p>Threads: as {@link MotionListener} says. A motion's end is heard on the platform's action
 * thread, which only queues it with the clock's time, lock-free; the segments are closed in
 * order by the next start, stop or pose, under this object's lock.
 */
final class DeadReckoning implements MotionListener {

    /**
     * One commanded walking motion at constant velocities.
     *
     * @param movement     the motion
     * @param startNanos   when it began, on the clock
     * @param plannedNanos how long it was commanded for; {@link Long#MAX_VALUE} for a continuous one
     * @param chainFirst   the sequence number of the first motion of its chain of refreshes (its
     *                     own, unless it continues a continuous one)
     */
    record Segment(Movement movement, long startNanos, long plannedNanos, long chainFirst) {
        boolean continuous() {
            return plannedNanos == Long.MAX_VALUE;
        }
    }

    /** A motion's end as heard, with when. */
    private record Ended(Movement movement, MotionEnd end, long atNanos) {
    }

    private final Clock clock;
    private final Queue<Ended> ends = new ConcurrentLinkedQueue<>();
    // Guarded by this:
    private Pose base = Pose.ORIGIN;
    private Segment current;

    /**
     * @param clock the platform's clock
     */
    DeadReckoning(Clock clock) {
        this.clock = clock;
    }

    /** Starts a walking motion now, ending the one before (a newer command on the legs ends it). */
    @Override
    public synchronized void motionStarted(Movement movement) {
        long now = clock.nanoTime();
        closeEnded();
        boolean continuous = movement.continuous();
        long chainFirst = continuous && current != null && current.continuous() ? current.chainFirst() : movement.sequence();
        closeAt(now);
        long planned = continuous ? Long.MAX_VALUE : Math.round(movement.plannedSeconds() * 1e9);
        current = new Segment(movement, now, planned, chainFirst);
    }

    /** Queues the end with the clock's time; takes no lock. */
    @Override
    public void motionEnded(Movement movement, MotionEnd end) {
        ends.offer(new Ended(movement, end, clock.nanoTime()));
    }

    /** The legs stopped now (a stop, or an action on the legs such as sit): ends the current motion. */
    @Override
    public synchronized void halted() {
        closeEnded();
        closeAt(clock.nanoTime());
    }

    /** @return the estimate now */
    synchronized Pose pose() {
        closeEnded();
        return current == null ? base : advance(base, current, clock.nanoTime());
    }

    /**
     * @param pose the robot's pose now; a motion under way continues from it
     */
    synchronized void reset(Pose pose) {
        closeEnded();
        closeAt(clock.nanoTime());
        base = pose;
    }

    /** Applies the ends heard since, in order: a completed motion counts whole, one ended early until its end. */
    private void closeEnded() {
        for (Ended e = ends.poll(); e != null; e = ends.poll()) {
            if (current == null) {
                continue;
            }
            if (e.end() == MotionEnd.COMPLETED) {
                if (current.movement() == e.movement() && !current.continuous()) {
                    closeAt(current.startNanos() + current.plannedNanos());
                }
            } else if (e.movement().sequence() >= current.chainFirst()) {
                closeAt(e.atNanos());
            }
        }
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
        double dTheta = s.movement().angularSpeed() * t;
        double ds = s.movement().linearSpeed() * t;
        double h = from.heading();
        double x;
        double y;
        if (Math.abs(dTheta) < 1e-12) {
            x = from.x() + ds * Math.cos(h);
            y = from.y() + ds * Math.sin(h);
        } else {
            double r = s.movement().linearSpeed() / s.movement().angularSpeed();
            x = from.x() + r * (Math.sin(h + dTheta) - Math.sin(h));
            y = from.y() - r * (Math.cos(h + dTheta) - Math.cos(h));
        }
        return new Pose(x, y, h + dTheta);
    }
}
