package io.robomw.config.kinematics;

import io.robomw.config.description.DifferentialDrive;
import io.robomw.config.description.DifferentialDrive.Wheel;
import org.junit.jupiter.api.Test;

import static org.junit.jupiter.api.Assertions.assertEquals;

class DifferentialKinematicsTest {

    private static final double WHEEL = 0.056;
    private static final double TRACK = 0.112;
    /** 360 / (π · 0.056): motor degrees per metre with 56 mm wheels and no gear. */
    private static final double DEGREES_PER_METRE = 2046.28;
    private static final double EPS = 1e-9;

    private static DifferentialKinematics kinematics(double gear, boolean leftReversed, boolean rightReversed) {
        return new DifferentialKinematics(new DifferentialDrive(WHEEL, TRACK, gear, 0.5, 360,
                new Wheel("B", leftReversed), new Wheel("C", rightReversed)));
    }

    private static DifferentialKinematics nxt() {
        return kinematics(1, false, false);
    }

    /** Motor degrees for a wheel travel, computed independently of the class under test. */
    private static double degrees(double metres) {
        return metres * 360 / (Math.PI * WHEEL);
    }

    @Test
    void shouldTurnEachWheel2046DegreesForOneMetreForwards() {
        WheelMotion m = nxt().move(1.0, 0.2);

        assertEquals(2046.3, m.leftDegrees(), 0.05);
        assertEquals(2046.3, m.rightDegrees(), 0.05);
    }

    @Test
    void shouldRunBothWheelsAtTheAskedSpeedWhenMovingStraight() {
        WheelMotion m = nxt().move(1.0, 0.2);

        assertEquals(0.2 * DEGREES_PER_METRE, m.leftDegreesPerSecond(), 0.01);
        assertEquals(0.2 * DEGREES_PER_METRE, m.rightDegreesPerSecond(), 0.01);
    }

    @Test
    void shouldTurnWheelsBackwardsForNegativeDistance() {
        WheelMotion m = nxt().move(-0.5, 0.2);

        assertEquals(-1023.14, m.leftDegrees(), 0.01);
        assertEquals(-1023.14, m.rightDegrees(), 0.01);
        assertEquals(0.2 * DEGREES_PER_METRE, m.leftDegreesPerSecond(), 0.01, "speeds are magnitudes");
    }

    @Test
    void shouldTurnWheels180DegreesInOppositeDirectionsForQuarterTurnLeft() {
        WheelMotion m = nxt().turn(Math.PI / 2, 1.0);

        assertEquals(-180.0, m.leftDegrees(), 1e-9, "left wheel runs backwards on a left turn");
        assertEquals(180.0, m.rightDegrees(), 1e-9, "right wheel runs forwards on a left turn");
    }

    @Test
    void shouldTurnLeftWheelForwardsForRightTurn() {
        WheelMotion m = nxt().turn(-Math.PI / 2, 1.0);

        assertEquals(180.0, m.leftDegrees(), 1e-9);
        assertEquals(-180.0, m.rightDegrees(), 1e-9);
    }

    @Test
    void shouldRunWheelsAtAngularSpeedTimesHalfTrackWhenTurning() {
        WheelMotion m = nxt().turn(Math.PI, 2.0);

        double wheelMetresPerSecond = 2.0 * TRACK / 2;
        assertEquals(degrees(wheelMetresPerSecond), m.leftDegreesPerSecond(), EPS);
        assertEquals(degrees(wheelMetresPerSecond), m.rightDegreesPerSecond(), EPS);
    }

    @Test
    void shouldFlipSignOfReversedLeftMotor() {
        WheelMotion m = kinematics(1, true, false).move(1.0, 0.2);

        assertEquals(-2046.3, m.leftDegrees(), 0.05);
        assertEquals(2046.3, m.rightDegrees(), 0.05);
    }

    @Test
    void shouldFlipSignOfReversedRightMotorWhenTurning() {
        WheelMotion m = kinematics(1, false, true).turn(Math.PI / 2, 1.0);

        assertEquals(-180.0, m.leftDegrees(), 1e-9);
        assertEquals(-180.0, m.rightDegrees(), 1e-9, "the reversed right motor turns backwards to drive its wheel forwards");
    }

    @Test
    void shouldKeepSpeedsPositiveForReversedMotors() {
        WheelMotion m = kinematics(1, true, true).move(1.0, 0.2);

        assertEquals(0.2 * DEGREES_PER_METRE, m.leftDegreesPerSecond(), 0.01);
        assertEquals(0.2 * DEGREES_PER_METRE, m.rightDegreesPerSecond(), 0.01);
    }

    @Test
    void shouldDoubleMotorDegreesWithGearRatioTwo() {
        WheelMotion m = kinematics(2, false, false).move(1.0, 0.2);

        assertEquals(2 * 2046.28, m.leftDegrees(), 0.05);
        assertEquals(2 * 2046.28, m.rightDegrees(), 0.05);
        assertEquals(2 * 0.2 * DEGREES_PER_METRE, m.leftDegreesPerSecond(), 0.01);
    }

    @Test
    void shouldDoubleTurnDegreesWithGearRatioTwo() {
        WheelMotion m = kinematics(2, false, false).turn(Math.PI / 2, 1.0);

        assertEquals(-360.0, m.leftDegrees(), 1e-9);
        assertEquals(360.0, m.rightDegrees(), 1e-9);
    }

