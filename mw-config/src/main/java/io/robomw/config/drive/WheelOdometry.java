package io.robomw.config.drive;

import io.robomw.api.Pose;
import io.robomw.api.spi.RobotPlatform;
import io.robomw.config.kinematics.DifferentialKinematics;
import io.robomw.config.kinematics.Odometry;

import java.util.Queue;
import java.util.concurrent.ConcurrentLinkedQueue;
import java.util.concurrent.atomic.AtomicLong;

/**
 * The pose of a robot on two wheels with encoders, as a listener of its drive's motions (leJOS's
 * {@code OdometryPoseProvider}): its {@link Odometry}, integrated from the wheel motors' readings,
 * kept across reloads of the description.
 *
 * <h2>Exact across motions, integrated off the action thread</h2>
 * {@link Odometry} integrates the travel between two readings as one arc, which is exact only if
 * the wheel speeds were constant in between: within one motion they are, across a motion's end
 * they are not. So the readings at each boundary matter:
 * <ul>
 *   <li>a motion's start, and a stop: read and integrated on the commanding thread, before the
 *   command goes (under this object's lock, which the pose's readers take too);</li>
 *   <li>a motion's end: only read, on the thread that ended it (the platform's execution action
 *   thread: a preempted motion ends when the newer one is admitted, a cycle after it was sent),
 *   and queued lock-free with a ticket; integrated in order by the next reader
 *   ({@link #pose()}, the next motion's start).</li>
 * </ul>
 * Every reading takes a ticket from one counter before it reads the encoders, and a boundary
 * whose ticket is older than the last reading integrated is dropped: a boundary read while a
 * reader integrated a newer reading adds nothing (the wheel travel is the same; only the shape of
 * the few microseconds between the two is lost).
 *
 * <p>Thread-safe. The commanding and reading threads hold the object's lock; the action thread
 * never does.
 */
final class WheelOdometry implements MotionListener {

    /** Encoder readings at a motion's end, in the order of their tickets. */
    private record Boundary(long ticket, double leftDegrees, double rightDegrees) {
    }

    private final RobotPlatform platform;
    private final AtomicLong tickets = new AtomicLong();
    private final Queue<Boundary> boundaries = new ConcurrentLinkedQueue<>();
    /** The wheel layout in force; its ports are read by the action thread too. */
    private volatile DifferentialKinematics kinematics;
    // Guarded by this:
    private Odometry odometry;
    private long integrated;

    /**
     * Records the wheels' readings now: the origin of the estimate.
     *
     * @param platform   where the readings come from
     * @param kinematics the wheel layout in force
     */
    WheelOdometry(RobotPlatform platform, DifferentialKinematics kinematics) {
        this.platform = platform;
        this.kinematics = kinematics;
        this.odometry = new Odometry(kinematics);
        integrate();
    }

    /**
     * The same estimate, continued with the wheel layout of a reloaded description: the travel so
     * far is integrated with the layout it was driven under, what follows with the new one.
     *
     * @param next the new wheel layout
     */
    synchronized void continueWith(DifferentialKinematics next) {
        integrate();
        if (!next.drive().equals(kinematics.drive())) {
            odometry = odometry.rebased(next);
        }
        kinematics = next;
    }

    @Override
    public void motionStarted(Movement movement) {
        integrate();
    }

    /** Reads the encoders and queues the readings; takes no lock. */
    @Override
    public void motionEnded(Movement movement, MotionEnd end) {
        DifferentialKinematics k = kinematics;
        long ticket = tickets.incrementAndGet();
        try {
            boundaries.offer(new Boundary(ticket, platform.motorDegrees(k.drive().left().port()), platform.motorDegrees(k.drive().right().port())));
        } catch (RuntimeException e) {
            // An encoder that cannot be read now (the platform is closing): the next reading
            // integrates across this boundary, as one arc.
        }
    }

    @Override
    public void halted() {
        integrate();
    }

    /**
     * Moves the estimate on to the wheels' readings now, after the boundaries queued before them.
     * Makes no pose and no other object (a controller's {@code drive} comes ten times a second).
     */
    synchronized void integrate() {
        for (Boundary b = boundaries.poll(); b != null; b = boundaries.poll()) {
            if (b.ticket() > integrated) {
                odometry.integrate(b.leftDegrees(), b.rightDegrees());
                integrated = b.ticket();
            }
        }
        DifferentialKinematics k = kinematics;
        long ticket = tickets.incrementAndGet();
        odometry.integrate(platform.motorDegrees(k.drive().left().port()), platform.motorDegrees(k.drive().right().port()));
        integrated = ticket;
    }

    /** @return the estimate now */
    synchronized Pose pose() {
        integrate();
        return odometry.pose();
    }

    /**
     * @param pose the robot's pose now
     */
    synchronized void reset(Pose pose) {
        integrate();
        odometry.reset(pose);
    }
}
