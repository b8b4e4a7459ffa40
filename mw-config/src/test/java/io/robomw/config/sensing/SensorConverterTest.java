package io.robomw.config.sensing;

import io.robomw.api.Position;
import io.robomw.api.ReturnType;
import io.robomw.api.SensorType;
import io.robomw.api.UnsupportedActionException;
import io.robomw.config.description.Conversion;
import io.robomw.config.description.Conversion.Point;
import io.robomw.config.description.SensorSpec;
import org.junit.jupiter.api.Test;

import java.util.List;
import java.util.Map;
import java.util.OptionalDouble;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

class SensorConverterTest {

    private static final String ROBOT = "scout";
    private static final double EPS = 1e-12;

    private static Conversion linear(double scale) {
        return new Conversion(scale, 0, List.of(), OptionalDouble.empty(), false, OptionalDouble.empty());
    }

    private static SensorSpec sensor(String name, SensorType type, Conversion conversion) {
        return new SensorSpec(name, type, Position.FRONT, "4", conversion, Map.of());
    }

    /** A sonar reporting centimetres. */
    private static SensorSpec sonar() {
        return sensor("sonar", SensorType.SONAR, linear(0.01));
    }

    /** A light sensor reporting 0..1023. */
    private static SensorSpec light(OptionalDouble luxAtFullScale) {
        return sensor("floor", SensorType.LIGHT, new Conversion(1.0 / 1023, 0, List.of(), OptionalDouble.empty(), false, luxAtFullScale));
    }

    /** An infra-red range finder whose raw value falls with distance. */
    private static SensorSpec infraredWithTable() {
        return sensor("trail", SensorType.INFRARED, new Conversion(1, 0,
                List.of(new Point(0, 0.30), new Point(512, 0.10), new Point(1023, 0.02)),
                OptionalDouble.empty(), false, OptionalDouble.empty()));
    }

    private static double convert(SensorSpec sensor, double raw, ReturnType type) {
        return SensorConverter.convert(ROBOT, sensor, raw, type);
    }

    // ---- distance ----

    @Test
    void shouldConvertLaserAndGenericRangeReadingsAsDistances() {
        SensorSpec laser = sensor("lidar", SensorType.LASER, linear(0.001));
        SensorSpec range = sensor("tof", SensorType.RANGE, linear(0.001));

        assertEquals(123.4, convert(laser, 1234, ReturnType.CENTIMETERS), 1e-9);
        assertEquals(1234, convert(range, 1234, ReturnType.MILLIMETERS), 1e-9);
        assertEquals(1.234, convert(range, 1234, ReturnType.METERS), 1e-12);
    }

    @Test
    void shouldRefuseAnAngleOfALaserSayingItMeasuresDistance() {
        UnsupportedActionException e = assertThrows(UnsupportedActionException.class,
                () -> SensorConverter.check(ROBOT, sensor("lidar", SensorType.LASER, linear(0.001)), ReturnType.DEGREES));

        assertTrue(e.getMessage().contains("a LASER sensor measures DISTANCE"), e.getMessage());
    }

    @Test
    void shouldConvertSonarCentimetresToMeters() {
        assertEquals(0.42, convert(sonar(), 42, ReturnType.METERS), EPS);
    }

    @Test
    void shouldConvertSonarCentimetresToCentimeters() {
        assertEquals(42, convert(sonar(), 42, ReturnType.CENTIMETERS), 1e-9);
    }

    @Test
    void shouldConvertSonarCentimetresToMillimeters() {
        assertEquals(420, convert(sonar(), 42, ReturnType.MILLIMETERS), 1e-9);
    }

    @Test
    void shouldApplyOffsetAfterScale() {
        SensorSpec s = sensor("sonar", SensorType.SONAR, new Conversion(0.01, 0.03, List.of(), OptionalDouble.empty(), false, OptionalDouble.empty()));

        assertEquals(0.45, convert(s, 42, ReturnType.METERS), EPS);
    }

    @Test
    void shouldReturnRawValueUnconvertedForRaw() {
        assertEquals(42, convert(sonar(), 42, ReturnType.RAW));
    }

    // ---- light ----

    @Test
    void shouldConvertFullScaleLightToHundredPercent() {
        assertEquals(100, convert(light(OptionalDouble.empty()), 1023, ReturnType.PERCENT), 1e-9);
    }

    @Test
    void shouldConvertHalfScaleLightToFiftyPercent() {
        assertEquals(50, convert(light(OptionalDouble.empty()), 511.5, ReturnType.PERCENT), 1e-9);
    }

    @Test
    void shouldConvertDarkLightToZeroPercent() {
        assertEquals(0, convert(light(OptionalDouble.empty()), 0, ReturnType.PERCENT), 1e-9);
    }

    @Test
    void shouldRefuseLuxWithoutLuxAtFullScale() {
        UnsupportedActionException e = assertThrows(UnsupportedActionException.class,
                () -> convert(light(OptionalDouble.empty()), 512, ReturnType.LUX));

        assertTrue(e.getMessage().contains("lux_at_full_scale"), e::getMessage);
    }

    @Test
    void shouldConvertLightToLuxWithLuxAtFullScale() {
        assertEquals(250, convert(light(OptionalDouble.of(500)), 511.5, ReturnType.LUX), 1e-9);
    }

    @Test
    void shouldRefuseLuxOfNonLightSensor() {
        assertThrows(UnsupportedActionException.class, () -> convert(sonar(), 42, ReturnType.LUX));
    }

    // ---- boolean ----

    @Test
    void shouldReadPressedTouchAsTrue() {
        assertEquals(1.0, convert(sensor("bumper", SensorType.TOUCH, Conversion.IDENTITY), 1, ReturnType.BOOLEAN));
    }

