package io.robomw.console.rosbridge.msg;

import com.fasterxml.jackson.databind.JsonNode;
import com.fasterxml.jackson.databind.node.ArrayNode;
import com.fasterxml.jackson.databind.node.BinaryNode;
import com.fasterxml.jackson.databind.node.JsonNodeFactory;
import com.fasterxml.jackson.databind.node.ObjectNode;

import java.math.BigInteger;
import java.nio.ByteBuffer;
import java.nio.ByteOrder;
import java.time.Clock;
import java.time.Instant;
import java.util.ArrayList;
import java.util.Base64;
import java.util.Iterator;
import java.util.List;

/**
 * Reads a message a client sent (a {@code publish}'s {@code msg}, a {@code call_service}'s
 * {@code args}) against its type, into the bridge's message tree, the way rosbridge_suite's
 * {@code populate_instance} does:
 * <ul>
 *   <li>a field left out gets its default (zero, empty, the file's default such as a
 *   quaternion's {@code w = 1}); a {@code std_msgs/Header}'s stamp defaults to now;</li>
 *   <li>a field the type does not have, or a value of the wrong kind, is an error naming the
 *   field ({@link MessageException});</li>
 *   <li>an integer where a float is expected is taken; a float where an integer is expected is
 *   not; integers must fit their type;</li>
 *   <li>a time is {@code {sec, nanosec}} (ROS 2) or {@code {secs, nsecs}} (ROS 1), or the string
 *   {@code "now"};</li>
 *   <li>{@code uint8[]} and {@code char[]} are a base64 string (or a list of numbers, or CBOR
 *   bytes);</li>
 *   <li>beyond rosbridge_suite: {@code null} for a float is NaN, so a message the bridge sent
 *   (where NaN and infinities are {@code null}) can be sent back as it came.</li>
 * </ul>
 *
 * <p>The tree it makes is what the bridge's own messages are: {@link ObjectNode}s, numbers,
 * strings, {@link BinaryNode}s for bytes and {@link NumberSequence}s (in POJO nodes) for numeric
 * sequences, written out by {@link Wire}. Thread-safe.
 */
public final class MessageReader {

    private static final JsonNodeFactory NODES = JsonNodeFactory.instance;
    private static final TypeName HEADER = new TypeName("std_msgs", TypeName.Kind.MSG, "Header");
    private static final TypeName TIME = new TypeName("builtin_interfaces", TypeName.Kind.MSG, "Time");
    private static final TypeName DURATION = new TypeName("builtin_interfaces", TypeName.Kind.MSG, "Duration");
    private static final long NANOS_PER_SECOND = 1_000_000_000L;

    private final Interfaces interfaces;
    private final Clock clock;

    /**
     * @param interfaces the types fields refer to
     * @param clock      what "now" is (a header's default stamp, {@code "now"})
     */
    public MessageReader(Interfaces interfaces, Clock clock) {
        this.interfaces = interfaces;
        this.clock = clock;
    }

    /**
     * @param in   what the client sent; {@code null} or a missing node for an empty message
     * @param type the message's type
     * @return the message, every field present
     * @throws MessageException if it does not fit the type
     */
    public ObjectNode read(JsonNode in, MessageType type) {
        if (in == null || in.isMissingNode() || in.isNull()) {
            in = NODES.objectNode();
        }
        return object(in, type, type, new ArrayList<>());
    }

    /**
     * @param type a message type
     * @return the message with every field at its default
     */
    public ObjectNode defaults(MessageType type) {
        return read(null, type);
    }

    /**
     * @param instant a time
     * @return it as ROS 2 writes a time: {@code {sec, nanosec}}
     */
    public static ObjectNode time(Instant instant) {
        ObjectNode t = NODES.objectNode();
        t.put("sec", instant.getEpochSecond());
        t.put("nanosec", (long) instant.getNano());
        return t;
    }

    private ObjectNode object(JsonNode in, MessageType type, MessageType root, List<String> path) {
        if (!in.isObject()) {
            throw mismatch(root, path, type.name().shortName(), in);
        }
        for (Iterator<String> names = in.fieldNames(); names.hasNext(); ) {
            String n = names.next();
            if (type.field(n).isEmpty()) {
                List<String> p = new ArrayList<>(path);
                p.add(n);
                throw new MessageException("Message type " + root.name().shortName() + " does not have a field " + String.join(".", p));
            }
        }
        ObjectNode out = NODES.objectNode();
        for (Field f : type.fields()) {
            path.add(f.name());
            JsonNode v = in.get(f.name());
            if (v == null && type.name().equals(HEADER) && f.name().equals("stamp")) {
                out.set("stamp", time(clock.instant()));
            } else {
                out.set(f.name(), field(v, f, root, path));
            }
            path.remove(path.size() - 1);
        }
        return out;
    }

