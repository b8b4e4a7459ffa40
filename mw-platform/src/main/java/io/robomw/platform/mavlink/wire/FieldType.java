package io.robomw.platform.mavlink.wire;

import java.util.Arrays;
import java.util.Map;
import java.util.function.Function;
import java.util.stream.Collectors;

/**
 * The types a MAVLink message field may have, as the message definitions (XML) name them, with
 * their size on the wire. Every multi-byte type is little-endian. A field's CRC_EXTRA contribution
 * uses the name as written here ({@code uint8_t}, {@code float}, {@code char}).
 */
public enum FieldType {
    /** Unsigned 8-bit integer. */
    UINT8_T("uint8_t", 1, true),
    /** Signed 8-bit integer. */
    INT8_T("int8_t", 1, true),
    /** Unsigned 16-bit integer. */
    UINT16_T("uint16_t", 2, true),
    /** Signed 16-bit integer. */
    INT16_T("int16_t", 2, true),
    /** Unsigned 32-bit integer. */
    UINT32_T("uint32_t", 4, true),
    /** Signed 32-bit integer. */
    INT32_T("int32_t", 4, true),
    /** Unsigned 64-bit integer (read into a {@code long}'s bits). */
    UINT64_T("uint64_t", 8, true),
    /** Signed 64-bit integer. */
    INT64_T("int64_t", 8, true),
    /** IEEE-754 single precision. */
    FLOAT("float", 4, false),
    /** IEEE-754 double precision. */
    DOUBLE("double", 8, false),
    /** A character; {@code char[N]} is text, NUL-padded, not necessarily NUL-terminated. */
    CHAR("char", 1, true);

    private static final Map<String, FieldType> BY_NAME = Arrays.stream(values())
            .collect(Collectors.toUnmodifiableMap(FieldType::typeName, Function.identity()));

    private final String typeName;
    private final int size;
    private final boolean integer;

    FieldType(String typeName, int size, boolean integer) {
        this.typeName = typeName;
        this.size = size;
        this.integer = integer;
    }

    /** @return the name in message definitions, {@code uint16_t} */
    public String typeName() {
        return typeName;
    }

    /** @return bytes of one value on the wire */
    public int size() {
        return size;
    }

    /** @return whether values are integers (or characters) rather than floating point */
    public boolean integer() {
        return integer;
    }

    /**
     * @param name a type name as in message definitions ({@code uint8_t})
     * @return the type
     * @throws IllegalArgumentException naming the type if there is none of that name
     */
    public static FieldType named(String name) {
        FieldType t = BY_NAME.get(name);
        if (t == null) {
            throw new IllegalArgumentException("no MAVLink field type '" + name + "'; the types are " + BY_NAME.keySet());
        }
        return t;
    }
}
