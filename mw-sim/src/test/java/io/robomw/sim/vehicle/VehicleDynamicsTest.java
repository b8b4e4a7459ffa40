package io.robomw.sim.vehicle;

import io.robomw.config.description.VehicleDrive;
import io.robomw.sim.world.WorldDescription;
import org.junit.jupiter.api.Test;

import java.util.List;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * The vehicles' dynamics against the models they follow (mavlink.md §1.6), on a manual step: the
 * test moves the body as the world's physics would (by the velocities the vehicle asks for, no
 * obstacles).
 */
class VehicleDynamicsTest {

    private static final double DT = 0.01;
    private static final WorldDescription.Surroundings STILL = WorldDescription.Surroundings.NONE;

    private static final VehicleSpec COPTER = new VehicleSpec(VehicleDrive.Medium.AIR, 3, 1.5, 1.5, 1.5, 0.5, 5, 74, 4);
    private static final VehicleSpec BOAT = new VehicleSpec(VehicleDrive.Medium.WATER, 2, 0, 0.8, 12, 1.5, 1.5, 148, 4);
    private static final VehicleSpec ROVER = new VehicleSpec(VehicleDrive.Medium.GROUND, 1.5, 0, 1.2, 6, 0.67, 3, 55, 3);

    /** Moves a vehicle as the world would, for a while. */
    private static final class Run {
        final SimVehicle v;
        final WorldDescription.Surroundings world;
        double x;
        double y;
        double heading;

        Run(VehicleSpec spec, double x, double y, WorldDescription.Surroundings world) {
            this.v = new SimVehicle(spec, x, y, 0);
            this.x = x;
            this.y = y;
            this.world = world;
            v.advance(DT, x, y, 0, 0, 0, world);
        }

        Run seconds(double s) {
            for (int i = 0; i < Math.round(s / DT); i++) {
                x += v.commandX() * DT;
                y += v.commandY() * DT;
                heading += v.commandYawRate() * DT;
                v.advance(DT, x, y, heading, v.commandX(), v.commandY(), world);
            }
            return this;
        }

        SimVehicle.Snapshot now() {
            return v.snapshot();
        }
    }

    @Test
    void aMultirotorStaysOnTheGroundUntilArmedAndAskedToClimb() {
        Run r = new Run(COPTER, 5, 5, STILL);
        r.v.target(new VehicleTarget(1, 0, 1, 0));
        r.seconds(2);
        assertTrue(r.now().landed());
        assertEquals(0, r.now().z());
        assertEquals(5, r.x, 1e-9, "an unarmed multirotor does not move");
        r.v.arm();
        r.v.target(new VehicleTarget(0, 0, 0, 0));
        r.seconds(1);
        assertTrue(r.now().landed(), "armed but not asked to climb: it stays down");
        r.v.target(new VehicleTarget(0, 0, 1, 0));
        r.seconds(1);
        assertFalse(r.now().landed());
        assertTrue(r.now().z() > 0.3, "z " + r.now().z());
    }

    @Test
    void aMultirotorClimbsNoFasterThanItsClimbRate() {
        Run r = new Run(COPTER, 5, 5, STILL);
        r.v.arm();
        r.v.target(new VehicleTarget(0, 0, 10, 0));
        r.seconds(4);
        assertEquals(1.5, r.now().vz(), 0.01);
        assertTrue(r.now().z() > 4.5 && r.now().z() < 6, "z " + r.now().z());
    }

    @Test
    void aMultirotorsVelocityAnswersInTheFirstOrderWithinItsSpeed() {
        Run r = new Run(COPTER, 5, 5, STILL);
        r.v.arm();
        r.v.target(new VehicleTarget(0, 0, 1, 0));
        r.seconds(2);
        r.v.target(new VehicleTarget(2, 0, 0, 0));
        r.seconds(COPTER.velocityTime());
        assertEquals(2 * (1 - Math.exp(-1)), r.now().vx(), 0.12, "one time constant: 63 %");
        r.seconds(4);
        assertEquals(2, r.now().vx(), 0.02);
        r.v.target(new VehicleTarget(10, 10, 0, 0));
        r.seconds(5);
        assertEquals(COPTER.maxSpeed(), Math.hypot(r.now().vx(), r.now().vy()), 0.05, "limited to max_speed");
    }

