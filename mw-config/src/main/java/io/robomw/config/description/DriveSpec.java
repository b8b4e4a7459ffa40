package io.robomw.config.description;

/**
 * A robot file's {@code drive:} section, read and checked: how the robot moves. One record per
 * {@link DriveKind}; the Configuration Layer chooses the drive implementation that turns the
 * Instruction Layer's motions into platform commands by it, once per description in force.
 */
public sealed interface DriveSpec permits DifferentialDrive, LeggedDrive, VehicleDrive {

    /** @return which kind of drive it describes */
    DriveKind kind();
}
