package io.robomw.config.kinematics;

import io.robomw.api.Pose;
import io.robomw.config.description.DifferentialDrive;
import io.robomw.config.description.DifferentialDrive.Wheel;
import org.junit.jupiter.api.Test;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

class OdometryTest {

    private static final double WHEEL = 0.056;
    private static final double TRACK = 0.112;
    private static final double EPS = 1e-9;

    private static DifferentialKinematics kinematics(boolean leftReversed, boolean rightReversed) {
        return new DifferentialKinematics(new DifferentialDrive(WHEEL, TRACK, 1, 0.5, 360,
                new Wheel("B", leftReversed), new Wheel("C", rightReversed)));
    }

    private static double degrees(double metres) {
        return metres * 360 / (Math.PI * WHEEL);
    }

    private static void assertPose(double x, double y, double heading, Pose actual, double tolerance) {
        assertEquals(x, actual.x(), tolerance, "x of " + actual);
        assertEquals(y, actual.y(), tolerance, "y of " + actual);
        assertEquals(0, Pose.normalize(heading - actual.heading()), tolerance, "heading of " + actual);
    }

    @Test
    void shouldOnlyRecordReadingsOnFirstUpdate() {
        Odometry odometry = new Odometry(kinematics(false, false));

        assertPose(0, 0, 0, odometry.update(5000, -300), EPS);
    }

    @Test
    void shouldReachOneMetreAlongXAfterDrivingOneMetreForwards() {
        Odometry odometry = new Odometry(kinematics(false, false));
        odometry.update(0, 0);

        assertPose(1, 0, 0, odometry.update(2046.28, 2046.28), 1e-5);
    }

    @Test
    void shouldIntegrateFromLastReadingsNotFromZero() {
        Odometry odometry = new Odometry(kinematics(false, false));
        odometry.update(1000, 1000);

        assertPose(1, 0, 0, odometry.update(1000 + degrees(1), 1000 + degrees(1)), EPS);
    }

    @Test
    void shouldFaceLeftAfterWheelsTurn180DegreesInOppositeDirections() {
        Odometry odometry = new Odometry(kinematics(false, false));
        odometry.update(0, 0);

        assertPose(0, 0, Math.PI / 2, odometry.update(-180, 180), EPS);
    }

    @Test
    void shouldFaceRightAfterLeftWheelForwardsAndRightWheelBackwards() {
        Odometry odometry = new Odometry(kinematics(false, false));
        odometry.update(0, 0);

        assertPose(0, 0, -Math.PI / 2, odometry.update(180, -180), EPS);
    }

    @Test
    void shouldReturnToOriginAfterDrivingOneMetreSquare() {
        Odometry odometry = new Odometry(kinematics(false, false));
        double left = 0;
        double right = 0;
        odometry.update(left, right);
        Pose pose = null;
        for (int side = 0; side < 4; side++) {
            left += degrees(1);
            right += degrees(1);
            odometry.update(left, right);
            left -= 180;
            right += 180;
            pose = odometry.update(left, right);
        }

        assertPose(0, 0, 0, pose, EPS);
    }

    @Test
    void shouldPassCornersOfSquareOnTheWay() {
        Odometry odometry = new Odometry(kinematics(false, false));
        odometry.update(0, 0);
        odometry.update(degrees(1), degrees(1));
        odometry.update(degrees(1) - 180, degrees(1) + 180);

        assertPose(1, 1, Math.PI / 2, odometry.update(2 * degrees(1) - 180, 2 * degrees(1) + 180), EPS);
    }

    @Test
    void shouldLandAtArcEndForQuarterArcLeft() {
        double r = 0.5;
        double theta = Math.PI / 2;
        Odometry odometry = new Odometry(kinematics(false, false));
        odometry.update(0, 0);

        Pose pose = odometry.update(degrees((r - TRACK / 2) * theta), degrees((r + TRACK / 2) * theta));

        assertPose(r, r, theta, pose, EPS);
    }

    @Test
    void shouldLandAtArcEndForQuarterArcRight() {
        double r = 0.5;
        double theta = Math.PI / 2;
        Odometry odometry = new Odometry(kinematics(false, false));
        odometry.update(0, 0);

        Pose pose = odometry.update(degrees((r + TRACK / 2) * theta), degrees((r - TRACK / 2) * theta));

        assertPose(r, -r, -theta, pose, EPS);
    }

