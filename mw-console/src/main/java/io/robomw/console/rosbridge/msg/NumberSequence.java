package io.robomw.console.rosbridge.msg;

import java.util.Arrays;
import java.util.Objects;

/**
 * A sequence of numbers in a message ({@code float32[] ranges}, {@code float64[] position}), held
 * unboxed: JSON writes it as a list (non-finite values as {@code null}); CBOR writes it as one
 * RFC 8746 typed array, little-endian, as rosbridge_suite does for {@code sequence<...>} fields.
 * Message trees carry it in a {@link com.fasterxml.jackson.databind.node.POJONode}.
 *
 * <p>Exactly one of {@code floats} and {@code integers} is given, by the element type.
 *
 * @param element  the element type, numeric and not a byte
 * @param floats   the values of a float32 or float64 sequence
 * @param integers the values of an integer sequence (a uint64 above 2^63 - 1 as its bits)
 */
public record NumberSequence(Primitive element, double[] floats, long[] integers) {

    /** Checks that the values fit the element type. */
    public NumberSequence {
        Objects.requireNonNull(element, "element");
        if (element.floating() != (floats != null) || element.integer() != (integers != null)) {
            throw new IllegalArgumentException("a " + element.rosName() + " sequence holds " + (element.floating() ? "floats" : "integers"));
        }
    }

    /**
     * @param element float32 or float64
     * @param values  the values (not copied)
     * @return the sequence
     */
    public static NumberSequence ofFloats(Primitive element, double... values) {
        return new NumberSequence(element, values, null);
    }

    /**
     * @param element an integer type
     * @param values  the values (not copied)
     * @return the sequence
     */
    public static NumberSequence ofIntegers(Primitive element, long... values) {
        return new NumberSequence(element, null, values);
    }

    /** @return how many values */
    public int size() {
        return floats != null ? floats.length : integers.length;
    }

    @Override
    public boolean equals(Object o) {
        return o instanceof NumberSequence n && n.element == element && Arrays.equals(n.floats, floats) && Arrays.equals(n.integers, integers);
    }

    @Override
    public int hashCode() {
        return Objects.hash(element, Arrays.hashCode(floats), Arrays.hashCode(integers));
    }

    @Override
    public String toString() {
        return element.rosName() + (floats != null ? Arrays.toString(floats) : Arrays.toString(integers));
    }
}
