package io.robomw.config.description;

import io.robomw.api.Position;
import io.robomw.api.SensorType;

import java.util.Map;

/**
 * One sensor.
 *
 * @param name       unique within the robot
 * @param type       what it measures
 * @param position   where it sits
 * @param port       the input port on the brick (or motor port, for a tachometer)
 * @param conversion how raw values become units
 * @param options    platform-specific settings (the brick's sensor mode, a simulated beam width...)
 */
public record SensorSpec(String name, SensorType type, Position position, String port,
                         Conversion conversion, Map<String, Object> options) {

    /** Copies the options. */
    public SensorSpec {
        options = Map.copyOf(options);
    }
}
