package io.robomw.config.yaml;

import java.math.BigDecimal;
import java.util.Objects;
import java.util.function.DoublePredicate;

/**
 * The values a number in a robot or world file may take: one value that makes both the check and
 * the words of the message, so the two cannot drift apart (as dyn4j's
 * {@code ValueOutOfRangeException} builds every range error from the name, the value, the rule
 * and the bound). {@link MappingReader#number(String, double, Range)} reports a value outside it
 * as {@code 'cycle_hz' must be between 1 and 1000, got 5000}: the key, the rule, the value.
 *
 * @param words how the rule reads, which also decides which ends are included
 * @param min   the lower end
 * @param max   the upper end
 * @param unit  the values' unit in words ({@code "metres"}), or empty
 * @param note  what a reader should also know ({@code "0 turns it off"}), or empty
 */
public record Range(Words words, double min, double max, String unit, String note) implements DoublePredicate {

    /** How a range reads, and which of its ends it includes. */
    public enum Words {
        /** {@code [min, max]}: "between 1 and 1000". */
        BETWEEN,
        /**
         * {@code [min, max]} with {@code min > 0}: "&gt; 0 metres (0.001 to 10)", a value that must
         * be positive, within the limits a real robot could have.
         */
        POSITIVE,
        /** {@code (min, max]}: "&gt; 0 metres per second (at most 100)". */
        ABOVE,
        /** {@code [min, max)}: "&gt;= 0 and &lt; 1", a fraction short of the whole. */
        FROM_BELOW,
        /** Any finite number: "a finite number". */
        FINITE
    }

    /** Any finite number. */
    public static final Range ANY = new Range(Words.FINITE, Double.NEGATIVE_INFINITY, Double.POSITIVE_INFINITY, "", "");

    /** Checks the ends. */
    public Range {
        Objects.requireNonNull(words, "words");
        Objects.requireNonNull(unit, "unit");
        Objects.requireNonNull(note, "note");
        if (Double.isNaN(min) || Double.isNaN(max) || !(min < max)) {
            throw new IllegalArgumentException("a range needs min < max, got " + min + " and " + max);
        }
        if (words == Words.POSITIVE && !(min > 0)) {
            throw new IllegalArgumentException("a POSITIVE range needs min > 0, got " + min);
        }
    }

    /**
     * @param min  the least value
     * @param max  the greatest value
     * @param unit the unit in words, or empty
     * @return {@code [min, max]}, "between min and max unit"
     */
    public static Range between(double min, double max, String unit) {
        return new Range(Words.BETWEEN, min, max, unit, "");
    }

    /**
     * @param min  the least value, &gt; 0
     * @param max  the greatest value
     * @param unit the unit in words, or empty
     * @return {@code [min, max]}, "&gt; 0 unit (min to max)"
     */
    public static Range positive(double min, double max, String unit) {
        return new Range(Words.POSITIVE, min, max, unit, "");
    }

    /**
     * @param min  the bound every value is above
     * @param max  the greatest value
     * @param unit the unit in words, or empty
     * @return {@code (min, max]}, "&gt; min unit (at most max)"
     */
    public static Range above(double min, double max, String unit) {
        return new Range(Words.ABOVE, min, max, unit, "");
    }

    /**
     * @param min  the least value
     * @param max  the bound every value is below
     * @param unit the unit in words, or empty
     * @return {@code [min, max)}, "&gt;= min and &lt; max unit"
     */
    public static Range fromBelow(double min, double max, String unit) {
        return new Range(Words.FROM_BELOW, min, max, unit, "");
    }

    /**
     * @param what what a reader should also know, in words
     * @return the same range, whose rule ends with the note in brackets (or after a comma, for an
     *         alternative: {@code "or 'argument'"})
     */
    public Range noting(String what) {
        return new Range(words, min, max, unit, what);
    }

    @Override
    public boolean test(double value) {
        return switch (words) {
            case BETWEEN, POSITIVE -> value >= min && value <= max;
            case ABOVE -> value > min && value <= max;
            case FROM_BELOW -> value >= min && value < max;
            case FINITE -> Double.isFinite(value);
        };
    }

    /** @return the rule in words, as a message says what a value must be: {@code between 1 and 1000} */
    public String rule() {
        String u = unit.isEmpty() ? "" : " " + unit;
        String text = switch (words) {
            case BETWEEN -> "between " + number(min) + " and " + number(max) + u;
            case POSITIVE -> "> 0" + u + " (" + number(min) + " to " + number(max) + ")";
            case ABOVE -> "> " + number(min) + u + (max == Double.POSITIVE_INFINITY ? "" : " (at most " + number(max) + ")");
            case FROM_BELOW -> ">= " + number(min) + " and < " + number(max) + u;
            case FINITE -> "a finite number" + u;
        };
        if (note.isEmpty()) {
            return text;
        }
        return note.startsWith("or ") ? text + ", " + note : text + " (" + note + ")";
    }

    /** @return the rule */
    @Override
    public String toString() {
        return rule();
    }

    /** A bound as a file would give it: {@code 1000}, {@code 0.001}, {@code 1000000}. */
    private static String number(double v) {
        if (Double.isInfinite(v)) {
            return v > 0 ? "infinity" : "-infinity";
        }
        return BigDecimal.valueOf(v).stripTrailingZeros().toPlainString();
    }
}
