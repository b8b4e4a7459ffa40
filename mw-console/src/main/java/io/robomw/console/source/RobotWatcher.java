package io.robomw.console.source;

import io.robomw.api.spi.FailurePolicy;
import io.robomw.api.Pose;
import io.robomw.api.Quantity;
import io.robomw.api.ReturnType;
import io.robomw.api.Robot;
import io.robomw.api.Robots;
import io.robomw.api.SensorInfo;
import io.robomw.console.observe.Observation;
import io.robomw.console.observe.Observer;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.net.URI;
import java.time.Duration;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.TimeUnit;

/**
 * Watches a robot served by another process ({@code Robots.remote}, e.g.
 * {@code tcp://127.0.0.1:7000/nxt}) on a thread of its own: its pose (the robot's own odometry)
 * and its sensors, a few times a second. When the robot stops answering it says so (the console
 * marks it unreachable and keeps its last pose, greyed) and connects again every
 * {@value #RECONNECT_MILLIS} ms until it answers. {@link #stop()} stops the robot's motors.
 */
public final class RobotWatcher implements AutoCloseable {

    private static final Logger LOG = LoggerFactory.getLogger(RobotWatcher.class);
    static final long RECONNECT_MILLIS = 2_000;

    private final String address;
    private final Observer observer;
    private final Duration period;
    private final Thread thread;
    private final FailurePolicy failures;
    private final CountDownLatch closed = new CountDownLatch(1);
    private final boolean owned;
    private volatile Robot robot;
    private volatile String name;

    private RobotWatcher(String address, Robot given, Observer observer, Duration period, FailurePolicy failures) {
        this.address = address;
        this.failures = failures;
        this.observer = observer;
        this.period = period;
        this.owned = given == null;
        this.robot = given;
        if (given != null) {
            this.name = given.name();
        } else {
            String path = URI.create(address).getPath();
            this.name = path == null || path.length() <= 1 ? address : path.substring(path.lastIndexOf('/') + 1);
        }
        this.thread = new Thread(this::run, "console-robot-" + name); // run() catches whatever ends it, in one place
        thread.setDaemon(true);
    }

    /**
     * @param address  the robot's address, as {@code Robots.remote} takes it
     * @param observer who is told
     * @param period   time between two looks
     * @param failures where what ends the watcher goes
     * @return the running watcher
     */
    public static RobotWatcher watch(String address, Observer observer, Duration period, FailurePolicy failures) {
        RobotWatcher w = new RobotWatcher(address, null, observer, period, failures);
        w.thread.start();
        return w;
    }

    /**
     * Watches a robot of this process; it stays the caller's (never closed here).
     *
     * @param robot    the robot
     * @param source   where it is, for the page
     * @param observer who is told
     * @param period   time between two looks
     * @param failures where what ends the watcher goes
     * @return the running watcher
     */
    public static RobotWatcher watch(Robot robot, String source, Observer observer, Duration period, FailurePolicy failures) {
        RobotWatcher w = new RobotWatcher(source, robot, observer, period, failures);
        w.thread.start();
        return w;
    }

    /** @return the robot's name (from its address until it answers) */
    public String name() {
        return name;
    }

    private void run() {
        try {
            while (closed.getCount() > 0) {
                try {
                    Robot r = robot;
                    if (r == null && !owned) {
                        return;
                    }
                    if (r == null) {
                        r = Robots.remote(address);
                        name = r.name();
                        robot = r;
                        LOG.info("console: watching robot {} at {}", name, address);
                    }
                    look(r);
                    if (closed.await(period.toMillis(), TimeUnit.MILLISECONDS)) {
                        return;
                    }
                } catch (RuntimeException e) {
                    observer.observe(new Observation.RobotStatus(now(), name, address, false, String.valueOf(e.getMessage())));
                    if (owned) {
                        drop();
                    }
                    if (closed.await(RECONNECT_MILLIS, TimeUnit.MILLISECONDS)) {
                        return;
                    }
                }
            }
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
        } catch (Throwable t) {
            LOG.warn("console: watching robot {} failed; no more updates of it: {}", name, t.toString());
            failures.died(thread.getName(), t);
        } finally {
            if (owned) {
                drop();
            }
        }
    }

    private void look(Robot r) {
        Pose p = r.pose();
        long t = now();
        observer.observe(new Observation.RobotStatus(t, name, address, true, ""));
        observer.observe(new Observation.RobotPose(t, name, p.x(), p.y(), p.z(), p.heading(), false));
        for (SensorInfo s : r.sensors()) {
            Quantity q = s.type().quantity();
            ReturnType unit = q == Quantity.DISTANCE ? ReturnType.METERS : q == Quantity.ANGLE ? ReturnType.DEGREES : ReturnType.RAW;
            double v = r.getValue(s.name(), unit);
            observer.observe(new Observation.SensorReading(now(), name, s.name(), v,
                    unit == ReturnType.METERS ? "m" : unit == ReturnType.DEGREES ? "°" : ""));
        }
    }

    private static long now() {
        return System.currentTimeMillis() * 1_000_000L;
    }

    private void drop() {
        Robot r = robot;
        robot = null;
        if (r != null) {
            try {
                r.close();
            } catch (RuntimeException e) {
                LOG.debug("console: closing the link to {} failed: {}", address, e.toString());
            }
        }
    }

    /**
     * Stops every motor of the robot (its safety stop).
     *
     * @return what happened
     */
    public String stop() {
        Robot r = robot;
        if (r == null) {
            throw new IllegalStateException("robot " + name + " at " + address + " is not answering");
        }
        r.stop();
        observer.observe(new Observation.RobotCommand(now(), name, "stop", java.util.Map.of()));
        return "robot " + name + " stopped";
    }

    /**
     * Drives the robot continuously ({@code Robot.drive}: it stops by itself unless driven again
     * within its watchdog's timeout).
     *
     * @param linear  m/s
     * @param angular rad/s
     * @throws IllegalStateException if the robot is not answering
     */
    public void drive(double linear, double angular) {
        Robot r = robot;
        if (r == null) {
            throw new IllegalStateException("robot " + name + " at " + address + " is not answering");
        }
        r.drive(linear, angular);
    }

    @Override
    public void close() {
        closed.countDown();
        thread.interrupt();
        try {
            thread.join(5_000);
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
        }
    }
}
