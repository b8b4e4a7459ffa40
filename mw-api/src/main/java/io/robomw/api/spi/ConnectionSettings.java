package io.robomw.api.spi;

import java.util.Map;
import java.util.Optional;

/**
 * The {@code connection:} block of a robot description: a serial device and its settings, or a
 * host and port. Accessors throw {@link IllegalArgumentException} naming the source file and the
 * key when a value is missing or of the wrong type.
 *
 * @param values the block's keys and values
 * @param source where the block came from (the description file), for error messages
 */
public record ConnectionSettings(Map<String, Object> values, String source) {

    /** Copies the map. */
    public ConnectionSettings {
        values = Map.copyOf(values);
    }

    /**
     * @param key a key
     * @return its value as text, if present
     */
    public Optional<String> text(String key) {
        Object v = values.get(key);
        return v == null ? Optional.empty() : Optional.of(v.toString());
    }

    /**
     * @param key a key that must be present
     * @return its value as text
     */
    public String requireText(String key) {
        return text(key).orElseThrow(() -> new IllegalArgumentException(
                source + ": connection." + key + " is missing; the platform needs it"));
    }

    /**
     * @param key      a key
     * @param fallback the value when the key is absent
     * @return its value as an integer
     */
    public int integer(String key, int fallback) {
        Object v = values.get(key);
        if (v == null) {
            return fallback;
        }
        if (v instanceof Number n && n.doubleValue() == Math.rint(n.doubleValue())) {
            return n.intValue();
        }
        throw new IllegalArgumentException(source + ": connection." + key + " must be an integer, got '" + v + "'");
    }

    /**
     * @param key      a key
     * @param fallback the value when absent
     * @return its value as a number
     */
    public double number(String key, double fallback) {
        Object v = values.get(key);
        if (v == null) {
            return fallback;
        }
        if (v instanceof Number n) {
            return n.doubleValue();
        }
        throw new IllegalArgumentException(source + ": connection." + key + " must be a number, got '" + v + "'");
    }

    /**
     * @param key      a key
     * @param fallback the value when absent
     * @return its value as a boolean ({@code true}/{@code false}, also as text)
     */
    public boolean bool(String key, boolean fallback) {
        Object v = values.get(key);
        if (v == null) {
            return fallback;
        }
        if (v instanceof Boolean b) {
            return b;
        }
        if ("true".equals(v.toString()) || "false".equals(v.toString())) {
            return Boolean.parseBoolean(v.toString());
        }
        throw new IllegalArgumentException(source + ": connection." + key + " must be true or false, got '" + v + "'");
    }
}
