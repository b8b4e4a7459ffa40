package io.robomw.api;

/**
 * One sensor of a robot, as {@link Robot#sensors()} lists it.
 *
 * @param name     its name in the description
 * @param type     what it measures
 * @param position where it sits
 */
public record SensorInfo(String name, SensorType type, Position position) implements java.io.Serializable {

    private static final long serialVersionUID = 1L;

}