    private JsonNode field(JsonNode v, Field f, MessageType root, List<String> path) {
        if (f.bytes()) {
            return bytes(v, f, root, path);
        }
        if (!f.array()) {
            return single(v, f, root, path);
        }
        if (v == null) {
            if (f.shape() == Field.Shape.SEQUENCE) {
                return f.numberSequence() ? NODES.pojoNode(emptySequence(f.primitive())) : NODES.arrayNode();
            }
            ArrayNode zeros = NODES.arrayNode();
            for (int i = 0; i < f.length(); i++) {
                zeros.add(single(null, f, root, path));
            }
            return zeros;
        }
        if (f.numberSequence() && v instanceof com.fasterxml.jackson.databind.node.POJONode pojo && pojo.getPojo() instanceof NumberSequence n
                && n.element() == f.primitive()) {
            checkLength(f, n.size(), root, path);
            return v; // the bridge's own tree
        }
        if (f.numberSequence() && v.isBinary()) {
            return NODES.pojoNode(typedArray(f.primitive(), binary(v)));
        }
        if (!v.isArray()) {
            throw mismatch(root, path, f.elementTypeName() + "[]", v);
        }
        checkLength(f, v.size(), root, path);
        if (f.numberSequence()) {
            return NODES.pojoNode(sequence(v, f, root, path));
        }
        ArrayNode out = NODES.arrayNode(v.size());
        for (int i = 0; i < v.size(); i++) {
            path.add(String.valueOf(i));
            out.add(single(v.get(i), f, root, path));
            path.remove(path.size() - 1);
        }
        return out;
    }

    private JsonNode single(JsonNode v, Field f, MessageType root, List<String> path) {
        if (f.message() != null) {
            MessageType nested = interfaces.message(f.message()).orElseThrow();
            if ((f.message().equals(TIME) || f.message().equals(DURATION)) && v != null) {
                return time(v, f.message(), root, path);
            }
            return object(v == null ? NODES.objectNode() : v, nested, root, path);
        }
        Primitive p = f.primitive();
        if (v == null) {
            JsonNode d = f.array() ? null : f.defaultValue();
            return d != null ? number(d, p, root, path) : zero(p);
        }
        return switch (p) {
            case BOOL -> {
                if (!v.isBoolean()) {
                    throw mismatch(root, path, p.fileName(), v);
                }
                yield v;
            }
            case STRING -> {
                if (!v.isTextual()) {
                    throw mismatch(root, path, p.fileName(), v);
                }
                yield v;
            }
            default -> {
                if (v.isNull() && p.floating()) {
                    yield p == Primitive.FLOAT32 ? NODES.numberNode(Float.NaN) : NODES.numberNode(Double.NaN);
                }
                if (!v.isNumber()) {
                    throw mismatch(root, path, p.fileName(), v);
                }
                yield number(v, p, root, path);
            }
        };
    }

    private JsonNode number(JsonNode v, Primitive p, MessageType root, List<String> path) {
        if (p.floating()) {
            return p == Primitive.FLOAT32 ? NODES.numberNode((float) v.doubleValue()) : NODES.numberNode(v.doubleValue());
        }
        if (!v.isIntegralNumber()) {
            throw mismatch(root, path, p.fileName(), v);
        }
        BigInteger b = v.bigIntegerValue();
        if (!p.holds(b)) {
            throw new MessageException(root.name().shortName() + " message requires a " + p.fileName() + " for field " + String.join(".", path)
                    + ", but " + b + " is out of its range");
        }
        return b.bitLength() < 64 ? NODES.numberNode(b.longValue()) : NODES.numberNode(b);
    }

    private static JsonNode zero(Primitive p) {
        return switch (p) {
            case BOOL -> NODES.booleanNode(false);
            case STRING -> NODES.textNode("");
            case FLOAT32 -> NODES.numberNode(0f);
            case FLOAT64 -> NODES.numberNode(0d);
            default -> NODES.numberNode(0L);
        };
    }

    private ObjectNode time(JsonNode v, TypeName type, MessageType root, List<String> path) {
        if (v.isTextual() && v.asText().equals("now") && type.equals(TIME)) {
            return time(clock.instant());
        }
        if (!v.isObject()) {
            throw mismatch(root, path, type.shortName(), v);
        }
        JsonNode sec = v.has("sec") ? v.get("sec") : v.get("secs");
        JsonNode nanosec = v.has("nanosec") ? v.get("nanosec") : v.get("nsecs");
        ObjectNode t = NODES.objectNode();
        path.add("sec");
        t.set("sec", sec == null ? NODES.numberNode(0L) : checkedInteger(sec, Primitive.INT32, root, path));
        path.set(path.size() - 1, "nanosec");
        JsonNode ns = nanosec == null ? NODES.numberNode(0L) : checkedInteger(nanosec, Primitive.UINT32, root, path);
        if (ns.longValue() >= NANOS_PER_SECOND) {
            throw new MessageException(root.name().shortName() + " message requires nanosec below 1000000000 for field " + String.join(".", path)
                    + ", got " + ns.longValue());
        }
        t.set("nanosec", ns);
        path.remove(path.size() - 1);
        return t;
    }

    private JsonNode checkedInteger(JsonNode v, Primitive p, MessageType root, List<String> path) {
        if (!v.isNumber()) {
            throw mismatch(root, path, p.fileName(), v);
        }
        return number(v, p, root, path);
    }