    @Test
    void shouldDriveInnerWheelLessOnLeftArc() {
        double r = 0.5;
        double theta = Math.PI / 2;
        WheelMotion m = nxt().arc(r, theta, 0.2);

        assertEquals(degrees((r - TRACK / 2) * theta), m.leftDegrees(), EPS);
        assertEquals(degrees((r + TRACK / 2) * theta), m.rightDegrees(), EPS);
    }

    @Test
    void shouldDriveRightWheelLessOnArcWithNegativeRadius() {
        double r = 0.5;
        double theta = Math.PI / 2;
        WheelMotion m = nxt().arc(-r, theta, 0.2);

        assertEquals(degrees((r + TRACK / 2) * theta), m.leftDegrees(), EPS, "outer wheel on a right turn");
        assertEquals(degrees((r - TRACK / 2) * theta), m.rightDegrees(), EPS, "inner wheel on a right turn");
    }

    @Test
    void shouldDriveBothWheelsBackwardsOnArcWithNegativeAngle() {
        double r = 0.5;
        double theta = -Math.PI / 2;
        WheelMotion m = nxt().arc(r, theta, 0.2);

        assertEquals(degrees((r - TRACK / 2) * theta), m.leftDegrees(), EPS);
        assertEquals(degrees((r + TRACK / 2) * theta), m.rightDegrees(), EPS);
    }

    @Test
    void shouldRunArcWheelSpeedsInProportionToTheirRadii() {
        double r = 0.5;
        double speed = 0.2;
        WheelMotion m = nxt().arc(r, Math.PI / 2, speed);

        assertEquals(degrees(speed * (r - TRACK / 2) / r), m.leftDegreesPerSecond(), EPS);
        assertEquals(degrees(speed * (r + TRACK / 2) / r), m.rightDegreesPerSecond(), EPS);
    }

    @Test
    void shouldRunInnerWheelBackwardsOnArcTighterThanHalfTrack() {
        double r = 0.028;
        double theta = Math.PI;
        WheelMotion m = nxt().arc(r, theta, 0.1);

        assertEquals(degrees((r - TRACK / 2) * theta), m.leftDegrees(), EPS);
        assertEquals(degrees((r + TRACK / 2) * theta), m.rightDegrees(), EPS);
        assertEquals(degrees(0.1 * (TRACK / 2 - r) / r), m.leftDegreesPerSecond(), EPS, "speeds are magnitudes");
    }

    @Test
    void shouldTurnOnTheSpotForArcOfRadiusZero() {
        WheelMotion arc = nxt().arc(0, Math.PI / 2, 0.1);

        assertEquals(-180.0, arc.leftDegrees(), 1e-9);
        assertEquals(180.0, arc.rightDegrees(), 1e-9);
        assertEquals(degrees(0.1), arc.leftDegreesPerSecond(), EPS, "for radius 0 the speed is each wheel's");
        assertEquals(degrees(0.1), arc.rightDegreesPerSecond(), EPS);
    }

    @Test
    void shouldGiveEqualSignedSpeedsForStraightVelocity() {
        WheelMotion m = nxt().velocity(0.2, 0);

        assertEquals(0.2 * DEGREES_PER_METRE, m.leftDegreesPerSecond(), 0.01);
        assertEquals(0.2 * DEGREES_PER_METRE, m.rightDegreesPerSecond(), 0.01);
        assertEquals(0, m.leftDegrees());
        assertEquals(0, m.rightDegrees());
    }

    @Test
    void shouldGiveNegativeSpeedsForBackwardsVelocity() {
        WheelMotion m = nxt().velocity(-0.1, 0);

        assertEquals(-0.1 * DEGREES_PER_METRE, m.leftDegreesPerSecond(), 0.01);
        assertEquals(-0.1 * DEGREES_PER_METRE, m.rightDegreesPerSecond(), 0.01);
    }

    @Test
    void shouldRunLeftWheelBackwardsForSpinLeftVelocity() {
        WheelMotion m = nxt().velocity(0, 1.0);

        assertEquals(-degrees(TRACK / 2), m.leftDegreesPerSecond(), EPS);
        assertEquals(degrees(TRACK / 2), m.rightDegreesPerSecond(), EPS);
    }

    @Test
    void shouldCombineLinearAndAngularVelocity() {
        WheelMotion m = nxt().velocity(0.2, 1.0);

        assertEquals(degrees(0.2 - TRACK / 2), m.leftDegreesPerSecond(), EPS);
        assertEquals(degrees(0.2 + TRACK / 2), m.rightDegreesPerSecond(), EPS);
    }

    @Test
    void shouldFlipVelocitySignOfReversedMotor() {
        WheelMotion m = kinematics(1, true, false).velocity(0.2, 0);

        assertEquals(-0.2 * DEGREES_PER_METRE, m.leftDegreesPerSecond(), 0.01);
        assertEquals(0.2 * DEGREES_PER_METRE, m.rightDegreesPerSecond(), 0.01);
    }

    @Test
    void shouldConvertMotorDegreesBackToWheelMetres() {
        DifferentialKinematics k = kinematics(2, true, false);

        assertEquals(1.0, k.wheelMetres(2 * degrees(1.0), false), EPS);
        assertEquals(-1.0, k.wheelMetres(2 * degrees(1.0), true), EPS, "a reversed motor's forward rolls the wheel backwards");
    }

    @Test
    void shouldLimitMotorSpeedToMaxSpeedTimesDegreesPerMetre() {
        assertEquals(0.5 * DEGREES_PER_METRE, nxt().maxMotorDegreesPerSecond(), 0.01);
    }
}
