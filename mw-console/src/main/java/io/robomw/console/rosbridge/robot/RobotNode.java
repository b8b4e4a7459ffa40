package io.robomw.console.rosbridge.robot;

import com.fasterxml.jackson.databind.node.ObjectNode;
import io.robomw.api.Pose;
import io.robomw.api.ReturnType;
import io.robomw.api.RobotException;
import io.robomw.api.SensorInfo;
import io.robomw.api.SensorType;
import io.robomw.api.UnsupportedActionException;
import io.robomw.console.rosbridge.BridgedRobot;
import io.robomw.console.rosbridge.SensorGeometry;
import io.robomw.console.rosbridge.graph.Graph;
import io.robomw.console.rosbridge.graph.Topic;
import io.robomw.console.rosbridge.msg.Interfaces;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.time.Clock;
import java.time.Instant;
import java.util.ArrayList;
import java.util.List;
import java.util.Optional;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.RejectedExecutionException;
import java.util.concurrent.atomic.AtomicBoolean;
import java.util.concurrent.atomic.AtomicLong;

/**
 * One robot as a ROS 2 node named after it ({@code /<ns>}, {@code <ns>} its
 * {@link Graph#namespace namespace}), with these topics:
 *
 * <table>
 *   <caption>a robot's topics</caption>
 *   <tr><th>topic</th><th>type</th><th>what</th></tr>
 *   <tr><td>{@code /<ns>/odom}</td><td>{@code nav_msgs/msg/Odometry}</td><td>{@code robot.pose()} at the odometry rate; the twist is the
 *   change since the sample before</td></tr>
 *   <tr><td>{@code /<ns>/cmd_vel}</td><td>{@code geometry_msgs/msg/Twist}</td><td>in: {@code robot.drive(linear.x, angular.z)} ({@link DriveSink})</td></tr>
 *   <tr><td>{@code /<ns>/range/<sensor>}</td><td>{@code sensor_msgs/msg/Range}</td><td>each range finder (sonar, infra-red, laser, range),
 *   read in metres at its rate</td></tr>
 *   <tr><td>{@code /<ns>/joint_states}</td><td>{@code sensor_msgs/msg/JointState}</td><td>the joint sensors (a legged robot's), radians</td></tr>
 *   <tr><td>{@code /<ns>/battery_state}</td><td>{@code sensor_msgs/msg/BatteryState}</td><td>a battery sensor (a vehicle's): {@code percentage} 0 to 1
 *   ({@code /<ns>/battery_state/<sensor>} each, for several)</td></tr>
 * </table>
 * and its pose in {@code /tf} ({@link TransformFeed}). Nothing is read while a topic has no
 * subscriber. A robot without odometry (its {@code pose()} is unsupported) publishes none, unless
 * it is simulated: then {@code odom} and {@code /tf} carry the simulator's true pose of its body;
 * a failed read is skipped and logged (at growing intervals), and the next one is tried.
 */
public final class RobotNode implements AutoCloseable {

    private static final Logger LOG = LoggerFactory.getLogger(RobotNode.class);
    private static final String ODOMETRY = "nav_msgs/msg/Odometry";

    private final BridgedRobot robot;
    private final String ns;
    private final String node;
    private final Threads threads;
    private final Clock clock;
    private final Topic odom;
    private final Topic cmdVel;
    private final DriveSink drive;
    private final Periodic poseFeed;
    private final List<Periodic> feeds = new ArrayList<>();
    private final AtomicBoolean poseInFlight = new AtomicBoolean();
    private final AtomicLong failures = new AtomicLong();
    private final List<PoseSample> window = new ArrayList<>();
    private volatile PoseSample latest;
    private volatile boolean noOdometry;
    private volatile boolean truth;
    private volatile boolean tfWanted;

    private RobotNode(BridgedRobot robot, Graph graph, double odometryHz, Threads threads, Clock clock) {
        this.robot = robot;
        this.ns = Graph.namespace(robot.robot().name());
        this.node = "/" + ns;
        this.threads = threads;
        this.clock = clock;
        Interfaces types = graph.interfaces();
        this.odom = graph.declare(node + "/odom", types.message(ODOMETRY), false);
        odom.addPublisher(node);
        this.cmdVel = graph.declare(node + "/cmd_vel", types.message("geometry_msgs/msg/Twist"), false);
        this.drive = new DriveSink(robot, threads);
        cmdVel.addSink(drive, node);
        this.poseFeed = new Periodic(threads, odometryHz, this::samplePose, "rosbridge " + ns + " odometry");
    }