    private JsonNode bytes(JsonNode v, Field f, MessageType root, List<String> path) {
        byte[] b;
        if (v == null) {
            b = new byte[f.shape() == Field.Shape.FIXED ? f.length() : 0];
        } else if (v.isBinary()) {
            b = binary(v);
        } else if (v.isTextual()) {
            try {
                b = Base64.getDecoder().decode(v.asText());
            } catch (IllegalArgumentException e) {
                throw new MessageException(root.name().shortName() + " message requires base64 text for " + f.primitive().fileName() + "[] field "
                        + String.join(".", path) + ": " + e.getMessage());
            }
        } else if (v.isArray()) {
            b = new byte[v.size()];
            for (int i = 0; i < v.size(); i++) {
                path.add(String.valueOf(i));
                b[i] = (byte) checkedInteger(v.get(i), Primitive.UINT8, root, path).longValue();
                path.remove(path.size() - 1);
            }
        } else {
            throw mismatch(root, path, f.primitive().fileName() + "[] (base64 text)", v);
        }
        checkLength(f, b.length, root, path);
        return NODES.binaryNode(b);
    }

    private NumberSequence sequence(JsonNode v, Field f, MessageType root, List<String> path) {
        Primitive p = f.primitive();
        if (p.floating()) {
            double[] d = new double[v.size()];
            for (int i = 0; i < d.length; i++) {
                JsonNode e = v.get(i);
                if (e.isNull()) {
                    d[i] = Double.NaN;
                } else if (e.isNumber()) {
                    d[i] = p == Primitive.FLOAT32 ? (float) e.doubleValue() : e.doubleValue();
                } else {
                    path.add(String.valueOf(i));
                    throw mismatch(root, path, p.fileName(), e);
                }
            }
            return NumberSequence.ofFloats(p, d);
        }
        long[] l = new long[v.size()];
        for (int i = 0; i < l.length; i++) {
            path.add(String.valueOf(i));
            l[i] = checkedInteger(v.get(i), p, root, path).bigIntegerValue().longValue();
            path.remove(path.size() - 1);
        }
        return NumberSequence.ofIntegers(p, l);
    }

    private static NumberSequence emptySequence(Primitive p) {
        return p.floating() ? NumberSequence.ofFloats(p) : NumberSequence.ofIntegers(p);
    }

    /** A typed array sent as CBOR bytes: little-endian elements of the field's width. */
    private static NumberSequence typedArray(Primitive p, byte[] b) {
        int width = p.width();
        if (b.length % width != 0) {
            throw new MessageException("a " + p.rosName() + " typed array must be a multiple of " + width + " bytes, got " + b.length);
        }
        ByteBuffer buf = ByteBuffer.wrap(b).order(ByteOrder.LITTLE_ENDIAN);
        int n = b.length / width;
        if (p.floating()) {
            double[] d = new double[n];
            for (int i = 0; i < n; i++) {
                d[i] = p == Primitive.FLOAT32 ? buf.getFloat() : buf.getDouble();
            }
            return NumberSequence.ofFloats(p, d);
        }
        long[] l = new long[n];
        for (int i = 0; i < n; i++) {
            l[i] = switch (p) {
                case INT8 -> buf.get();
                case INT16 -> buf.getShort();
                case UINT16 -> buf.getShort() & 0xFFFF;
                case INT32 -> buf.getInt();
                case UINT32 -> buf.getInt() & 0xFFFF_FFFFL;
                default -> buf.getLong();
            };
        }
        return NumberSequence.ofIntegers(p, l);
    }

    private static byte[] binary(JsonNode v) {
        try {
            return v.binaryValue();
        } catch (java.io.IOException e) {
            throw new MessageException("unreadable bytes: " + e.getMessage());
        }
    }

    private static void checkLength(Field f, int size, MessageType root, List<String> path) {
        if (f.shape() == Field.Shape.FIXED && size != f.length()) {
            throw new MessageException(root.name().shortName() + " message requires exactly " + f.length() + " values for field " + String.join(".", path)
                    + ", got " + size);
        }
        if (f.shape() == Field.Shape.SEQUENCE && f.length() > 0 && size > f.length()) {
            throw new MessageException(root.name().shortName() + " message allows at most " + f.length() + " values for field " + String.join(".", path)
                    + ", got " + size);
        }
    }

    private static MessageException mismatch(MessageType root, List<String> path, String expected, JsonNode found) {
        if (path.isEmpty()) {
            return new MessageException("Expected a JSON object for type " + root.name().shortName() + " but received " + kind(found));
        }
        return new MessageException(root.name().shortName() + " message requires a " + expected + " for field " + String.join(".", path) + ", but got "
                + kind(found));
    }

    private static String kind(JsonNode n) {
        return switch (n.getNodeType()) {
            case ARRAY -> "a list";
            case OBJECT, POJO -> "an object";
            case STRING -> "a string";
            case NUMBER -> n.isIntegralNumber() ? "an integer (" + n.asText() + ")" : "a float (" + n.asText() + ")";
            case BOOLEAN -> "a boolean";
            case NULL -> "null";
            case BINARY -> "bytes";
            case MISSING -> "nothing";
        };
    }
}
