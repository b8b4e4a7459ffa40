package io.robomw.console.rosbridge.msg;

import com.fasterxml.jackson.databind.JsonNode;
import com.fasterxml.jackson.databind.ObjectMapper;
import com.fasterxml.jackson.databind.node.ObjectNode;
import com.fasterxml.jackson.databind.node.POJONode;
import org.junit.jupiter.api.Test;

import java.time.Clock;
import java.time.Instant;
import java.time.ZoneOffset;

import static org.junit.jupiter.api.Assertions.assertArrayEquals;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/** A client's message is read against its type as rosbridge_suite's populate_instance reads it. */
class MessageReaderTest {

    private static final ObjectMapper JSON = new ObjectMapper();
    private static final Instant NOW = Instant.parse("2026-05-01T12:00:00.250Z");

    private final Interfaces interfaces = Interfaces.load();
    private final MessageReader reader = new MessageReader(interfaces, Clock.fixed(NOW, ZoneOffset.UTC));

    private ObjectNode read(String json, String type) throws Exception {
        return reader.read(JSON.readTree(json), interfaces.message(type));
    }

    @Test
    void fieldsLeftOutGetTheirDefaults() throws Exception {
        ObjectNode twist = read("{\"linear\":{\"x\":0.2}}", "geometry_msgs/msg/Twist");
        assertEquals("{\"linear\":{\"x\":0.2,\"y\":0.0,\"z\":0.0},\"angular\":{\"x\":0.0,\"y\":0.0,\"z\":0.0}}", Wire.json(twist));
        assertEquals(1.0, read("{}", "geometry_msgs/msg/Quaternion").get("w").doubleValue());
        assertEquals(Wire.json(read("{}", "geometry_msgs/msg/Twist")), Wire.json(reader.read(null, interfaces.message("geometry_msgs/msg/Twist"))));
    }

    @Test
    void aHeadersStampDefaultsToNow() throws Exception {
        ObjectNode stamped = read("{\"header\":{\"frame_id\":\"map\"}}", "geometry_msgs/msg/PoseStamped");
        assertEquals(NOW.getEpochSecond(), stamped.at("/header/stamp/sec").longValue());
        assertEquals(250_000_000L, stamped.at("/header/stamp/nanosec").longValue());
    }

    @Test
    void aFieldTheTypeDoesNotHaveIsRefusedInRosbridgesWords() {
        MessageException e = assertThrows(MessageException.class, () -> read("{\"linear\":{\"q\":1}}", "geometry_msgs/msg/Twist"));
        assertEquals("Message type geometry_msgs/Twist does not have a field linear.q", e.getMessage());
    }

    @Test
    void aValueOfTheWrongKindIsRefusedNamingTheField() {
        MessageException e = assertThrows(MessageException.class, () -> read("{\"linear\":{\"x\":\"fast\"}}", "geometry_msgs/msg/Twist"));
        assertEquals("geometry_msgs/Twist message requires a float64 for field linear.x, but got a string", e.getMessage());
        MessageException top = assertThrows(MessageException.class, () -> read("[1,2]", "geometry_msgs/msg/Twist"));
        assertEquals("Expected a JSON object for type geometry_msgs/Twist but received a list", top.getMessage());
    }

    @Test
    void anIntegerIsTakenForAFloatButNotTheOtherWayRound() throws Exception {
        assertEquals(1.0, read("{\"data\":1}", "std_msgs/msg/Float64").get("data").doubleValue());
        assertThrows(MessageException.class, () -> read("{\"data\":1.5}", "std_msgs/msg/Int32"));
        assertThrows(MessageException.class, () -> read("{\"data\":true}", "std_msgs/msg/Int32"));
        assertThrows(MessageException.class, () -> read("{\"data\":1}", "std_msgs/msg/Bool"));
    }