    /**
     * Declares the robot's topics in the graph and starts serving them on demand.
     *
     * @param robot      the robot
     * @param graph      the graph
     * @param odometryHz odometry samples per second
     * @param sensorRate each sensor's readings per second
     * @param threads    where samples and calls run
     * @param clock      the stamps' clock (the wall clock, as ROS nodes stamp without simulated time)
     * @return the node
     */
    public static RobotNode start(BridgedRobot robot, Graph graph, double odometryHz, java.util.function.ToDoubleFunction<SensorGeometry> sensorRate,
                                  Threads threads, Clock clock) {
        RobotNode n = new RobotNode(robot, graph, odometryHz, threads, clock);
        n.odom.onDemand(wanted -> n.poseFeed.demand(!n.noOdometry && (wanted || n.tfWanted)));
        Interfaces types = graph.interfaces();
        List<SensorInfo> joints = new ArrayList<>();
        List<SensorInfo> batteries = new ArrayList<>();
        double jointHz = 0;
        for (SensorInfo s : robot.robot().sensors()) {
            SensorGeometry g = robot.geometry(s);
            if (s.type().ranging()) {
                Topic t = graph.declare(n.node + "/range/" + Graph.namespace(s.name()), types.message("sensor_msgs/msg/Range"), false);
                t.addPublisher(n.node);
                Periodic p = new Periodic(threads, sensorRate.applyAsDouble(g), n.rangeReader(s, g, t), "rosbridge " + n.ns + " " + s.name());
                n.feeds.add(p);
                t.onDemand(p::demand);
            } else if (s.type() == SensorType.JOINT) {
                joints.add(s);
                jointHz = Math.max(jointHz, sensorRate.applyAsDouble(g));
            } else if (s.type() == SensorType.BATTERY) {
                batteries.add(s);
            }
        }
        for (SensorInfo s : batteries) {
            // one battery: battery_state, as ROS drivers name it; several: one topic each, by sensor name
            String name = batteries.size() == 1 ? "/battery_state" : "/battery_state/" + Graph.namespace(s.name());
            Topic t = graph.declare(n.node + name, types.message("sensor_msgs/msg/BatteryState"), false);
            t.addPublisher(n.node);
            Periodic p = new Periodic(threads, sensorRate.applyAsDouble(robot.geometry(s)), n.batteryReader(s, t), "rosbridge " + n.ns + " " + s.name());
            n.feeds.add(p);
            t.onDemand(p::demand);
        }
        if (!joints.isEmpty()) {
            Topic t = graph.declare(n.node + "/joint_states", types.message("sensor_msgs/msg/JointState"), false);
            t.addPublisher(n.node);
            Periodic p = new Periodic(threads, jointHz, n.jointReader(joints, t), "rosbridge " + n.ns + " joints");
            n.feeds.add(p);
            t.onDemand(p::demand);
        }
        return n;
    }

    /** @return the robot */
    public BridgedRobot robot() {
        return robot;
    }

    /** @return its ROS namespace */
    public String namespace() {
        return ns;
    }

    /** @return its node's name, {@code /<ns>} */
    public String node() {
        return node;
    }

    /** @return the latest pose sample, if one was taken */
    Optional<PoseSample> latest() {
        return Optional.ofNullable(latest);
    }

    /** @param wanted whether {@code /tf} has subscribers, which need this robot's pose */
    void tfDemand(boolean wanted) {
        tfWanted = wanted;
        poseFeed.demand(!noOdometry && (wanted || odom.hasSubscribers()));
    }

    /**
     * @param stamp the stamp
     * @return {@code <ns>/base_link} to each sensor's frame, where the sensor sits
     */
    List<ObjectNode> sensorMounts(Instant stamp) {
        List<ObjectNode> out = new ArrayList<>();
        for (SensorInfo s : robot.robot().sensors()) {
            SensorGeometry g = robot.geometry(s);
            out.add(RosMessages.transform(stamp, ns + "/base_link", ns + "/" + Graph.namespace(s.name()), g.x(), g.y(), 0, g.yaw()));
        }
        return out;
    }

    private void samplePose() {
        if (noOdometry) {
            return;
        }
        if (robot.reach() == BridgedRobot.Reach.IN_PROCESS) {
            takePose();
            return;
        }
        if (!poseInFlight.compareAndSet(false, true)) {
            return; // the last one is still on its way: skip a tick rather than queue calls
        }
        try {
            threads.blocking().execute(() -> {
                try {
                    takePose();
                } catch (Throwable t) {
                    threads.failures().surviveOrRethrow("rosbridge " + ns + " odometry", t);
                } finally {
                    poseInFlight.set(false);
                }
            });
        } catch (RejectedExecutionException e) {
            poseInFlight.set(false); // closing
        }
    }

