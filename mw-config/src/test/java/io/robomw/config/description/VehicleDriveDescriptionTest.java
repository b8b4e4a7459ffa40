package io.robomw.config.description;

import io.robomw.api.Capability;
import org.junit.jupiter.api.Test;

import java.nio.file.Path;
import java.util.Set;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/** The vehicle drive of robot files (drive: {type: vehicle, ...}), and the examples. */
class VehicleDriveDescriptionTest {

    private static final Path EXAMPLES = Path.of("..", "examples", "robots");
    private final RobotDescriptionLoader loader = new RobotDescriptionLoader();

    @Test
    void theExampleVehiclesLoadWithTheirMediumAndDialect() {
        RobotDescription copter = loader.load(EXAMPLES.resolve("copter-ardupilot.yaml"));
        VehicleDrive d = copter.vehicleDrive().orElseThrow();
        assertEquals(VehicleDrive.Medium.AIR, d.medium());
        assertEquals(VehicleDrive.Autopilot.ARDUPILOT, d.autopilot());
        assertEquals(1.5, d.maxClimbRate());
        assertEquals(Set.of(Capability.AIR), copter.capabilities());
        assertTrue(copter.drive().isEmpty() && copter.leggedDrive().isEmpty());
        assertEquals(VehicleDrive.Autopilot.PX4, loader.load(EXAMPLES.resolve("copter-px4.yaml")).vehicleDrive().orElseThrow().autopilot());
        RobotDescription boat = loader.load(EXAMPLES.resolve("boat.yaml"));
        assertEquals(VehicleDrive.Medium.WATER, boat.vehicleDrive().orElseThrow().medium());
        assertEquals(0, boat.vehicleDrive().orElseThrow().maxClimbRate());
        assertEquals(Set.of(Capability.WATER), boat.capabilities());
        assertEquals(Set.of(Capability.GROUND), loader.load(EXAMPLES.resolve("rover.yaml")).capabilities());
    }

    @Test
    void aVehicleWithoutMediumOrWithAClimbingBoatIsRefusedNamingTheKey() {
        DescriptionException e = assertThrows(DescriptionException.class, () -> loader.parse("""
                name: v
                platform: mavlink
                drive: { type: vehicle, max_speed: 2 }
                """, "v.yaml"));
        assertTrue(e.getMessage().contains("medium"), e.getMessage());
        e = assertThrows(DescriptionException.class, () -> loader.parse("""
                name: v
                platform: mavlink
                drive: { type: vehicle, medium: water, max_speed: 2, max_climb_rate: 1, autopilot: inav }
                """, "v.yaml"));
        assertTrue(e.getMessage().contains("max_climb_rate") && e.getMessage().contains("autopilot"), e.getMessage());
    }

    @Test
    void anAirVehicleGetsADefaultClimbRateAndTakeoffAltitude() {
        VehicleDrive d = loader.parse("""
                name: v
                platform: mavlink
                drive: { type: vehicle, medium: air, max_speed: 2 }
                """, "v.yaml").vehicleDrive().orElseThrow();
        assertEquals(1.5, d.maxClimbRate());
        assertEquals(2.0, d.takeoffAltitude());
        assertEquals(0.5, d.acceptanceRadius());
    }
}
