package io.robomw.console.rosbridge.msg;

import org.junit.jupiter.api.Test;

import java.util.List;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/** The bridge's interface definitions load, name their types both ways, and say what they hold. */
class InterfacesTest {

    private final Interfaces interfaces = Interfaces.load();

    @Test
    void bothSpellingsOfATypeNameTheSameType() {
        assertEquals(interfaces.message("geometry_msgs/msg/Twist"), interfaces.message("geometry_msgs/Twist"));
        assertEquals("geometry_msgs/msg/Twist", TypeName.parse("geometry_msgs/Twist", TypeName.Kind.MSG).full());
        assertEquals("robomw_msgs/Move", TypeName.parse("robomw_msgs/srv/Move", TypeName.Kind.SRV).shortName());
    }

    @Test
    void aNameThatIsNeitherSpellingIsRefusedSayingHowToWriteIt() {
        IllegalArgumentException e = assertThrows(IllegalArgumentException.class, () -> TypeName.parse("geometry_msgs/srv/Twist", TypeName.Kind.MSG));
        assertTrue(e.getMessage().contains("pkg/msg/Type"), e.getMessage());
        assertThrows(IllegalArgumentException.class, () -> TypeName.parse("Twist", TypeName.Kind.MSG));
        assertThrows(IllegalArgumentException.class, () -> TypeName.parse("a/b/c/d", TypeName.Kind.MSG));
        assertThrows(IllegalArgumentException.class, () -> TypeName.parse("9pkg/Type", TypeName.Kind.MSG));
    }

    @Test
    void anUnknownTypeIsRefusedNamingThePackagesTheBridgeKnows() {
        IllegalArgumentException e = assertThrows(IllegalArgumentException.class, () -> interfaces.message("my_pkg/msg/Foo"));
        assertTrue(e.getMessage().contains("nav_msgs") && e.getMessage().contains("robomw_msgs"), e.getMessage());
    }

    @Test
    void odometryHasROS2sFieldsInOrder() {
        MessageType odom = interfaces.message("nav_msgs/msg/Odometry");
        assertEquals(List.of("header", "child_frame_id", "pose", "twist"), odom.fields().stream().map(Field::name).toList());
        Field covariance = interfaces.message("geometry_msgs/msg/PoseWithCovariance").field("covariance").orElseThrow();
        assertEquals(Field.Shape.FIXED, covariance.shape());
        assertEquals(36, covariance.arrayLength());
        assertEquals("double", covariance.elementTypeName());
    }

    @Test
    void rangeHasItsConstantsAndNoVarianceAsInJazzy() {
        MessageType range = interfaces.message("sensor_msgs/msg/Range");
        assertEquals(List.of("ULTRASOUND", "INFRARED"), range.constants().stream().map(Constant::name).toList());
        assertFalse(range.field("variance").isPresent());
        assertEquals("float", range.field("range").orElseThrow().elementTypeName());
    }

    @Test
    void aQuaternionDefaultsToNoRotation() {
        assertEquals(1.0, interfaces.message("geometry_msgs/msg/Quaternion").field("w").orElseThrow().defaultValue().doubleValue());
    }

    @Test
    void aServiceHasARequestAndAResponse() {
        ServiceType move = interfaces.service("robomw_msgs/srv/Move");
        assertEquals(List.of("distance", "speed"), move.request().fields().stream().map(Field::name).toList());
        assertEquals(List.of("success", "message"), move.response().fields().stream().map(Field::name).toList());
        assertEquals("robomw_msgs/Move_Request", move.request().name().shortName());
        assertTrue(interfaces.service("std_srvs/Trigger").request().fields().isEmpty());
    }

    @Test
    void aTypesDependenciesComeOnceEachAfterIt() {
        List<String> names = interfaces.withDependencies(interfaces.message("nav_msgs/msg/Odometry")).stream().map(t -> t.name().shortName()).toList();
        assertEquals("nav_msgs/Odometry", names.get(0));
        assertTrue(names.containsAll(List.of("std_msgs/Header", "builtin_interfaces/Time", "geometry_msgs/PoseWithCovariance", "geometry_msgs/Pose",
                "geometry_msgs/Point", "geometry_msgs/Quaternion", "geometry_msgs/TwistWithCovariance", "geometry_msgs/Twist", "geometry_msgs/Vector3")), names.toString());
        assertEquals(names.size(), names.stream().distinct().count());
        String text = interfaces.fullText(interfaces.message("tf2_msgs/msg/TFMessage"));
        assertTrue(text.startsWith("geometry_msgs/TransformStamped[] transforms"), text);
        assertTrue(text.contains("\n================================================================================\nMSG: geometry_msgs/TransformStamped\n"), text);
    }
}