    @Test
    void shouldLandWhereArcSaysWhenIntegratedInManySmallSteps() {
        double r = 0.5;
        double theta = Math.PI / 2;
        Odometry odometry = new Odometry(kinematics(false, false));
        odometry.update(0, 0);
        Pose pose = null;
        for (int i = 1; i <= 100; i++) {
            pose = odometry.update(degrees((r - TRACK / 2) * theta * i / 100), degrees((r + TRACK / 2) * theta * i / 100));
        }

        assertPose(r, r, theta, pose, EPS);
    }

    @Test
    void shouldFollowKinematicsArcCommandToItsGeometricEnd() {
        DifferentialKinematics k = kinematics(false, false);
        WheelMotion arc = k.arc(0.3, Math.PI, 0.1);
        Odometry odometry = new Odometry(k);
        odometry.update(0, 0);

        assertPose(0, 0.6, Math.PI, odometry.update(arc.leftDegrees(), arc.rightDegrees()), EPS);
    }

    @Test
    void shouldDriveForwardsWhenBothReversedMotorsTurnBackwards() {
        Odometry odometry = new Odometry(kinematics(true, true));
        odometry.update(0, 0);

        assertPose(1, 0, 0, odometry.update(-degrees(1), -degrees(1)), EPS);
    }

    @Test
    void shouldDriveForwardsWithReversedLeftMotorTurningBackwards() {
        Odometry odometry = new Odometry(kinematics(true, false));
        odometry.update(0, 0);

        assertPose(1, 0, 0, odometry.update(-degrees(1), degrees(1)), EPS);
    }

    @Test
    void shouldTurnLeftWithReversedLeftMotorWhenBothMotorsTurnForwards() {
        Odometry odometry = new Odometry(kinematics(true, false));
        odometry.update(0, 0);

        assertPose(0, 0, Math.PI / 2, odometry.update(180, 180), EPS);
    }

    @Test
    void shouldReturnToStartWhenReplayingKinematicsOfReversedMotors() {
        DifferentialKinematics k = kinematics(true, false);
        Odometry odometry = new Odometry(k);
        double left = 0;
        double right = 0;
        odometry.update(left, right);
        Pose pose = null;
        for (int side = 0; side < 4; side++) {
            WheelMotion straight = k.move(1, 0.2);
            left += straight.leftDegrees();
            right += straight.rightDegrees();
            odometry.update(left, right);
            WheelMotion turn = k.turn(Math.PI / 2, 1);
            left += turn.leftDegrees();
            right += turn.rightDegrees();
            pose = odometry.update(left, right);
        }

        assertPose(0, 0, 0, pose, EPS);
    }

    @Test
    void shouldIntegrateFromResetPose() {
        Odometry odometry = new Odometry(kinematics(false, false));
        odometry.update(0, 0);
        odometry.reset(new Pose(2, 3, Math.PI / 2));

        assertPose(2, 4, Math.PI / 2, odometry.update(degrees(1), degrees(1)), EPS);
    }

    @Test
    void shouldIntegrateWithoutAPoseExactlyAsUpdateDoes() {
        // integrate() keeps the estimate in fields; update() returns it as a pose: the same bits, and
        // the heading kept normalised through many turns
        Odometry byUpdate = new Odometry(kinematics(false, true));
        Odometry byIntegrate = new Odometry(kinematics(false, true));
        java.util.SplittableRandom random = new java.util.SplittableRandom(7);
        double left = 0;
        double right = 0;
        for (int i = 0; i < 2000; i++) {
            left += random.nextDouble(-40, 90);
            right += random.nextDouble(-90, 40);
            Pose expected = byUpdate.update(left, right);
            byIntegrate.integrate(left, right);
            assertEquals(expected, byIntegrate.pose(), "after " + (i + 1) + " readings");
            assertTrue(expected.heading() > -Math.PI && expected.heading() <= Math.PI, "heading normalised: " + expected);
        }
    }

    @Test
    void shouldRefuseReadingsThatWouldMakeThePoseNotANumberAndKeepTheEstimate() {
        Odometry odometry = new Odometry(kinematics(false, false));
        odometry.update(0, 0);
        Pose before = odometry.update(degrees(1), degrees(1));

        IllegalArgumentException e = assertThrows(IllegalArgumentException.class, () -> odometry.integrate(Double.POSITIVE_INFINITY, degrees(1)));

        assertTrue(e.getMessage().contains("finite"), e.getMessage());
        assertEquals(before, odometry.pose(), "the estimate is unchanged");
        assertPose(2, 0, 0, odometry.update(degrees(2), degrees(2)), EPS);
    }
}
