package io.robomw.api;

import org.junit.jupiter.api.Test;

import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

class SensorTypeTest {

    @Test
    void shouldMatchEveryRangeFinderWhenRangeIsAskedFor() {
        assertTrue(SensorType.RANGE.matches(SensorType.SONAR));
        assertTrue(SensorType.RANGE.matches(SensorType.INFRARED));
        assertTrue(SensorType.RANGE.matches(SensorType.LASER));
        assertTrue(SensorType.RANGE.matches(SensorType.RANGE));
        assertFalse(SensorType.RANGE.matches(SensorType.TOUCH));
    }

    @Test
    void shouldMatchOnlyItsOwnTypeOtherwise() {
        assertTrue(SensorType.SONAR.matches(SensorType.SONAR));
        assertFalse(SensorType.SONAR.matches(SensorType.INFRARED));
        assertFalse(SensorType.SONAR.matches(SensorType.RANGE));
    }
}
