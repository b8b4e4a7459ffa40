package io.robomw.console.rosbridge.robot;

import com.fasterxml.jackson.databind.node.ObjectNode;
import io.robomw.api.Pose;
import io.robomw.console.rosbridge.msg.Interfaces;
import io.robomw.console.rosbridge.msg.MessageReader;
import io.robomw.console.rosbridge.msg.Wire;
import org.junit.jupiter.api.Test;

import java.time.Clock;
import java.time.Instant;
import java.util.List;

import static org.junit.jupiter.api.Assertions.assertEquals;

/**
 * The messages the bridge builds by hand are complete messages of their types: reading one back
 * against its definition changes nothing (no field missing, none extra, each of its kind).
 */
class RosMessagesTest {

    private static final Instant T = Instant.parse("2026-05-01T12:00:01.5Z");
    private final Interfaces interfaces = Interfaces.load();
    private final MessageReader reader = new MessageReader(interfaces, Clock.systemUTC());

    private void conforms(ObjectNode built, String type) {
        assertEquals(Wire.json(built), Wire.json(reader.read(built, interfaces.message(type))), type);
    }

    @Test
    void odometryIsACompleteOdometryWithTheRobotsFrames() {
        PoseSample s = new PoseSample(new Pose(1, 2, Math.PI / 2), 0, T, 0.2, 0.1);
        ObjectNode odom = RosMessages.odometry(s, "nxt_1");
        conforms(odom, "nav_msgs/msg/Odometry");
        assertEquals("nxt_1/odom", odom.at("/header/frame_id").asText());
        assertEquals(1_777_636_801L, odom.at("/header/stamp/sec").longValue());
        assertEquals(500_000_000L, odom.at("/header/stamp/nanosec").longValue());
        assertEquals(Math.sqrt(0.5), odom.at("/pose/pose/orientation/z").doubleValue(), 1e-12, "heading 90° about z");
        assertEquals(0.2, odom.at("/twist/twist/linear/x").doubleValue());
        assertEquals(0.1, odom.at("/twist/twist/angular/z").doubleValue());
    }

    @Test
    void rangeTfAndJointStatesAreCompleteMessagesOfTheirTypes() {
        conforms(RosMessages.range(T, "nxt/sonar", 0, 0.5, 0.03, 2.55, 1.25), "sensor_msgs/msg/Range");
        conforms(RosMessages.tf(List.of(RosMessages.odomToBase(new PoseSample(Pose.ORIGIN, 0, T, 0, 0), "nxt"),
                RosMessages.transform(T, "nxt/base_link", "nxt/sonar", 0.1, 0, 0, 0))), "tf2_msgs/msg/TFMessage");
        conforms(RosMessages.jointState(T, "aibo/base_link", List.of("neck", "tail"), new double[] {0.1, -0.2}), "sensor_msgs/msg/JointState");
    }

    @Test
    void aFlyersOdometryAndTransformCarryItsAltitude() {
        PoseSample s = PoseSample.after(null, new Pose(1, 2, 0, 2.5), T);
        ObjectNode odom = RosMessages.odometry(s, "copter");
        conforms(odom, "nav_msgs/msg/Odometry");
        assertEquals(2.5, odom.at("/pose/pose/position/z").doubleValue(), 1e-12, "z up, the pose's altitude");
        assertEquals(2.5, RosMessages.odomToBase(s, "copter").at("/transform/translation/z").doubleValue(), 1e-12);
        PoseSample later = PoseSample.after(s, new Pose(1.1, 2, 0, 2.75), T.plusMillis(200));
        assertEquals(2.75, later.z(), 1e-12);
    }

    @Test
    void aSamplesVelocityIsInTheBodyFrame() {
        PoseSample a = new PoseSample(new Pose(0, 0, Math.PI / 2), 0, T, 0, 0);
        PoseSample b = PoseSample.after(a, new Pose(0, 0.1, Math.PI / 2 + 0.05), T.plusMillis(200));
        assertEquals(0.5, b.forward(), 1e-9, "moving along its heading (+y) is forwards");
        assertEquals(0.25, b.turning(), 1e-9);
    }
}
