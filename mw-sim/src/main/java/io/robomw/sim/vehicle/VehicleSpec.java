package io.robomw.sim.vehicle;

import io.robomw.config.description.Body;
import io.robomw.config.description.VehicleDrive;

import java.util.Objects;

/**
 * What the simulator needs to move one vehicle: its medium, its limits (from the robot file's
 * vehicle drive) and the constants of its dynamics (from its body's mass, and the defaults of
 * ArduPilot's SITL models, shared/protocols/mavlink.md §1.6).
 *
 * @param medium          air, water or ground
 * @param maxSpeed        m/s, horizontal
 * @param maxClimbRate    m/s (air only)
 * @param maxTurnRate     rad/s
 * @param mass            kg
 * @param velocityTime    s, the time constant of the first-order velocity response
 * @param maxAcceleration m/s², horizontal
 * @param batteryWh       watt-hours of the battery when full
 * @param batteryCells    lithium cells in series (4S: 16.8 V full)
 */
public record VehicleSpec(VehicleDrive.Medium medium, double maxSpeed, double maxClimbRate, double maxTurnRate, double mass,
                          double velocityTime, double maxAcceleration, double batteryWh, int batteryCells) {

    /** Checks the values. */
    public VehicleSpec {
        Objects.requireNonNull(medium, "medium");
        if (!(maxSpeed > 0) || !(maxTurnRate > 0) || !(mass > 0) || !(velocityTime > 0) || !(maxAcceleration > 0) || !(batteryWh > 0)
                || batteryCells < 1 || !(maxClimbRate >= 0)) {
            throw new IllegalArgumentException("vehicle constants must be positive, got " + maxSpeed + " m/s, " + maxTurnRate + " rad/s, "
                    + mass + " kg, " + velocityTime + " s, " + maxAcceleration + " m/s², " + batteryWh + " Wh, " + batteryCells + " cells");
        }
    }

    /**
     * @param drive the robot file's vehicle drive
     * @param body  its body (mass)
     * @return the constants: a multirotor answers in 0.5 s (up to 5 m/s²) on a 4S 5 Ah battery, a
     *         boat in 1.5 s (up to 1.5 m/s²) on 4S 10 Ah, a rover in 0.67 s (SITL's rover) on
     *         3S 5 Ah
     */
    public static VehicleSpec of(VehicleDrive drive, Body body) {
        return switch (drive.medium()) {
            case AIR -> new VehicleSpec(drive.medium(), drive.maxSpeed(), drive.maxClimbRate(), drive.maxTurnRate(), body.mass(), 0.5, 5.0,
                    74, 4);
            case WATER -> new VehicleSpec(drive.medium(), drive.maxSpeed(), 0, drive.maxTurnRate(), body.mass(), 1.5, 1.5, 148, 4);
            case GROUND -> new VehicleSpec(drive.medium(), drive.maxSpeed(), 0, drive.maxTurnRate(), body.mass(), 0.67, 3.0, 55, 3);
        };
    }
}
