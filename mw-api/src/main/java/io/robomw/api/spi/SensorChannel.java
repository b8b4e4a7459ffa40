package io.robomw.api.spi;

import io.robomw.api.SensorType;

import java.util.Map;
import java.util.Objects;

/**
 * One sensor as the platform sees it.
 *
 * @param name    its name in the description
 * @param type    what it measures
 * @param port    the input port, as the platform names it ({@code "S1"}, {@code "I3"}, or a motor port for {@link SensorType#TACHO})
 * @param options platform-specific settings from the description's {@code options:} block
 */
public record SensorChannel(String name, SensorType type, String port, Map<String, Object> options) {

    /** Checks and copies. */
    public SensorChannel {
        Objects.requireNonNull(name, "name");
        Objects.requireNonNull(type, "type");
        Objects.requireNonNull(port, "port");
        options = Map.copyOf(options);
    }
}