    @Test
    void windMovesAHoveringMultirotorDownwind() {
        WorldDescription.Surroundings windy = new WorldDescription.Surroundings(List.of(), 5, 0, 0, 0, WorldDescription.GeoOrigin.SITL_DEFAULT);
        Run r = new Run(COPTER, 5, 5, windy);
        r.v.arm();
        r.v.target(new VehicleTarget(0, 0, 1, 0));
        r.seconds(2);
        r.v.target(VehicleTarget.HOLD);
        r.seconds(10);
        double drag = Dynamics.GRAVITY / Multirotor.TERMINAL_VELOCITY * Multirotor.UNCANCELLED_DRAG;
        double expected = 5 * drag * COPTER.velocityTime();
        assertEquals(expected, r.now().vx(), 0.02, "steady drift east");
        assertEquals(0, r.now().vy(), 1e-9);
    }

    @Test
    void aMultirotorComingDownLands() {
        Run r = new Run(COPTER, 5, 5, STILL);
        r.v.arm();
        r.v.target(new VehicleTarget(0, 0, 1.5, 0));
        r.seconds(3);
        r.v.target(new VehicleTarget(1, 0, -1, 0));
        r.seconds(8);
        assertTrue(r.now().landed());
        assertEquals(0, r.now().z());
        assertEquals(0, r.now().vx(), "on the ground it stands");
    }

    @Test
    void flyingDrainsTheBatteryFasterThanStandingArmed() {
        Run flying = new Run(COPTER, 5, 5, STILL);
        flying.v.arm();
        flying.v.target(new VehicleTarget(0, 0, 1, 0));
        flying.seconds(2);
        flying.v.target(VehicleTarget.HOLD);
        flying.seconds(58);
        Run standing = new Run(COPTER, 5, 5, STILL);
        standing.v.arm();
        standing.seconds(60);
        double flyingUsed = 1 - flying.now().battery();
        double standingUsed = 1 - standing.now().battery();
        assertTrue(flyingUsed > 10 * standingUsed, flyingUsed + " vs " + standingUsed);
        // 1.5 kg at 180 W/kg for a minute (and a little more climbing) of 74 Wh
        assertEquals(270.0 / 60 / 74, flyingUsed, 0.005);
        assertTrue(flying.now().volts() < 16.8 && flying.now().volts() > 13.2, "volts " + flying.now().volts());
    }

    @Test
    void aBoatReachesItsSpeedAndTheCurrentCarriesIt() {
        WorldDescription.Surroundings sea = new WorldDescription.Surroundings(
                List.of(WorldDescription.WaterArea.rectangle(0, 0, 1000, 1000)), 0, 0, 0, 0.3, WorldDescription.GeoOrigin.SITL_DEFAULT);
        Run r = new Run(BOAT, 100, 100, sea);
        r.v.arm();
        r.v.target(new VehicleTarget(1.5, 0, 0, 0));
        r.seconds(20);
        assertEquals(1.5, r.now().vx(), 0.05, "through the water along its heading");
        assertEquals(0.3, r.now().vy(), 1e-9, "plus the current");
        r.v.target(new VehicleTarget(5, 0, 0, 0));
        r.seconds(30);
        assertEquals(BOAT.maxSpeed(), r.now().vx(), 0.05, "full thrust: max_speed");
    }

    @Test
    void aBoatStopsAtTheShore() {
        WorldDescription.Surroundings basin = new WorldDescription.Surroundings(
                List.of(WorldDescription.WaterArea.rectangle(0, 0, 20, 20)), 0, 0, 0, 0, WorldDescription.GeoOrigin.SITL_DEFAULT);
        Run r = new Run(BOAT, 15, 10, basin);
        r.v.arm();
        r.v.target(new VehicleTarget(2, 0, 0, 0));
        r.seconds(30);
        assertTrue(r.x <= 20 && r.x > 19.9, "at the shore: x " + r.x);
        assertEquals(0, r.now().vx(), "stopped");
    }

    @Test
    void aRoversSpeedAnswersWithSitlsTimeConstant() {
        Run r = new Run(ROVER, 5, 5, STILL);
        r.v.arm();
        r.v.target(new VehicleTarget(1, 0, 0, 0));
        double tau = ROVER.maxSpeed() / ROVER.maxAcceleration();
        r.seconds(tau);
        assertEquals(1 - Math.exp(-1), r.now().vx(), 0.03);
        r.v.target(new VehicleTarget(0, 0, 0, 1.0));
        r.seconds(3);
        assertEquals(1.0, r.now().yawRate(), 0.01, "skid-steer: it turns at rest");
    }
}