    @Test
    void anIntegerMustFitItsType() {
        MessageException e = assertThrows(MessageException.class, () -> read("{\"data\":2147483648}", "std_msgs/msg/Int32"));
        assertTrue(e.getMessage().contains("out of its range"), e.getMessage());
        assertThrows(MessageException.class, () -> read("{\"radiation_type\":256}", "sensor_msgs/msg/Range"));
        assertThrows(MessageException.class, () -> read("{\"radiation_type\":-1}", "sensor_msgs/msg/Range"));
    }

    @Test
    void nullForAFloatIsNaNSoWhatTheBridgeSentCanBeSentBack() throws Exception {
        assertTrue(Double.isNaN(read("{\"data\":null}", "std_msgs/msg/Float64").get("data").doubleValue()));
        ObjectNode scan = read("{\"ranges\":[1.5,null,2]}", "sensor_msgs/msg/LaserScan");
        NumberSequence ranges = (NumberSequence) ((POJONode) scan.get("ranges")).getPojo();
        assertEquals(1.5, ranges.floats()[0]);
        assertTrue(Double.isNaN(ranges.floats()[1]));
        assertEquals(Primitive.FLOAT32, ranges.element());
    }

    @Test
    void aTimeIsReadInROS2sAndROS1sNamesOrAsNow() throws Exception {
        assertEquals("{\"sec\":3,\"nanosec\":5}", Wire.json(read("{\"stamp\":{\"sec\":3,\"nanosec\":5}}", "std_msgs/msg/Header").get("stamp")));
        assertEquals("{\"sec\":3,\"nanosec\":5}", Wire.json(read("{\"stamp\":{\"secs\":3,\"nsecs\":5}}", "std_msgs/msg/Header").get("stamp")));
        assertEquals(NOW.getEpochSecond(), read("{\"stamp\":\"now\"}", "std_msgs/msg/Header").at("/stamp/sec").longValue());
        assertThrows(MessageException.class, () -> read("{\"stamp\":{\"sec\":1,\"nanosec\":1000000000}}", "std_msgs/msg/Header"));
    }

    @Test
    void bytesComeAsBase64OrAsAListOfNumbers() throws Exception {
        JsonNode fromText = read("{\"data\":\"AQID\"}", "std_msgs/msg/UInt8MultiArray").get("data");
        assertArrayEquals(new byte[] {1, 2, 3}, fromText.binaryValue());
        JsonNode fromList = read("{\"data\":[1,2,255]}", "std_msgs/msg/UInt8MultiArray").get("data");
        assertArrayEquals(new byte[] {1, 2, (byte) 255}, fromList.binaryValue());
        assertThrows(MessageException.class, () -> read("{\"data\":\"not base64!\"}", "std_msgs/msg/UInt8MultiArray"));
        assertThrows(MessageException.class, () -> read("{\"data\":[256]}", "std_msgs/msg/UInt8MultiArray"));
    }

    @Test
    void aFixedArrayMustHaveItsLength() {
        MessageException e = assertThrows(MessageException.class, () -> read("{\"covariance\":[1,2,3]}", "geometry_msgs/msg/PoseWithCovariance"));
        assertEquals("geometry_msgs/PoseWithCovariance message requires exactly 36 values for field covariance, got 3", e.getMessage());
    }

    @Test
    void anArrayOfMessagesIsReadElementByElement() throws Exception {
        ObjectNode tf = read("{\"transforms\":[{\"child_frame_id\":\"a\"},{\"transform\":{\"rotation\":{\"z\":1,\"w\":0}}}]}", "tf2_msgs/msg/TFMessage");
        assertEquals(2, tf.get("transforms").size());
        assertEquals("a", tf.at("/transforms/0/child_frame_id").asText());
        assertEquals(1.0, tf.at("/transforms/0/transform/rotation/w").doubleValue());
        MessageException e = assertThrows(MessageException.class, () -> read("{\"transforms\":[{\"bogus\":1}]}", "tf2_msgs/msg/TFMessage"));
        assertEquals("Message type tf2_msgs/TFMessage does not have a field transforms.0.bogus", e.getMessage());
    }
}
