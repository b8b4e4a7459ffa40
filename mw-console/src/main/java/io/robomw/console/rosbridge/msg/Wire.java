package io.robomw.console.rosbridge.msg;

import com.fasterxml.jackson.core.JsonFactory;
import com.fasterxml.jackson.core.JsonGenerator;
import com.fasterxml.jackson.core.io.SegmentedStringWriter;
import com.fasterxml.jackson.core.util.BufferRecycler;
import com.fasterxml.jackson.databind.JsonNode;
import com.fasterxml.jackson.databind.node.POJONode;
import com.fasterxml.jackson.dataformat.cbor.CBORFactory;
import com.fasterxml.jackson.dataformat.cbor.CBORGenerator;

import java.io.ByteArrayOutputStream;
import java.io.IOException;
import java.io.UncheckedIOException;
import java.nio.ByteBuffer;
import java.nio.ByteOrder;
import java.util.Iterator;
import java.util.Map;

/**
 * Writes message trees (and whole protocol frames holding them) as the client asked:
 *
 * <ul>
 *   <li><b>JSON</b>, as rosbridge_suite's {@code message_conversion} does: NaN and infinities as
 *   {@code null} ("JSON does not support Inf and NaN"), bytes ({@code uint8[]}) as one base64
 *   string, numeric sequences as lists;</li>
 *   <li><b>CBOR</b> ({@code compression: cbor}), as its {@code cbor_conversion} does: floats as
 *   they are (CBOR has NaN and infinities), bytes as a byte string, and each numeric sequence as
 *   one RFC 8746 typed array, little-endian:
 *   <table>
 *     <caption>typed-array tags</caption>
 *     <tr><th>element</th><th>tag</th></tr>
 *     <tr><td>uint16, uint32, uint64</td><td>{@value #TAG_UINT16_LE}, {@value #TAG_UINT32_LE}, {@value #TAG_UINT64_LE}</td></tr>
 *     <tr><td>int8</td><td>{@value #TAG_INT8}</td></tr>
 *     <tr><td>int16, int32, int64</td><td>{@value #TAG_INT16_LE}, {@value #TAG_INT32_LE}, {@value #TAG_INT64_LE}</td></tr>
 *     <tr><td>float32, float64</td><td>{@value #TAG_FLOAT32_LE}, {@value #TAG_FLOAT64_LE}</td></tr>
 *   </table></li>
 * </ul>
 * Stateless and thread-safe.
 */
public final class Wire {

    /** RFC 8746: uint16 little-endian. */
    public static final int TAG_UINT16_LE = 69;
    /** RFC 8746: uint32 little-endian. */
    public static final int TAG_UINT32_LE = 70;
    /** RFC 8746: uint64 little-endian. */
    public static final int TAG_UINT64_LE = 71;
    /** RFC 8746: sint8. */
    public static final int TAG_INT8 = 72;
    /** RFC 8746: sint16 little-endian. */
    public static final int TAG_INT16_LE = 77;
    /** RFC 8746: sint32 little-endian. */
    public static final int TAG_INT32_LE = 78;
    /** RFC 8746: sint64 little-endian. */
    public static final int TAG_INT64_LE = 79;
    /** RFC 8746: IEEE 754 binary32 little-endian. */
    public static final int TAG_FLOAT32_LE = 85;
    /** RFC 8746: IEEE 754 binary64 little-endian. */
    public static final int TAG_FLOAT64_LE = 86;

    private static final JsonFactory JSON = JsonFactory.builder().build();
    private static final CBORFactory CBOR = CBORFactory.builder().build();

    private Wire() {
    }

    /**
     * @param tree a message tree, or a frame (an object) holding one
     * @return its JSON text
     */
    public static String json(JsonNode tree) {
        try (SegmentedStringWriter w = new SegmentedStringWriter(new BufferRecycler());
             JsonGenerator g = JSON.createGenerator(w)) {
            writeJson(tree, g);
            g.flush();
            return w.getAndClear();
        } catch (IOException e) {
            throw new UncheckedIOException("writing JSON into memory failed", e);
        }
    }

