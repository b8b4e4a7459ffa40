package io.robomw.console.rosbridge.robot;

import com.fasterxml.jackson.databind.node.ArrayNode;
import com.fasterxml.jackson.databind.node.JsonNodeFactory;
import com.fasterxml.jackson.databind.node.ObjectNode;
import io.robomw.api.Pose;
import io.robomw.console.rosbridge.msg.MessageReader;
import io.robomw.console.rosbridge.msg.NumberSequence;
import io.robomw.console.rosbridge.msg.Primitive;

import java.time.Instant;
import java.util.List;

/**
 * The bridge's own messages, built field by field in their types' order (the tests read each
 * against its definition): cheaper than filling a default message, which matters for a hundred
 * robots' odometry at 50 Hz.
 *
 * <h2>Frames (REP 105, one tree per robot)</h2>
 * {@code <ns>/odom} is where the robot's odometry started; {@code <ns>/base_link} is its body,
 * x forwards, y left, z up; {@code <ns>/<sensor>} is a sensor, facing along its x axis.
 * {@code <ns>} is the robot's ROS namespace (its name, with characters ROS names do not allow
 * made {@code _}).
 */
final class RosMessages {

    private static final JsonNodeFactory NODES = JsonNodeFactory.instance;
    /** The unknown covariance ROS drivers send: all zeros. Shared and never changed. */
    private static final ArrayNode ZERO_COVARIANCE;

    static {
        ArrayNode zeros = NODES.arrayNode(36);
        for (int i = 0; i < 36; i++) {
            zeros.add(0.0);
        }
        ZERO_COVARIANCE = zeros;
    }

    private RosMessages() {
    }

    static ObjectNode header(Instant stamp, String frame) {
        ObjectNode h = NODES.objectNode();
        h.set("stamp", MessageReader.time(stamp));
        h.put("frame_id", frame);
        return h;
    }

    static ObjectNode vector(double x, double y, double z) {
        ObjectNode v = NODES.objectNode();
        v.put("x", x);
        v.put("y", y);
        v.put("z", z);
        return v;
    }

    /** A rotation about z by {@code yaw} radians. */
    static ObjectNode yaw(double yaw) {
        ObjectNode q = NODES.objectNode();
        q.put("x", 0.0);
        q.put("y", 0.0);
        q.put("z", Math.sin(yaw / 2));
        q.put("w", Math.cos(yaw / 2));
        return q;
    }

    /**
     * {@code nav_msgs/msg/Odometry}: the pose in {@code <ns>/odom}, the velocity in {@code <ns>/base_link}.
     *
     * @param s  the sample
     * @param ns the robot's namespace
     * @return the message
     */
    static ObjectNode odometry(PoseSample s, String ns) {
        ObjectNode m = NODES.objectNode();
        m.set("header", header(s.stamp(), ns + "/odom"));
        m.put("child_frame_id", ns + "/base_link");
        ObjectNode pose = m.putObject("pose");
        ObjectNode p = pose.putObject("pose");
        p.set("position", vector(s.pose().x(), s.pose().y(), s.z()));
        p.set("orientation", yaw(s.pose().heading()));
        pose.set("covariance", ZERO_COVARIANCE);
        ObjectNode twist = m.putObject("twist");
        ObjectNode t = twist.putObject("twist");
        t.set("linear", vector(s.forward(), 0, 0));
        t.set("angular", vector(0, 0, s.turning()));
        twist.set("covariance", ZERO_COVARIANCE);
        return m;
    }

    /**
     * {@code geometry_msgs/msg/TransformStamped}: {@code <ns>/odom} to {@code <ns>/base_link}.
     *
     * @param s  the sample
     * @param ns the robot's namespace
     * @return the transform
     */
    static ObjectNode odomToBase(PoseSample s, String ns) {
        return transform(s.stamp(), ns + "/odom", ns + "/base_link", s.pose().x(), s.pose().y(), s.z(), s.pose().heading());
    }

