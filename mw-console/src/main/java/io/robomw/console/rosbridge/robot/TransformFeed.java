package io.robomw.console.rosbridge.robot;

import com.fasterxml.jackson.databind.node.ObjectNode;
import io.robomw.console.rosbridge.graph.Graph;
import io.robomw.console.rosbridge.graph.Topic;

import java.time.Clock;
import java.util.ArrayList;
import java.util.List;

/**
 * {@code /tf} and {@code /tf_static} ({@code tf2_msgs/msg/TFMessage}) for all the bridge's robots:
 *
 * <ul>
 *   <li>{@code /tf}: at the odometry rate, one message with each robot's {@code <ns>/odom} to
 *   {@code <ns>/base_link} (its latest pose sample), while {@code /tf} has subscribers;</li>
 *   <li>{@code /tf_static}, latched (a new subscriber gets it at once, as from ROS 2's
 *   transient-local static broadcaster): each robot's {@code <ns>/base_link} to each of its
 *   sensors' frames, where the sensor sits (the simulator's mount, or the robot file's sensor
 *   options, or the centre of the body facing the sensor's position).</li>
 * </ul>
 */
public final class TransformFeed implements AutoCloseable {

    private final List<RobotNode> robots;
    private final Topic tf;
    private final Periodic feed;

    private TransformFeed(List<RobotNode> robots, Topic tf, Periodic feed) {
        this.robots = robots;
        this.tf = tf;
        this.feed = feed;
    }

    /**
     * Declares {@code /tf} and {@code /tf_static}, publishes the static transforms, and serves {@code /tf} on demand.
     *
     * @param robots     the robots
     * @param graph      the graph
     * @param odometryHz {@code /tf} messages per second
     * @param threads    where it runs
     * @param clock      the stamps' clock
     * @return the feed
     */
    public static TransformFeed start(List<RobotNode> robots, Graph graph, double odometryHz, Threads threads, Clock clock) {
        Topic tf = graph.declare("/tf", graph.interfaces().message("tf2_msgs/msg/TFMessage"), false);
        Topic tfStatic = graph.declare("/tf_static", graph.interfaces().message("tf2_msgs/msg/TFMessage"), true);
        List<ObjectNode> mounts = new ArrayList<>();
        for (RobotNode r : robots) {
            tf.addPublisher(r.node());
            tfStatic.addPublisher(r.node());
            mounts.addAll(r.sensorMounts(clock.instant()));
        }
        tfStatic.publish(RosMessages.tf(mounts));
        List<RobotNode> all = List.copyOf(robots);
        Periodic p = new Periodic(threads, odometryHz, () -> {
            List<ObjectNode> transforms = new ArrayList<>(all.size());
            for (RobotNode r : all) {
                r.latest().ifPresent(s -> transforms.add(RosMessages.odomToBase(s, r.namespace())));
            }
            if (!transforms.isEmpty()) {
                tf.publish(RosMessages.tf(transforms));
            }
        }, "rosbridge /tf");
        TransformFeed f = new TransformFeed(all, tf, p);
        tf.onDemand(wanted -> {
            for (RobotNode r : all) {
                r.tfDemand(wanted);
            }
            p.demand(wanted);
        });
        return f;
    }

    /** Stops publishing {@code /tf}. */
    @Override
    public void close() {
        feed.demand(false);
        for (RobotNode r : robots) {
            r.tfDemand(false);
        }
    }

    /** @return {@code /tf} */
    Topic topic() {
        return tf;
    }
}
