package io.robomw.console.rosbridge.robot;

import com.fasterxml.jackson.databind.JsonNode;
import io.robomw.console.rosbridge.BridgedRobot;
import io.robomw.console.rosbridge.graph.Publication;
import io.robomw.console.rosbridge.graph.TopicListener;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.util.concurrent.RejectedExecutionException;
import java.util.concurrent.atomic.AtomicBoolean;
import java.util.concurrent.atomic.AtomicLong;
import java.util.concurrent.atomic.AtomicReference;

/**
 * A robot's {@code cmd_vel}: each {@code geometry_msgs/msg/Twist} becomes
 * {@code robot.drive(linear.x, angular.z)}, a continuous command under the robot's own watchdog,
 * so a client that stops publishing (or goes away) stops the robot within the watchdog's timeout
 * (its robot file's {@code watchdog}, 0.5 s by default). The other four components are ignored:
 * RoboMW's drives move along x and turn about z.
 *
 * <p>An in-process robot is driven on the publishing thread ({@code drive} returns at once). A
 * remote one is driven on the blocking pool, and only its latest command is kept while one is on
 * its way, so a client publishing faster than the network answers does not queue commands.
 */
final class DriveSink implements TopicListener {

    private static final Logger LOG = LoggerFactory.getLogger(DriveSink.class);

    private final BridgedRobot robot;
    private final Threads threads;
    private final AtomicReference<double[]> latest = new AtomicReference<>();
    private final AtomicBoolean pending = new AtomicBoolean();
    private final AtomicLong refused = new AtomicLong();

    DriveSink(BridgedRobot robot, Threads threads) {
        this.robot = robot;
        this.threads = threads;
    }

    @Override
    public void deliver(Publication publication) {
        JsonNode m = publication.msg();
        double v = m.path("linear").path("x").asDouble();
        double w = m.path("angular").path("z").asDouble();
        if (robot.reach() == BridgedRobot.Reach.IN_PROCESS) {
            drive(v, w);
            return;
        }
        latest.set(new double[] {v, w});
        if (pending.compareAndSet(false, true)) {
            try {
                threads.blocking().execute(this::driveLatest);
            } catch (RejectedExecutionException e) {
                pending.set(false); // the bridge is closing
            }
        }
    }

    private void driveLatest() {
        pending.set(false);
        double[] c = latest.getAndSet(null);
        if (c != null) {
            drive(c[0], c[1]);
        }
    }

    private void drive(double v, double w) {
        try {
            robot.robot().drive(v, w);
        } catch (RuntimeException e) {
            long n = refused.incrementAndGet();
            if (Long.bitCount(n) == 1) {
                LOG.info("rosbridge: robot '{}' refused cmd_vel (linear.x {}, angular.z {}): {} ({} refused so far)", robot.robot().name(), v, w,
                        e.getMessage(), n);
            }
        }
    }
}
