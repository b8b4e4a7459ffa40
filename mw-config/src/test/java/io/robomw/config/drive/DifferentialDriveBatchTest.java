package io.robomw.config.drive;

import io.robomw.api.Pose;
import io.robomw.api.UnsupportedActionException;
import io.robomw.config.description.RobotDescription;
import io.robomw.config.description.RobotDescriptionLoader;
import io.robomw.config.kinematics.DifferentialKinematics;
import io.robomw.config.kinematics.Odometry;
import io.robomw.config.kinematics.WheelMotion;
import org.junit.jupiter.api.Test;

import java.util.List;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * The batch's Configuration Layer does for each member what one robot's drive does: the same
 * wheel speeds as {@link DifferentialKinematics#velocity} (reversed motors included), the same
 * refusals naming the robot, and the same odometry as {@link Odometry} from the same encoders.
 */
class DifferentialDriveBatchTest {

    private static final RobotDescription BOT = new RobotDescriptionLoader().parse("""
            name: bot
            platform: sim
            drive: { wheel_diameter: 0.056, track_width: 0.112, max_speed: 0.3, left: { port: B, reversed: true }, right: { port: C } }
            """, "bot.yaml");

    /** A platform of two members whose encoders the test sets, recording the last refresh. */
    private static final class Wheels implements WheelBatch {
        final double[][] encoders = new double[2][2];
        final double[][] refreshed = new double[2][2];

        @Override
        public String name() {
            return "bot.yaml";
        }

        @Override
        public List<String> ports() {
            return List.of("B", "C");
        }

        @Override
        public int members() {
            return 2;
        }

        @Override
        public void refresh(int member, double left, double right) {
            refreshed[member][0] = left;
            refreshed[member][1] = right;
        }

        @Override
        public double degrees(int member, int motor) {
            return encoders[member][motor];
        }
    }

    private final Wheels wheels = new Wheels();
    private final DifferentialDriveBatch batch = new DifferentialDriveBatch(BOT, wheels, List.of("r0", "r1"));

    @Test
    void aMembersDriveGivesTheWheelSpeedsOfOneRobotsDrive() {
        WheelMotion expected = new DifferentialKinematics(BOT.drive().orElseThrow()).velocity(0.15, -0.8);
        batch.drive(1, 0.15, -0.8);
        assertEquals(expected.leftDegreesPerSecond(), wheels.refreshed[1][0], 0.0, "left, reversed");
        assertEquals(expected.rightDegreesPerSecond(), wheels.refreshed[1][1], 0.0);
        assertEquals(0, wheels.refreshed[0][0], "the other member is not driven");
    }

    @Test
    void refusesWhatOneRobotsDriveRefusesNamingTheRobot() {
        UnsupportedActionException tooFast = assertThrows(UnsupportedActionException.class, () -> batch.drive(1, 0.4, 0));
        assertTrue(tooFast.getMessage().contains("r1") && tooFast.getMessage().contains("drive.max_speed"), tooFast.getMessage());
        UnsupportedActionException notANumber = assertThrows(UnsupportedActionException.class, () -> batch.drive(0, Double.NaN, 0));
        assertTrue(notANumber.getMessage().contains("r0") && notANumber.getMessage().contains("linear speed"), notANumber.getMessage());
        assertEquals(0, wheels.refreshed[1][0], "nothing was sent");
        assertThrows(IllegalArgumentException.class, () -> new DifferentialDriveBatch(BOT, wheels, List.of("only-one")));
    }

    @Test
    void keepsEachMembersOdometryAsOneRobotsOdometry() {
        Odometry one = new Odometry(new DifferentialKinematics(BOT.drive().orElseThrow()));
        one.integrate(0, 0);
        batch.startOdometry(0);
        double[][] readings = {{-100, 120}, {-300, 250}, {-320, 700}, {-900, 710}};
        for (double[] r : readings) {
            wheels.encoders[0][0] = r[0];
            wheels.encoders[0][1] = r[1];
            one.integrate(r[0], r[1]);
            batch.drive(0, 0.1, 0.2); // a motion's start integrates, as one robot's drive does
        }
        Pose expected = one.pose();
        Pose pose = batch.pose(0);
        assertEquals(expected.x(), pose.x(), 1e-12);
        assertEquals(expected.y(), pose.y(), 1e-12);
        assertEquals(expected.heading(), pose.heading(), 1e-12);
        assertEquals(new Pose(0, 0, 0), batch.pose(1), "the other member did not move");
        batch.resetPose(0, new Pose(1, 2, 0.5));
        assertEquals(new Pose(1, 2, 0.5), batch.pose(0), "a reset holds until the wheels turn");
    }
}
