package io.robomw.config.robot;

import io.robomw.api.spi.ConnectionSettings;
import io.robomw.api.spi.PlatformConfig;

import java.util.LinkedHashMap;
import java.util.Map;

/**
 * Connection values that replace those of a robot file when it is opened, for links whose
 * address is only known at run time (the {@code /dev/pts/N} an emulator prints, a TCP port it
 * chose). Given to {@link io.robomw.api.Robots#open(java.nio.file.Path, io.robomw.api.spi.PlatformServices)}
 * as a platform service, as {@code mw host --connection port=/dev/pts/5} does.
 *
 * @param values the keys to replace or add; numeric text becomes a number, as in YAML
 */
public record ConnectionOverride(Map<String, String> values) {

    /** Copies the values. */
    public ConnectionOverride {
        values = Map.copyOf(values);
    }

    /**
     * @param config what a platform would be told
     * @return the same with these connection values in place
     */
    public PlatformConfig applyTo(PlatformConfig config) {
        Map<String, Object> merged = new LinkedHashMap<>(config.connection().values());
        values.forEach((k, v) -> merged.put(k, v.matches("-?\\d{1,9}") ? (Object) Integer.valueOf(v) : v));
        ConnectionSettings c = new ConnectionSettings(merged, config.connection().source() + " (connection overridden by " + values + ")");
        return config.withConnection(c);
    }
}
