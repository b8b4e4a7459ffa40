package io.robomw.config.description;

import org.junit.jupiter.api.Test;

import java.util.Map;
import java.util.Set;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

class CommandTemplateTest {

    @Test
    void shouldRenderSiValuesInPlainDecimal() {
        CommandTemplate t = CommandTemplate.parse("robot.walk(${distance}, ${speed})", LeggedDrive.MOVE_VALUES);

        assertEquals("robot.walk(0.5, 0.15)", t.render(Map.of("distance", 0.5, "speed", 0.15)));
        assertEquals("robot.walk(-1.25, 0.000001)", t.render(Map.of("distance", -1.25, "speed", 1e-6)));
        assertEquals("robot.walk(1000000, 0)", t.render(Map.of("distance", 1e6, "speed", -1e-9)), "no exponent, no -0");
    }

    @Test
    void shouldConvertUnitsOfPlaceholders() {
        CommandTemplate t = CommandTemplate.parse("headPan.val = ${angle:deg} time:${duration:ms}; x = ${d:mm} + ${d:cm}", Set.of("angle", "duration", "d"));

        assertEquals("headPan.val = 90 time:400; x = 250 + 25", t.render(Map.of("angle", Math.PI / 2, "duration", 0.4, "d", 0.25)));
        assertEquals("headPan.val = -28.64789 time:1235; x = 1 + 0.1",
                t.render(Map.of("angle", -0.5, "duration", 1.2346, "d", 0.001)), "ms is a whole number");
    }

    @Test
    void shouldLeaveUrbiBracesAndDollarsAlone() {
        CommandTemplate t = CommandTemplate.parse("{ robot.sit(); $x = ${duration:ms} }", Set.of("duration"));

        assertEquals("{ robot.sit(); $x = 1500 }", t.render(Map.of("duration", 1.5)));
        assertEquals(Set.of("duration"), t.placeholders());
    }

    @Test
    void shouldRefuseAPlaceholderTheCommandDoesNotHave() {
        IllegalArgumentException e = assertThrows(IllegalArgumentException.class,
                () -> CommandTemplate.parse("robot.walk(${distanse})", LeggedDrive.MOVE_VALUES));

        assertTrue(e.getMessage().contains("'distanse'") && e.getMessage().contains("distance, duration, speed"), e.getMessage());
    }

    @Test
    void shouldRefuseAnUnknownUnitAndAnUnclosedPlaceholder() {
        IllegalArgumentException unit = assertThrows(IllegalArgumentException.class,
                () -> CommandTemplate.parse("x = ${angle:rad}", Set.of("angle")));
        IllegalArgumentException open = assertThrows(IllegalArgumentException.class,
                () -> CommandTemplate.parse("x = ${angle", Set.of("angle")));
        IllegalArgumentException blank = assertThrows(IllegalArgumentException.class, () -> CommandTemplate.parse("  ", Set.of()));

        assertTrue(unit.getMessage().contains("unit 'rad'") && unit.getMessage().contains("cm, deg, mm, ms"), unit.getMessage());
        assertTrue(open.getMessage().contains("not closed"), open.getMessage());
        assertTrue(blank.getMessage().contains("empty"), blank.getMessage());
    }

    @Test
    void shouldRefuseToRenderWithoutAFiniteValue() {
        CommandTemplate t = CommandTemplate.parse("robot.turn(${angle})", Set.of("angle"));

        assertThrows(IllegalArgumentException.class, () -> t.render(Map.of()));
        assertThrows(IllegalArgumentException.class, () -> t.render(Map.of("angle", Double.NaN)));
    }
}
