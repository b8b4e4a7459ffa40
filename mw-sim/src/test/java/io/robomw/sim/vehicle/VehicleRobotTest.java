package io.robomw.sim.vehicle;

import io.robomw.api.Capability;
import io.robomw.api.Pose;
import io.robomw.api.Position;
import io.robomw.api.ReturnType;
import io.robomw.api.Robot;
import io.robomw.api.RobotException;
import io.robomw.api.SensorType;
import io.robomw.api.UnsupportedActionException;
import io.robomw.sim.Simulation;
import org.junit.jupiter.api.Test;

import java.nio.file.Path;
import java.time.Duration;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * Vehicles through all three layers in the simulator (the harbour world): the Instruction Layer's
 * verbs on a copter and a boat, their checks before anything moves, their sensors through getValue
 * with units, and the pose with its altitude.
 */
class VehicleRobotTest {

    private static final Path HARBOUR = Path.of("..", "examples", "worlds", "harbour.yaml");

    @Test
    void aCopterTakesOffMovesClimbsReadsItsSensorsAndLands() {
        try (Simulation sim = Simulation.load(HARBOUR)) {
            Robot copter = sim.robot("copter");
            double[] seen = new double[6];
            Pose[] poses = new Pose[3];
            sim.run(Duration.ofMinutes(2), () -> {
                RobotException grounded = assertThrows(RobotException.class, () -> copter.move(1, 1));
                assertTrue(grounded.getMessage().contains("take off first"), grounded.getMessage());
                copter.takeOff(2);
                poses[0] = copter.pose();
                copter.move(3, 1.5);
                copter.turn(Math.PI / 2, 1);
                copter.changeAltitude(1, 0.5);
                poses[1] = copter.pose();
                seen[0] = copter.getValue(Position.BOTTOM, SensorType.LASER, ReturnType.METERS);
                seen[1] = copter.getValue(Position.CENTER, SensorType.ALTITUDE, ReturnType.CENTIMETERS);
                seen[2] = copter.getValue(Position.CENTER, SensorType.BATTERY, ReturnType.PERCENT);
                seen[3] = copter.getValue(Position.CENTER, SensorType.LATITUDE, ReturnType.DEGREES);
                seen[4] = copter.getValue(Position.FRONT, SensorType.RANGE, ReturnType.METERS);
                copter.land();
                poses[2] = copter.pose();
            });
            assertEquals(2.0, poses[0].z(), 0.1, "at 2 m after take-off");
            // reached within its acceptance radius (0.3 m), and the breeze from the west pushes it while it hovers
            assertEquals(3.0, poses[1].x(), 0.4, "3 m ahead of where it started");
            assertEquals(0.0, poses[1].y(), 0.3);
            assertEquals(Math.PI / 2, poses[1].heading(), 0.03);
            assertEquals(3.0, poses[1].z(), 0.1, "climbed 1 m");
            assertEquals(3.0, seen[0], 0.1, "the downward laser sees the ground 3 m below");
            assertEquals(300, seen[1], 10, "altitude in centimetres");
            assertTrue(seen[2] > 80 && seen[2] < 100, "battery " + seen[2] + " %");
            assertEquals(50.154, seen[3], 0.001, "latitude near the harbour's home");
            assertTrue(seen[4] > 0, "a range ahead: " + seen[4]);
            assertEquals(0.0, poses[2].z(), 0.02, "landed");
            assertTrue(!sim.world().robot("copter").vehicle().snapshot().armed(), "disarmed after landing");
        }
    }

    @Test
    void aBoatSailsButCannotTakeOffOrClimbAndAWheeledRobotCannotFly() {
        try (Simulation sim = Simulation.load(HARBOUR)) {
            Robot boat = sim.robot("boat");
            Robot nxt = sim.robot("nxt");
            UnsupportedActionException takeoff = assertThrows(UnsupportedActionException.class, () -> boat.takeOffAsync(2));
            assertTrue(takeoff.getMessage().contains("water vehicle"), takeoff.getMessage());
            assertThrows(UnsupportedActionException.class, () -> boat.changeAltitudeAsync(1, 0.5));
            assertThrows(UnsupportedActionException.class, boat::landAsync);
            UnsupportedActionException wheels = assertThrows(UnsupportedActionException.class, () -> nxt.takeOffAsync(1));
            assertTrue(wheels.getMessage().contains("nxt"), wheels.getMessage());
            UnsupportedActionException climb = assertThrows(UnsupportedActionException.class, () -> nxt.changeAltitudeAsync(0.5, 0.2));
            assertTrue(climb.getMessage().contains("nxt"), "a wheeled robot cannot climb: " + climb.getMessage());
            // capabilities() says why: the boat is built for water, not air; the copter for air
            assertTrue(boat.can(Capability.WATER) && !boat.can(Capability.AIR), "boat: " + boat.capabilities());
            assertTrue(!nxt.can(Capability.AIR), "nxt: " + nxt.capabilities());
            assertTrue(sim.robot("copter").can(Capability.AIR), "copter: " + sim.robot("copter").capabilities());
            assertThrows(UnsupportedActionException.class, () -> boat.moveAsync(1, 5), "above drive.max_speed");
            Pose[] after = new Pose[1];
            sim.run(Duration.ofMinutes(2), () -> {
                boat.move(4, 1);
                boat.turn(-Math.PI / 2, 0.5);
                boat.move(2, 1);
                after[0] = boat.pose();
            });
            // each move ends within the acceptance radius (0.5 m); the tide then moves the boat within its hold radius
            assertEquals(4.0, after[0].x(), 0.8);
            assertEquals(-2.0, after[0].y(), 0.8, "a quarter turn right, then 2 m");
            assertTrue(sim.world().description().surroundings().onWater(sim.world().robot("boat").pose().x(),
                    sim.world().robot("boat").pose().y()), "still on the water");
        }
    }
}