    /**
     * @param frame the frame's fields in order ({@code op}, {@code topic}...), each a tree or a plain value
     * @return the frame's JSON text
     */
    public static String jsonFrame(Map<String, ?> frame) {
        try (SegmentedStringWriter w = new SegmentedStringWriter(new BufferRecycler());
             JsonGenerator g = JSON.createGenerator(w)) {
            g.writeStartObject();
            for (Map.Entry<String, ?> e : frame.entrySet()) {
                g.writeFieldName(e.getKey());
                writeValue(e.getValue(), g, false);
            }
            g.writeEndObject();
            g.flush();
            return w.getAndClear();
        } catch (IOException e) {
            throw new UncheckedIOException("writing JSON into memory failed", e);
        }
    }

    /**
     * @param frame the frame's fields in order, each a tree or a plain value
     * @return the frame as one CBOR map
     */
    public static byte[] cborFrame(Map<String, ?> frame) {
        ByteArrayOutputStream out = new ByteArrayOutputStream(256);
        try (CBORGenerator g = CBOR.createGenerator(out)) {
            g.writeStartObject();
            for (Map.Entry<String, ?> e : frame.entrySet()) {
                g.writeFieldName(e.getKey());
                writeValue(e.getValue(), g, true);
            }
            g.writeEndObject();
        } catch (IOException e) {
            throw new UncheckedIOException("writing CBOR into memory failed", e);
        }
        return out.toByteArray();
    }

    private static void writeValue(Object v, JsonGenerator g, boolean cbor) throws IOException {
        if (v instanceof JsonNode n) {
            if (cbor) {
                writeCbor(n, (CBORGenerator) g);
            } else {
                writeJson(n, g);
            }
        } else if (v instanceof String s) {
            g.writeString(s);
        } else if (v instanceof Boolean b) {
            g.writeBoolean(b);
        } else if (v instanceof Integer i) {
            g.writeNumber(i);
        } else if (v instanceof Long l) {
            g.writeNumber(l);
        } else if (v == null) {
            g.writeNull();
        } else {
            throw new IllegalArgumentException("a frame field holds a " + v.getClass().getName() + ", which the wire does not write");
        }
    }

    private static void writeJson(JsonNode n, JsonGenerator g) throws IOException {
        switch (n.getNodeType()) {
            case OBJECT -> {
                g.writeStartObject();
                for (Iterator<Map.Entry<String, JsonNode>> it = n.fields(); it.hasNext(); ) {
                    Map.Entry<String, JsonNode> e = it.next();
                    g.writeFieldName(e.getKey());
                    writeJson(e.getValue(), g);
                }
                g.writeEndObject();
            }
            case ARRAY -> {
                g.writeStartArray();
                for (JsonNode e : n) {
                    writeJson(e, g);
                }
                g.writeEndArray();
            }
            case NUMBER -> {
                if (n.isFloat()) {
                    float f = n.floatValue();
                    if (Float.isFinite(f)) {
                        g.writeNumber(f);
                    } else {
                        g.writeNull();
                    }
                } else if (n.isDouble()) {
                    double d = n.doubleValue();
                    if (Double.isFinite(d)) {
                        g.writeNumber(d);
                    } else {
                        g.writeNull();
                    }
                } else if (n.isBigInteger()) {
                    g.writeNumber(n.bigIntegerValue());
                } else if (n.isBigDecimal()) {
                    g.writeNumber(n.decimalValue());
                } else {
                    g.writeNumber(n.longValue());
                }
            }
            case BINARY -> g.writeBinary(n.binaryValue());
            case POJO -> writeJsonSequence(sequence(n), g);
            case STRING -> g.writeString(n.textValue());
            case BOOLEAN -> g.writeBoolean(n.booleanValue());
            default -> g.writeNull();
        }
    }

