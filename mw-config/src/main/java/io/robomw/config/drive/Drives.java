package io.robomw.config.drive;

import io.robomw.api.spi.RobotPlatform;
import io.robomw.config.description.DifferentialDrive;
import io.robomw.config.description.DriveSpec;
import io.robomw.config.description.LeggedDrive;
import io.robomw.config.description.RobotDescription;
import io.robomw.config.description.VehicleDrive;
import io.robomw.config.legged.LeggedDriveControl;
import io.robomw.config.vehicle.VehicleDriveControl;

/**
 * Chooses the {@link DriveControl} for a description: the one place that knows which
 * implementation serves which {@link io.robomw.config.description.DriveKind}. A robot chooses
 * once per description in force, not in every verb: when a reload brings a new description it
 * chooses again, and a drive of the same kind continues the previous one's pose.
 *
 * <h2>Adding a kind of drive</h2>
 * A vehicle (air, water, ground over an autopilot) is the next: a {@link
 * io.robomw.config.description.DriveKind} constant (its {@code type:} value), a
 * {@link DriveSpec} record for its section (permitted by the sealed interface, read and checked by
 * the loader, carried by the description), a {@link DriveControl} that turns the verbs into its
 * platform's commands (overriding {@link DriveControl#changeAltitude}, {@link DriveControl#takeOff}
 * and {@link DriveControl#land} if it flies) and reports its motions to its pose tracker, and one
 * branch here.
 */
public final class Drives {

    private Drives() {
    }

    /**
     * @param description the description in force
     * @param platform    the opened platform
     * @param previous    the drive chosen for the description before (a reload), or {@code null}
     * @return the drive for the description: its pose continues {@code previous}'s if both are of
     *         the same kind
     */
    public static DriveControl choose(RobotDescription description, RobotPlatform platform, DriveControl previous) {
        DriveSpec spec = description.driveSpec().orElse(null);
        if (spec instanceof DifferentialDrive wheels) {
            return new DifferentialDriveControl(description, wheels, platform,
                    previous instanceof DifferentialDriveControl p ? p : null);
        }
        if (spec instanceof LeggedDrive legs) {
            return new LeggedDriveControl(description, legs, platform, previous instanceof LeggedDriveControl p ? p : null);
        }
        if (spec instanceof VehicleDrive vehicle) {
            return new VehicleDriveControl(description, vehicle, platform, previous instanceof VehicleDriveControl p ? p : null);
        }
        return new NoDrive(description);
    }
}
