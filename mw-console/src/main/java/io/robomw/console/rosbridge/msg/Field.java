package io.robomw.console.rosbridge.msg;

import com.fasterxml.jackson.databind.JsonNode;

import java.util.Objects;

/**
 * One field of a message type.
 *
 * @param name         the field's name
 * @param primitive    its built-in type, or {@code null} if it holds a message
 * @param message      the message type it holds, or {@code null} if it is built-in
 * @param shape        single value, fixed-size array or sequence
 * @param length       the fixed array's length, a bounded sequence's bound, 0 for an unbounded sequence or a single value
 * @param defaultValue the default an interface file gives ({@code float64 w 1}), or {@code null} for the type's zero
 */
public record Field(String name, Primitive primitive, TypeName message, Shape shape, int length, JsonNode defaultValue) {

    /** How many values a field holds. */
    public enum Shape {
        /** One value: {@code float64 x}. */
        SINGLE,
        /** Exactly {@code length} values: {@code float64[36] covariance}. */
        FIXED,
        /** Any number ({@code float32[] ranges}), or at most {@code length} ({@code float32[<=10]}). */
        SEQUENCE
    }

    /** Checks that exactly one of primitive and message is given. */
    public Field {
        Objects.requireNonNull(name, "name");
        Objects.requireNonNull(shape, "shape");
        if ((primitive == null) == (message == null)) {
            throw new IllegalArgumentException("field '" + name + "' must have either a built-in or a message type");
        }
    }

    /** @return whether it holds several values */
    public boolean array() {
        return shape != Shape.SINGLE;
    }

    /**
     * @return whether it is {@code uint8[]} or {@code char[]}, which JSON carries as one base64 string
     *         (a {@code byte[]}, ROS 2's octets, stays a list of numbers, as in rosbridge_suite)
     */
    public boolean bytes() {
        return array() && (primitive == Primitive.UINT8 || primitive == Primitive.CHAR);
    }

    /** @return whether it is a sequence of numbers other than bytes, which CBOR carries as a typed array (RFC 8746) */
    public boolean numberSequence() {
        return shape == Shape.SEQUENCE && primitive != null && primitive.numeric() && !bytes();
    }

    /** @return the element type as rosapi names it: {@code double}, {@code geometry_msgs/Pose} */
    public String elementTypeName() {
        return primitive != null ? primitive.rosName() : message.shortName();
    }

    /** @return rosapi's {@code fieldarraylen}: -1 for a single value, the length of a fixed array, 0 for a sequence */
    public int arrayLength() {
        return switch (shape) {
            case SINGLE -> -1;
            case FIXED -> length;
            case SEQUENCE -> 0;
        };
    }
}
