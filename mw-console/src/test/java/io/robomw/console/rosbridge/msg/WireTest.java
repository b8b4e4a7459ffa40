package io.robomw.console.rosbridge.msg;

import com.fasterxml.jackson.core.JsonToken;
import com.fasterxml.jackson.databind.node.JsonNodeFactory;
import com.fasterxml.jackson.databind.node.ObjectNode;
import com.fasterxml.jackson.dataformat.cbor.CBORFactory;
import com.fasterxml.jackson.dataformat.cbor.CBORParser;
import org.junit.jupiter.api.Test;

import java.nio.ByteBuffer;
import java.nio.ByteOrder;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Map;

import static org.junit.jupiter.api.Assertions.assertArrayEquals;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

/** Message trees go out as rosbridge_suite writes them: JSON without NaN, CBOR with typed arrays. */
class WireTest {

    private static final JsonNodeFactory NODES = JsonNodeFactory.instance;

    private static ObjectNode scan() {
        ObjectNode scan = NODES.objectNode();
        scan.put("angle_min", -1.5f);
        scan.put("range_max", Float.POSITIVE_INFINITY);
        scan.putPOJO("ranges", NumberSequence.ofFloats(Primitive.FLOAT32, 1.25, Double.POSITIVE_INFINITY, Double.NaN));
        scan.putPOJO("position", NumberSequence.ofFloats(Primitive.FLOAT64, 0.5, -2));
        scan.putPOJO("counts", NumberSequence.ofIntegers(Primitive.INT32, 7, -1));
        scan.put("data", new byte[] {1, 2, 3, (byte) 0xFF});
        scan.put("nan", Double.NaN);
        return scan;
    }

    @Test
    void jsonHasNullForNaNAndInfinityAndBase64ForBytes() {
        assertEquals("{\"angle_min\":-1.5,\"range_max\":null,\"ranges\":[1.25,null,null],\"position\":[0.5,-2.0],\"counts\":[7,-1],"
                + "\"data\":\"AQID/w==\",\"nan\":null}", Wire.json(scan()));
    }

    @Test
    void aFrameWritesItsFieldsInOrder() {
        Map<String, Object> f = new LinkedHashMap<>();
        f.put("op", "service_response");
        f.put("service", "/x");
        f.put("values", NODES.textNode("no"));
        f.put("result", false);
        f.put("id", NODES.numberNode(7));
        assertEquals("{\"op\":\"service_response\",\"service\":\"/x\",\"values\":\"no\",\"result\":false,\"id\":7}", Wire.jsonFrame(f));
    }

    @Test
    void cborCarriesEachNumberSequenceAsOneLittleEndianTypedArray() throws Exception {
        Map<String, Object> f = new LinkedHashMap<>();
        f.put("op", "publish");
        f.put("topic", "/scan");
        f.put("msg", scan());
        byte[] cbor = Wire.cborFrame(f);
        Map<String, Object> seen = new LinkedHashMap<>();
        try (CBORParser p = new CBORFactory().createParser(cbor)) {
            read(p, "", seen);
        }
        assertEquals("publish", seen.get("op"));
        assertEquals("/scan", seen.get("topic"));
        assertEquals(-1.5f, ((Number) seen.get("msg.angle_min")).floatValue());
        assertEquals(Float.POSITIVE_INFINITY, ((Number) seen.get("msg.range_max")).floatValue(), "CBOR keeps infinities");
        assertEquals(Wire.TAG_FLOAT32_LE, seen.get("msg.ranges#tag"));
        assertArrayEquals(le(Float.BYTES, b -> b.putFloat(1.25f).putFloat(Float.POSITIVE_INFINITY).putFloat(Float.NaN)), (byte[]) seen.get("msg.ranges"));
        assertEquals(Wire.TAG_FLOAT64_LE, seen.get("msg.position#tag"));
        assertArrayEquals(le(Double.BYTES, b -> b.putDouble(0.5).putDouble(-2)), (byte[]) seen.get("msg.position"));
        assertEquals(Wire.TAG_INT32_LE, seen.get("msg.counts#tag"));
        assertArrayEquals(new byte[] {7, 0, 0, 0, -1, -1, -1, -1}, (byte[]) seen.get("msg.counts"));
        assertArrayEquals(new byte[] {1, 2, 3, (byte) 0xFF}, (byte[]) seen.get("msg.data"));
        assertTrue(Double.isNaN(((Number) seen.get("msg.nan")).doubleValue()));
    }

    @Test
    void cborBytesOfATypedArrayReadBackIntoTheSameSequence() throws Exception {
        Interfaces interfaces = Interfaces.load();
        MessageReader reader = new MessageReader(interfaces, java.time.Clock.systemUTC());
        ObjectNode joints = NODES.objectNode();
        joints.putArray("name").add("neck").add("tail");
        joints.putPOJO("position", NumberSequence.ofFloats(Primitive.FLOAT64, 0.25, -1.0));
        Map<String, Object> f = new LinkedHashMap<>();
        f.put("msg", joints);
        ObjectNode decoded = (ObjectNode) new com.fasterxml.jackson.dataformat.cbor.databind.CBORMapper().readTree(Wire.cborFrame(f)).get("msg");
        ObjectNode back = reader.read(decoded, interfaces.message("sensor_msgs/msg/JointState"));
        assertEquals(NumberSequence.ofFloats(Primitive.FLOAT64, 0.25, -1.0), ((com.fasterxml.jackson.databind.node.POJONode) back.get("position")).getPojo());
        assertEquals("[\"neck\",\"tail\"]", Wire.json(back.get("name")));
    }

    @Test
    void everyNumericElementTypeHasItsRfc8746Tag() {
        assertEquals(List.of(69, 70, 71, 72, 77, 78, 79, 85, 86), List.of(Primitive.UINT16, Primitive.UINT32, Primitive.UINT64, Primitive.INT8,
                Primitive.INT16, Primitive.INT32, Primitive.INT64, Primitive.FLOAT32, Primitive.FLOAT64).stream().map(Wire::tag).toList());
    }

    private static byte[] le(int width, java.util.function.Consumer<ByteBuffer> fill) {
        ByteBuffer b = ByteBuffer.allocate(width * 3).order(ByteOrder.LITTLE_ENDIAN);
        fill.accept(b);
        byte[] out = new byte[b.position()];
        b.flip();
        b.get(out);
        return out;
    }

    /** Flattens a CBOR map into path → value, with each typed array's tag under path#tag. */
    private static void read(CBORParser p, String prefix, Map<String, Object> out) throws Exception {
        if (p.nextToken() != JsonToken.START_OBJECT) {
            throw new AssertionError("expected a map");
        }
        readObject(p, prefix, out);
    }

    private static void readObject(CBORParser p, String prefix, Map<String, Object> out) throws Exception {
        while (p.nextToken() == JsonToken.FIELD_NAME) {
            String key = prefix + p.currentName();
            JsonToken t = p.nextToken();
            int tag = p.getCurrentTag();
            if (tag >= 0) {
                out.put(key + "#tag", tag);
            }
            switch (t) {
                case START_OBJECT -> readObject(p, key + ".", out);
                case VALUE_STRING -> out.put(key, p.getText());
                case VALUE_EMBEDDED_OBJECT -> out.put(key, p.getBinaryValue());
                case VALUE_NUMBER_FLOAT, VALUE_NUMBER_INT -> out.put(key, p.getNumberValue());
                default -> out.put(key, p.getText());
            }
        }
    }
}