    private void takePose() {
        Pose p;
        try {
            p = truth ? robot.truePose().get() : robot.robot().pose();
        } catch (UnsupportedActionException e) {
            if (robot.truePose() != null) {
                truth = true;
                LOG.info("rosbridge: robot '{}' has no odometry ({}); {}/odom carries the simulator's true pose", robot.robot().name(), e.getMessage(), node);
                return;
            }
            noOdometry = true;
            poseFeed.demand(false);
            LOG.info("rosbridge: robot '{}' has no odometry ({}); {}/odom and its /tf stay empty", robot.robot().name(), e.getMessage(), node);
            return;
        } catch (RobotException e) {
            failed("its pose", e);
            return;
        }
        PoseSample s;
        synchronized (window) {
            Instant now = clock.instant();
            Instant from = now.minus(PoseSample.WINDOW);
            while (window.size() > 1 && !window.get(1).stamp().isAfter(from)) {
                window.remove(0); // keep one sample at or before the window's start
            }
            s = PoseSample.after(window.isEmpty() ? null : window.get(0), p, now);
            window.add(s);
            latest = s;
        }
        if (odom.hasSubscribers()) {
            odom.publish(RosMessages.odometry(s, ns));
        }
    }

    private Runnable rangeReader(SensorInfo s, SensorGeometry g, Topic topic) {
        String frame = ns + "/" + Graph.namespace(s.name());
        return sensorReader(s, ReturnType.METERS, metres -> topic.publish(
                RosMessages.range(clock.instant(), frame, g.radiation().code(), g.fieldOfView(), g.minRange(), g.maxRange(), metres)));
    }

    private Runnable batteryReader(SensorInfo s, Topic topic) {
        return sensorReader(s, ReturnType.PERCENT, percent -> topic.publish(
                RosMessages.batteryState(clock.instant(), ns + "/base_link", percent / 100.0, s.name())));
    }

    /**
     * A reader of one sensor for a topic's timer: one read at a time (a tick while the last is in
     * flight is skipped), each value handed to {@code publish}, a failure reported and the next tick
     * tried again.
     */
    private Runnable sensorReader(SensorInfo s, ReturnType unit, java.util.function.DoubleConsumer publish) {
        AtomicBoolean inFlight = new AtomicBoolean();
        return () -> {
            if (!inFlight.compareAndSet(false, true)) {
                return;
            }
            CompletableFuture<Double> reading;
            try {
                reading = robot.robot().getValueAsync(s.name(), unit);
            } catch (RuntimeException e) {
                inFlight.set(false);
                failed("sensor " + s.name(), e);
                return;
            }
            reading.whenComplete((value, e) -> {
                inFlight.set(false);
                if (e != null) {
                    failed("sensor " + s.name(), e);
                } else {
                    publish.accept(value);
                }
            });
        };
    }

    private Runnable jointReader(List<SensorInfo> joints, Topic topic) {
        AtomicBoolean inFlight = new AtomicBoolean();
        List<String> names = joints.stream().map(SensorInfo::name).toList();
        return () -> {
            if (!inFlight.compareAndSet(false, true)) {
                return;
            }
            List<CompletableFuture<Double>> readings = new ArrayList<>();
            try {
                for (SensorInfo s : joints) {
                    readings.add(robot.robot().getValueAsync(s.name(), ReturnType.RADIANS));
                }
            } catch (RuntimeException e) {
                inFlight.set(false);
                failed("its joints", e);
                return;
            }
            CompletableFuture.allOf(readings.toArray(CompletableFuture[]::new)).whenComplete((v, e) -> {
                inFlight.set(false);
                if (e != null) {
                    failed("its joints", e);
                    return;
                }
                double[] positions = readings.stream().mapToDouble(CompletableFuture::join).toArray();
                topic.publish(RosMessages.jointState(clock.instant(), ns + "/base_link", names, positions));
            });
        };
    }

    private void failed(String what, Throwable e) {
        long n = failures.incrementAndGet();
        if (Long.bitCount(n) == 1) {
            Throwable cause = e instanceof java.util.concurrent.CompletionException && e.getCause() != null ? e.getCause() : e;
            LOG.info("rosbridge: reading {} of robot '{}' failed: {} ({} failed reads so far; the next is tried)", what, robot.robot().name(),
                    cause.getMessage(), n);
        }
    }

    /** Stops sampling and driving; the graph keeps the topics. */
    @Override
    public void close() {
        poseFeed.demand(false);
        for (Periodic p : feeds) {
            p.demand(false);
        }
        cmdVel.removeSink(drive);
    }

}