    private static void writeJsonSequence(NumberSequence s, JsonGenerator g) throws IOException {
        g.writeStartArray();
        if (s.floats() != null) {
            boolean single = s.element() == Primitive.FLOAT32;
            for (double d : s.floats()) {
                if (!Double.isFinite(d)) {
                    g.writeNull();
                } else if (single) {
                    g.writeNumber((float) d);
                } else {
                    g.writeNumber(d);
                }
            }
        } else {
            for (long l : s.integers()) {
                if (s.element() == Primitive.UINT64 && l < 0) {
                    g.writeNumber(new java.math.BigInteger(Long.toUnsignedString(l)));
                } else {
                    g.writeNumber(l);
                }
            }
        }
        g.writeEndArray();
    }

    private static void writeCbor(JsonNode n, CBORGenerator g) throws IOException {
        switch (n.getNodeType()) {
            case OBJECT -> {
                g.writeStartObject();
                for (Iterator<Map.Entry<String, JsonNode>> it = n.fields(); it.hasNext(); ) {
                    Map.Entry<String, JsonNode> e = it.next();
                    g.writeFieldName(e.getKey());
                    writeCbor(e.getValue(), g);
                }
                g.writeEndObject();
            }
            case ARRAY -> {
                g.writeStartArray();
                for (JsonNode e : n) {
                    writeCbor(e, g);
                }
                g.writeEndArray();
            }
            case NUMBER -> {
                if (n.isFloat()) {
                    g.writeNumber(n.floatValue());
                } else if (n.isDouble()) {
                    g.writeNumber(n.doubleValue());
                } else if (n.isBigInteger()) {
                    g.writeNumber(n.bigIntegerValue());
                } else if (n.isBigDecimal()) {
                    g.writeNumber(n.decimalValue());
                } else {
                    g.writeNumber(n.longValue());
                }
            }
            case BINARY -> g.writeBinary(n.binaryValue());
            case POJO -> {
                NumberSequence s = sequence(n);
                g.writeTag(tag(s.element()));
                g.writeBinary(littleEndian(s));
            }
            case STRING -> g.writeString(n.textValue());
            case BOOLEAN -> g.writeBoolean(n.booleanValue());
            default -> g.writeNull();
        }
    }

    /**
     * @param element a numeric element type
     * @return its RFC 8746 little-endian typed-array tag
     */
    public static int tag(Primitive element) {
        return switch (element) {
            case UINT16 -> TAG_UINT16_LE;
            case UINT32 -> TAG_UINT32_LE;
            case UINT64 -> TAG_UINT64_LE;
            case INT8 -> TAG_INT8;
            case INT16 -> TAG_INT16_LE;
            case INT32 -> TAG_INT32_LE;
            case INT64 -> TAG_INT64_LE;
            case FLOAT32 -> TAG_FLOAT32_LE;
            case FLOAT64 -> TAG_FLOAT64_LE;
            default -> throw new IllegalArgumentException("a " + element.rosName() + " sequence has no typed-array tag");
        };
    }

    private static byte[] littleEndian(NumberSequence s) {
        int width = s.element().width();
        ByteBuffer b = ByteBuffer.allocate(s.size() * width).order(ByteOrder.LITTLE_ENDIAN);
        if (s.floats() != null) {
            for (double d : s.floats()) {
                if (width == 4) {
                    b.putFloat((float) d);
                } else {
                    b.putDouble(d);
                }
            }
        } else {
            for (long l : s.integers()) {
                switch (width) {
                    case 1 -> b.put((byte) l);
                    case 2 -> b.putShort((short) l);
                    case 4 -> b.putInt((int) l);
                    default -> b.putLong(l);
                }
            }
        }
        return b.array();
    }

    private static NumberSequence sequence(JsonNode n) {
        if (n instanceof POJONode p && p.getPojo() instanceof NumberSequence s) {
            return s;
        }
        throw new IllegalArgumentException("a message tree holds a " + n + ", which is not a number sequence");
    }
}
