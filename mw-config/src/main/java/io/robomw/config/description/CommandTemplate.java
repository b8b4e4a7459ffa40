package io.robomw.config.description;

import java.math.BigDecimal;
import java.math.RoundingMode;
import java.util.ArrayList;
import java.util.Collections;
import java.util.LinkedHashSet;
import java.util.List;
import java.util.Locale;
import java.util.Map;
import java.util.Objects;
import java.util.Set;

/**
 * A command in a platform's own language with placeholders for its values, as a robot file gives
 * it: {@code robot.walk(${distance}, ${speed})}, {@code headPan.val = ${angle:deg} time:${duration:ms}}.
 * The Configuration Layer renders it with the values of one motion or action; it never looks
 * inside the rest of the text, so another firmware's commands need only another template.
 *
 * <h2>Placeholders</h2>
 * {@code ${name}} is the value in SI units (metres, radians, seconds, metres or radians per
 * second); {@code ${name:unit}} converts it first:
 * <table>
 *   <caption>units of placeholders</caption>
 *   <tr><th>unit</th><th>value</th><th>for</th></tr>
 *   <tr><td>{@code deg}</td><td>degrees</td><td>radians: angles, angular speeds (degrees per second)</td></tr>
 *   <tr><td>{@code ms}</td><td>milliseconds, rounded to a whole number</td><td>seconds</td></tr>
 *   <tr><td>{@code mm}</td><td>millimetres</td><td>metres, metres per second (mm/s)</td></tr>
 *   <tr><td>{@code cm}</td><td>centimetres</td><td>metres, metres per second (cm/s)</td></tr>
 * </table>
 * Numbers are written in plain decimal with a point and at most six decimals ({@code 0.5},
 * {@code -90}, {@code 1500}), never with an exponent. A {@code $} not followed by {@code {} is
 * text; braces without {@code $} are text too (URBI blocks use them).
 *
 * <p>Immutable; equal when the text is equal.
 */
public final class CommandTemplate {

    /** The units a placeholder may give. */
    public static final Set<String> UNITS = Set.of("deg", "ms", "mm", "cm");

    private final String text;
    private final List<Part> parts;
    private final Set<String> placeholders;

    private CommandTemplate(String text, List<Part> parts) {
        this.text = text;
        this.parts = List.copyOf(parts);
        Set<String> names = new LinkedHashSet<>();
        for (Part p : parts) {
            if (p.name() != null) {
                names.add(p.name());
            }
        }
        this.placeholders = Collections.unmodifiableSet(names);
    }

    /** One piece of a template: literal text, or a placeholder with its unit ({@code null} for SI). */
    private record Part(String literal, String name, String unit) {
    }

    /**
     * Parses a template and checks its placeholders.
     *
     * @param text    the template
     * @param allowed the placeholders this template may use (the values it is rendered with)
     * @return the template
     * @throws IllegalArgumentException naming the placeholder and the rule, if a placeholder is
     *                                  unclosed, unknown, has an unknown unit, or the text is blank
     */
    public static CommandTemplate parse(String text, Set<String> allowed) {
        Objects.requireNonNull(text, "text");
        if (text.isBlank()) {
            throw new IllegalArgumentException("a command template must not be empty");
        }
        List<Part> parts = new ArrayList<>();
        StringBuilder literal = new StringBuilder();
        int i = 0;
        while (i < text.length()) {
            char c = text.charAt(i);
            if (c == '$' && i + 1 < text.length() && text.charAt(i + 1) == '{') {
                int close = text.indexOf('}', i + 2);
                if (close < 0) {
                    throw new IllegalArgumentException("placeholder at character " + (i + 1) + " of \"" + text + "\" is not closed with '}'");
                }
                String inside = text.substring(i + 2, close).trim();
                int colon = inside.indexOf(':');
                String name = colon < 0 ? inside : inside.substring(0, colon).trim();
                String unit = colon < 0 ? null : inside.substring(colon + 1).trim();
                if (!allowed.contains(name)) {
                    throw new IllegalArgumentException("placeholder ${" + inside + "} names '" + name + "', which this command does not have; it has "
                            + (allowed.isEmpty() ? "no values" : String.join(", ", allowed.stream().sorted().toList())));
                }
                if (unit != null && !UNITS.contains(unit)) {
                    throw new IllegalArgumentException("placeholder ${" + inside + "} has unit '" + unit + "'; units are "
                            + String.join(", ", UNITS.stream().sorted().toList()) + " (or none, for SI)");
                }
                if (!literal.isEmpty()) {
                    parts.add(new Part(literal.toString(), null, null));
                    literal.setLength(0);
                }
                parts.add(new Part(null, name, unit));
                i = close + 1;
            } else {
                literal.append(c);
                i++;
            }
        }
        if (!literal.isEmpty()) {
            parts.add(new Part(literal.toString(), null, null));
        }
        return new CommandTemplate(text, parts);
    }

    /** @return the template as written */
    public String text() {
        return text;
    }

    /** @return the names of its placeholders, in order of first use */
    public Set<String> placeholders() {
        return placeholders;
    }

    /**
     * @param values every value its placeholders name, in SI units
     * @return the command text
     * @throws IllegalArgumentException if a value is missing or not finite
     */
    public String render(Map<String, Double> values) {
        StringBuilder out = new StringBuilder(text.length() + 16);
        for (Part p : parts) {
            if (p.literal() != null) {
                out.append(p.literal());
                continue;
            }
            Double v = values.get(p.name());
            if (v == null || !Double.isFinite(v)) {
                throw new IllegalArgumentException("template \"" + text + "\" needs a finite value for " + p.name() + ", got " + v);
            }
            out.append(number(convert(v, p.unit()), p.unit()));
        }
        return out.toString();
    }

    private static double convert(double si, String unit) {
        if (unit == null) {
            return si;
        }
        return switch (unit) {
            case "deg" -> Math.toDegrees(si);
            case "ms", "mm" -> si * 1000;
            case "cm" -> si * 100;
            default -> throw new IllegalStateException("unit " + unit);
        };
    }

    /**
     * @param value a finite number
     * @param unit  its unit ({@code ms} gives a whole number)
     * @return it in plain decimal: at most six decimals, no trailing zeros, no exponent, no {@code -0}
     */
    static String number(double value, String unit) {
        int scale = "ms".equals(unit) ? 0 : 6;
        BigDecimal d = BigDecimal.valueOf(value).setScale(scale, RoundingMode.HALF_EVEN).stripTrailingZeros();
        if (d.signum() == 0) {
            return "0";
        }
        return d.toPlainString().toLowerCase(Locale.ROOT);
    }

    @Override
    public boolean equals(Object o) {
        return o instanceof CommandTemplate t && t.text.equals(text);
    }

    @Override
    public int hashCode() {
        return text.hashCode();
    }

    @Override
    public String toString() {
        return text;
    }
}