    @Test
    void shouldReadReleasedTouchAsFalse() {
        assertEquals(0.0, convert(sensor("bumper", SensorType.TOUCH, Conversion.IDENTITY), 0, ReturnType.BOOLEAN));
    }

    /** A sonar that reads true when something is within 20 cm. */
    private static SensorSpec obstacleDetector() {
        return sensor("sonar", SensorType.SONAR, new Conversion(0.01, 0, List.of(), OptionalDouble.of(0.2), true, OptionalDouble.empty()));
    }

    @Test
    void shouldReadDistanceBelowTrueBelowThresholdAsTrue() {
        assertEquals(1.0, convert(obstacleDetector(), 15, ReturnType.BOOLEAN));
    }

    @Test
    void shouldReadDistanceAtTrueBelowThresholdAsTrue() {
        assertEquals(1.0, convert(obstacleDetector(), 20, ReturnType.BOOLEAN));
    }

    @Test
    void shouldReadDistanceAboveTrueBelowThresholdAsFalse() {
        assertEquals(0.0, convert(obstacleDetector(), 30, ReturnType.BOOLEAN));
    }

    @Test
    void shouldReadValueAboveThresholdAsTrueWithoutTrueBelow() {
        SensorSpec bright = sensor("floor", SensorType.LIGHT, new Conversion(1.0 / 1023, 0, List.of(), OptionalDouble.of(0.5), false, OptionalDouble.empty()));

        assertEquals(1.0, convert(bright, 800, ReturnType.BOOLEAN));
        assertEquals(0.0, convert(bright, 200, ReturnType.BOOLEAN));
    }

    @Test
    void shouldRefuseBooleanOfDistanceSensorWithoutThreshold() {
        UnsupportedActionException e = assertThrows(UnsupportedActionException.class, () -> convert(sonar(), 42, ReturnType.BOOLEAN));

        assertTrue(e.getMessage().contains("threshold"), e::getMessage);
    }

    // ---- tables ----

    @Test
    void shouldInterpolateBetweenTableRows() {
        assertEquals(0.20, convert(infraredWithTable(), 256, ReturnType.METERS), EPS);
    }

    @Test
    void shouldInterpolateInLaterTableSegment() {
        assertEquals(0.06, convert(infraredWithTable(), 767.5, ReturnType.METERS), EPS);
    }

    @Test
    void shouldHitTableRowExactly() {
        assertEquals(0.10, convert(infraredWithTable(), 512, ReturnType.METERS), EPS);
    }

    @Test
    void shouldClampBelowFirstTableRow() {
        assertEquals(0.30, convert(infraredWithTable(), -40, ReturnType.METERS), EPS);
    }

    @Test
    void shouldClampAboveLastTableRow() {
        assertEquals(0.02, convert(infraredWithTable(), 4000, ReturnType.METERS), EPS);
    }

    @Test
    void shouldConvertTableValueToCentimeters() {
        assertEquals(20, convert(infraredWithTable(), 256, ReturnType.CENTIMETERS), 1e-9);
    }

    // ---- units that do not fit ----

    @Test
    void shouldRefuseDegreesOfSonarNamingRobotSensorAndUnit() {
        UnsupportedActionException e = assertThrows(UnsupportedActionException.class, () -> convert(sonar(), 42, ReturnType.DEGREES));

        assertEquals(ROBOT, e.robot());
        assertTrue(e.getMessage().contains("'" + ROBOT + "'"), e::getMessage);
        assertTrue(e.getMessage().contains("'sonar'"), e::getMessage);
        assertTrue(e.getMessage().contains("DEGREES"), e::getMessage);
    }

    @Test
    void shouldRefuseUnitThatDoesNotFitBeforeLookingAtValue() {
        assertThrows(UnsupportedActionException.class, () -> SensorConverter.check(ROBOT, sonar(), ReturnType.PERCENT));
    }

    // ---- tachometers ----

    @Test
    void shouldConvertTachoDegreesToRadians() {
        assertEquals(Math.PI, convert(sensor("odometer", SensorType.TACHO, Conversion.IDENTITY), 180, ReturnType.RADIANS), EPS);
    }

    @Test
    void shouldReturnTachoDegreesAsDegrees() {
        assertEquals(180, convert(sensor("odometer", SensorType.TACHO, Conversion.IDENTITY), 180, ReturnType.DEGREES), 1e-9);
    }

    @Test
    void shouldApplyTachoConversionInDegreesBeforeRadians() {
        SensorSpec geared = sensor("odometer", SensorType.TACHO, linear(0.5));

        assertEquals(Math.PI, convert(geared, 360, ReturnType.RADIANS), EPS);
    }

    // ---- a legged robot's joints and accelerometer ----

    @Test
    void shouldReadAJointsServoDegreesAsAnAngle() {
        SensorSpec neck = sensor("neck", SensorType.JOINT, Conversion.IDENTITY);

        assertEquals(Math.toRadians(-30), convert(neck, -30, ReturnType.RADIANS), EPS);
        assertEquals(-30, convert(neck, -30, ReturnType.DEGREES), EPS);
        assertThrows(UnsupportedActionException.class, () -> convert(neck, -30, ReturnType.METERS));
    }

    @Test
    void shouldReadAnAccelerometerInMetresPerSecondSquaredOnly() {
        SensorSpec accel = sensor("accel_z", SensorType.ACCELEROMETER, Conversion.IDENTITY);

        assertEquals(9.81, convert(accel, 9.81, ReturnType.METERS_PER_SECOND_SQUARED), EPS);
        assertEquals(9.81, convert(accel, 9.81, ReturnType.RAW), EPS);
        assertThrows(UnsupportedActionException.class, () -> convert(accel, 9.81, ReturnType.PERCENT));
    }
}