    static ObjectNode transform(Instant stamp, String parent, String child, double x, double y, double z, double yaw) {
        ObjectNode t = NODES.objectNode();
        t.set("header", header(stamp, parent));
        t.put("child_frame_id", child);
        ObjectNode tr = t.putObject("transform");
        tr.set("translation", vector(x, y, z));
        tr.set("rotation", yaw(yaw));
        return t;
    }

    /**
     * @param transforms {@code TransformStamped}s
     * @return a {@code tf2_msgs/msg/TFMessage}
     */
    static ObjectNode tf(List<ObjectNode> transforms) {
        ObjectNode m = NODES.objectNode();
        ArrayNode a = m.putArray("transforms");
        transforms.forEach(a::add);
        return m;
    }

    /**
     * {@code sensor_msgs/msg/Range}.
     *
     * @param stamp     when read
     * @param frame     the sensor's frame
     * @param radiation {@code Range.ULTRASOUND} (0) or {@code INFRARED} (1)
     * @param fov       the beam's angle, radians
     * @param min       nearest, metres
     * @param max       farthest, metres
     * @param range     the reading, metres
     * @return the message
     */
    static ObjectNode range(Instant stamp, String frame, int radiation, double fov, double min, double max, double range) {
        ObjectNode m = NODES.objectNode();
        m.set("header", header(stamp, frame));
        m.put("radiation_type", radiation);
        m.put("field_of_view", (float) fov);
        m.put("min_range", (float) min);
        m.put("max_range", (float) max);
        m.put("range", (float) range);
        return m;
    }

    /**
     * {@code sensor_msgs/msg/JointState} with positions only.
     *
     * @param stamp     when read
     * @param frame     the robot's body frame
     * @param names     the joints
     * @param positions their angles, radians
     * @return the message
     */
    static ObjectNode jointState(Instant stamp, String frame, List<String> names, double[] positions) {
        ObjectNode m = NODES.objectNode();
        m.set("header", header(stamp, frame));
        ArrayNode n = m.putArray("name");
        names.forEach(n::add);
        m.putPOJO("position", NumberSequence.ofFloats(Primitive.FLOAT64, positions));
        m.putPOJO("velocity", NumberSequence.ofFloats(Primitive.FLOAT64));
        m.putPOJO("effort", NumberSequence.ofFloats(Primitive.FLOAT64));
        return m;
    }

    /**
     * {@code sensor_msgs/msg/BatteryState} with what a RoboMW battery sensor gives: the charge left
     * as {@code percentage} (0 to 1, as the message wants it) and {@code present}; what is not
     * measured is NaN (null on JSON) or unknown (0), as the message's own comments ask.
     *
     * @param stamp    when read
     * @param frame    the robot's body frame
     * @param fraction the charge left, 0 to 1
     * @param location the sensor's name
     * @return the message
     */
    static ObjectNode batteryState(Instant stamp, String frame, double fraction, String location) {
        ObjectNode m = NODES.objectNode();
        m.set("header", header(stamp, frame));
        for (String unmeasured : new String[] {"voltage", "temperature", "current", "charge", "capacity", "design_capacity"}) {
            m.put(unmeasured, Float.NaN);
        }
        m.put("percentage", (float) fraction);
        m.put("power_supply_status", 0);
        m.put("power_supply_health", 0);
        m.put("power_supply_technology", 0);
        m.put("present", true);
        m.putPOJO("cell_voltage", NumberSequence.ofFloats(Primitive.FLOAT32));
        m.putPOJO("cell_temperature", NumberSequence.ofFloats(Primitive.FLOAT32));
        m.put("location", location);
        m.put("serial_number", "");
        return m;
    }

    /**
     * @param pose a pose
     * @return it as a {@code geometry_msgs/msg/Pose}-shaped position and heading, for logs and tests
     */
    static String describe(Pose pose) {
        return String.format(java.util.Locale.ROOT, "(%.3f, %.3f, %.1f°)", pose.x(), pose.y(), Math.toDegrees(pose.heading()));
    }
}
