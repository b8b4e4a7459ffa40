package io.robomw.config.robot;

import io.robomw.api.Clock;
import io.robomw.api.ManualClock;
import io.robomw.api.Pose;
import io.robomw.api.UnsupportedActionException;
import io.robomw.api.spi.HighLevelCommand;
import io.robomw.api.spi.HighLevelPlatform;
import io.robomw.api.spi.MotorCommand;
import io.robomw.api.spi.PoseSource;
import io.robomw.api.spi.RobotPlatform;
import io.robomw.config.description.RobotDescription;
import io.robomw.config.description.RobotDescriptionLoader;
import io.robomw.config.drive.DriveControl;
import io.robomw.config.drive.Drives;
import io.robomw.config.vehicle.VehicleDriveControl;
import org.junit.jupiter.api.Test;

import java.util.List;
import java.util.Optional;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.CopyOnWriteArrayList;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertInstanceOf;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * A vehicle drive under a reload, as every drive: the verbs are checked against the limits of the
 * description in force before anything is sent, a reload brings the new limits to the next
 * command, and the pose keeps its frame (where the robot was opened) across the reload.
 */
class VehicleDriveReloadTest {

    private static final String COPTER = """
            name: copter
            platform: mavlink
            drive: { type: vehicle, medium: air, autopilot: ardupilot, max_speed: %s, max_climb_rate: 1.5, max_turn_rate: 1.57,
                     acceptance_radius: %s, takeoff_altitude: 2.0 }
            """;

    private static RobotDescription copter(double maxSpeed, double acceptance) {
        return new RobotDescriptionLoader().parse(COPTER.formatted(maxSpeed, acceptance), "copter.yaml");
    }

    @Test
    void aReloadBringsNewLimitsToTheNextCommandAndKeepsThePosesFrame() {
        Vehicle vehicle = new Vehicle();
        vehicle.at = new Pose(10, 5, Math.PI / 2, 0);
        DriveControl before = Drives.choose(copter(3, 0.3), vehicle, null);
        assertInstanceOf(VehicleDriveControl.class, before);

        UnsupportedActionException tooFast = assertThrows(UnsupportedActionException.class, () -> before.move(1, 4));
        assertTrue(tooFast.getMessage().contains("drive.max_speed"), tooFast.getMessage());
        assertEquals(List.of(), vehicle.commands, "refused before anything was sent");
        before.move(1, 2);
        assertEquals(0.3, vehicle.last().argument("acceptance_radius"), 1e-12);

        vehicle.at = new Pose(10, 6, Math.PI / 2, 2); // 1 m ahead (north, its heading when opened), 2 m up
        DriveControl after = Drives.choose(copter(5, 0.6), vehicle, before);
        after.move(1, 4);
        assertEquals("move", vehicle.last().name());
        assertEquals(4, vehicle.last().argument("speed"), 1e-12, "the reloaded max_speed lets 4 m/s through");
        assertEquals(0.6, vehicle.last().argument("acceptance_radius"), 1e-12, "and the new acceptance radius goes with it");
        Pose pose = after.pose();
        assertEquals(1.0, pose.x(), 1e-9, "the pose still counts from where the robot was opened: " + pose);
        assertEquals(0.0, pose.y(), 1e-9);
        assertEquals(2.0, pose.z(), 1e-9, "z is the altitude");
    }

    /** A vehicle's platform as the drive sees it: high-level commands recorded, a pose it reports. */
    private static final class Vehicle implements RobotPlatform, HighLevelPlatform, PoseSource {
        final ManualClock clock = new ManualClock();
        final List<HighLevelCommand> commands = new CopyOnWriteArrayList<>();
        volatile Pose at;

        HighLevelCommand last() {
            return commands.get(commands.size() - 1);
        }

        @Override
        public CompletableFuture<Void> execute(HighLevelCommand command) {
            commands.add(command);
            return new CompletableFuture<>();
        }

        @Override
        public Optional<Pose> reportedPose() {
            return Optional.ofNullable(at);
        }

        @Override
        public Clock clock() {
            return clock;
        }

        @Override
        public CompletableFuture<Void> run(MotorCommand command) {
            return CompletableFuture.failedFuture(new IllegalStateException("a vehicle takes no motor commands: " + command));
        }

        @Override
        public CompletableFuture<Void> stopAll() {
            return CompletableFuture.completedFuture(null);
        }

        @Override
        public CompletableFuture<Double> readRaw(String sensorName) {
            return CompletableFuture.completedFuture(0.0);
        }

        @Override
        public double motorDegrees(String port) {
            throw new UnsupportedOperationException("no motors");
        }

        @Override
        public boolean hasEncoder(String port) {
            return false;
        }

        @Override
        public void close() {
        }
    }
}
