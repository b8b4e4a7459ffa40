package io.robomw.console.rosbridge.msg;

import java.math.BigInteger;
import java.util.Map;
import java.util.function.Function;
import java.util.stream.Collectors;
import java.util.stream.Stream;

/**
 * The built-in field types of ROS 2 interfaces, as an interface file writes them and as ROS 2's
 * type introspection ({@code get_fields_and_field_types}, which rosapi reports) names them.
 *
 * <table>
 *   <caption>spellings</caption>
 *   <tr><th>in a .msg file</th><th>ROS 2 name (rosapi)</th><th>JSON</th></tr>
 *   <tr><td>bool</td><td>boolean</td><td>true/false</td></tr>
 *   <tr><td>byte</td><td>octet</td><td>number 0..255</td></tr>
 *   <tr><td>char, uint8</td><td>uint8</td><td>number 0..255</td></tr>
 *   <tr><td>int8 ... uint64</td><td>the same</td><td>number</td></tr>
 *   <tr><td>float32</td><td>float</td><td>number; NaN and infinities as null</td></tr>
 *   <tr><td>float64</td><td>double</td><td>number; NaN and infinities as null</td></tr>
 *   <tr><td>string</td><td>string</td><td>string</td></tr>
 * </table>
 */
public enum Primitive {
    /** true or false. */
    BOOL("bool", "boolean", 0, 0),
    /** An opaque byte (ROS 2 {@code octet}). */
    BYTE("byte", "octet", 0, 255),
    /** An 8-bit character, which ROS 2 maps to uint8. */
    CHAR("char", "uint8", 0, 255),
    /** Signed 8 bits. */
    INT8("int8", "int8", -128, 127),
    /** Unsigned 8 bits. */
    UINT8("uint8", "uint8", 0, 255),
    /** Signed 16 bits. */
    INT16("int16", "int16", Short.MIN_VALUE, Short.MAX_VALUE),
    /** Unsigned 16 bits. */
    UINT16("uint16", "uint16", 0, 65535),
    /** Signed 32 bits. */
    INT32("int32", "int32", Integer.MIN_VALUE, Integer.MAX_VALUE),
    /** Unsigned 32 bits. */
    UINT32("uint32", "uint32", 0, 4294967295L),
    /** Signed 64 bits. */
    INT64("int64", "int64", Long.MIN_VALUE, Long.MAX_VALUE),
    /** Unsigned 64 bits (up to 2^64 - 1; held as a long's bits above 2^63 - 1 would not fit, so as a BigInteger). */
    UINT64("uint64", "uint64", 0, Long.MAX_VALUE),
    /** IEEE 754 single precision. */
    FLOAT32("float32", "float", 0, 0),
    /** IEEE 754 double precision. */
    FLOAT64("float64", "double", 0, 0),
    /** UTF-8 text. */
    STRING("string", "string", 0, 0);

    /** The largest uint64. */
    public static final BigInteger UINT64_MAX = BigInteger.ONE.shiftLeft(64).subtract(BigInteger.ONE);

    private static final Map<String, Primitive> BY_FILE_NAME = Stream.of(values())
            .collect(Collectors.toUnmodifiableMap(Primitive::fileName, Function.identity()));

    private final String fileName;
    private final String rosName;
    private final long min;
    private final long max;

    Primitive(String fileName, String rosName, long min, long max) {
        this.fileName = fileName;
        this.rosName = rosName;
        this.min = min;
        this.max = max;
    }

    /** @return how an interface file writes it */
    public String fileName() {
        return fileName;
    }

    /** @return how ROS 2's introspection and rosapi name it */
    public String rosName() {
        return rosName;
    }

    /**
     * @param fileName a type as an interface file writes it
     * @return the primitive of that name, or {@code null} if it is a message type
     */
    public static Primitive ofFileName(String fileName) {
        return BY_FILE_NAME.get(fileName);
    }

    /** @return whether it is a whole number */
    public boolean integer() {
        return this != BOOL && this != FLOAT32 && this != FLOAT64 && this != STRING;
    }

    /** @return whether it is a floating-point number */
    public boolean floating() {
        return this == FLOAT32 || this == FLOAT64;
    }

    /** @return whether it is a number of either kind */
    public boolean numeric() {
        return integer() || floating();
    }

    /**
     * @param value a whole number
     * @return whether this integer type holds it
     */
    public boolean holds(BigInteger value) {
        if (this == UINT64) {
            return value.signum() >= 0 && value.compareTo(UINT64_MAX) <= 0;
        }
        return value.bitLength() < 64 && value.longValue() >= min && value.longValue() <= max;
    }

    /** @return the bytes of one element in a typed array (CBOR tags of RFC 8746) */
    public int width() {
        return switch (this) {
            case BOOL, BYTE, CHAR, INT8, UINT8 -> 1;
            case INT16, UINT16 -> 2;
            case INT32, UINT32, FLOAT32 -> 4;
            case INT64, UINT64, FLOAT64 -> 8;
            case STRING -> throw new IllegalStateException("a string has no fixed width");
        };
    }
}
