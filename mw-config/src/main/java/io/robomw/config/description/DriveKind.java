package io.robomw.config.description;

import java.util.Arrays;
import java.util.Optional;
import java.util.stream.Collectors;

/**
 * The kinds of drive a robot file's {@code drive:} section can describe, by the value of its
 * {@code type:} key. Each kind has one {@link DriveSpec} record that holds its section and one
 * drive implementation in the Configuration Layer ({@code io.robomw.config.drive.Drives} chooses
 * it): a new kind of robot (a vehicle) adds a constant here, its record and its drive.
 */
public enum DriveKind {
    /** Two driven wheels on one axle, steering by speed difference ({@link DifferentialDrive}). */
    DIFFERENTIAL("differential", "two driven wheels on one axle"),
    /** Walks by its firmware's own high-level commands ({@link LeggedDrive}). */
    LEGGED("legged", "walks by its firmware's own commands"),
    /** A drone, boat or rover moved by its autopilot's own targets over MAVLink ({@link VehicleDrive}). */
    VEHICLE("vehicle", "a drone, boat or rover moved by its autopilot");

    private final String yamlName;
    private final String meaning;

    DriveKind(String yamlName, String meaning) {
        this.yamlName = yamlName;
        this.meaning = meaning;
    }

    /** @return the {@code type:} value that names it in a robot file */
    public String yamlName() {
        return yamlName;
    }

    /**
     * @param type a {@code type:} value
     * @return the kind it names, if any
     */
    public static Optional<DriveKind> fromYaml(String type) {
        return Arrays.stream(values()).filter(k -> k.yamlName.equals(type)).findFirst();
    }

    /** @return every kind as a robot file names it, with its meaning, for messages: {@code 'differential' (two driven wheels on one axle) or ...} */
    public static String choices() {
        return Arrays.stream(values()).map(k -> "'" + k.yamlName + "' (" + k.meaning + ")").collect(Collectors.joining(" or "));
    }
}
