package io.robomw.cli;

import picocli.CommandLine;

import java.math.BigDecimal;
import java.time.Duration;
import java.time.format.DateTimeParseException;
import java.util.Locale;
import java.util.regex.Matcher;
import java.util.regex.Pattern;

/**
 * The one way every {@code mw} option reads a duration: a number of seconds ({@code 30},
 * {@code 0.5}), a number with a unit ({@code 500ms}, {@code 30s}, {@code 2m}, {@code 1h}), or
 * ISO-8601 ({@code PT30S}, {@code PT1M30S}). Negative durations are refused. Registered for every
 * {@link Duration} option of the command line by {@link Mw#commandLine()}.
 */
final class Durations implements CommandLine.ITypeConverter<Duration> {

    /** What a duration option takes, for error messages and option descriptions. */
    static final String FORMS = "30 (seconds), 500ms, 30s, 2m, 1h or ISO-8601 (PT30S)";

    private static final Pattern NUMBER_AND_UNIT = Pattern.compile("(\\d+(?:\\.\\d+)?|\\.\\d+)\\s*(ms|s|m|min|h)?");

    @Override
    public Duration convert(String value) {
        return parse(value);
    }

    /**
     * @param text a duration as a user types it
     * @return the duration
     * @throws CommandLine.TypeConversionException naming the text and the forms accepted
     */
    static Duration parse(String text) {
        String t = text.strip().toLowerCase(Locale.ROOT);
        if (t.startsWith("p")) {
            try {
                Duration d = Duration.parse(t.toUpperCase(Locale.ROOT));
                if (d.isNegative()) {
                    throw refused(text, "negative");
                }
                return d;
            } catch (DateTimeParseException e) {
                throw refused(text, "malformed ISO-8601");
            }
        }
        Matcher m = NUMBER_AND_UNIT.matcher(t);
        if (!m.matches()) {
            throw refused(text, t.startsWith("-") ? "negative" : "unknown form");
        }
        BigDecimal amount = new BigDecimal(m.group(1));
        String unit = m.group(2) == null ? "s" : m.group(2);
        BigDecimal nanosPerUnit = switch (unit) {
            case "ms" -> BigDecimal.valueOf(1_000_000L);
            case "s" -> BigDecimal.valueOf(1_000_000_000L);
            case "m", "min" -> BigDecimal.valueOf(60_000_000_000L);
            case "h" -> BigDecimal.valueOf(3_600_000_000_000L);
            default -> throw new IllegalStateException(unit);
        };
        BigDecimal nanos = amount.multiply(nanosPerUnit);
        if (nanos.compareTo(BigDecimal.valueOf(Long.MAX_VALUE)) > 0) {
            throw refused(text, "too long");
        }
        return Duration.ofNanos(nanos.longValue());
    }

    /**
     * @param d a duration
     * @return it as a user would type it: {@code 500ms}, {@code 30s}, {@code 2m}, {@code 1.5s}
     */
    static String format(Duration d) {
        if (d.toNanos() % 1_000_000 != 0 || d.isZero()) {
            return d.isZero() ? "0s" : d.toString();
        }
        long ms = d.toMillis();
        if (ms % 60_000 == 0 && ms >= 60_000) {
            return ms / 60_000 + "m";
        }
        if (ms % 1000 == 0) {
            return ms / 1000 + "s";
        }
        return ms < 1000 ? ms + "ms" : BigDecimal.valueOf(ms, 3).stripTrailingZeros().toPlainString() + "s";
    }

    private static CommandLine.TypeConversionException refused(String text, String why) {
        return new CommandLine.TypeConversionException("'" + text + "' is not a duration (" + why + "); give " + FORMS);
    }
}
