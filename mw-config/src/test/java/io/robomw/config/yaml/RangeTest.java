package io.robomw.config.yaml;

import io.robomw.config.description.DescriptionException;
import org.junit.jupiter.api.Test;

import static org.junit.jupiter.api.Assertions.assertAll;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/** One range makes both the check and the words of the problem. */
class RangeTest {

    @Test
    void shouldWordEachKindOfRangeAsItChecksIt() {
        Range between = Range.between(1, 1000, "");
        Range positive = Range.positive(0.001, 10, "metres");
        Range above = Range.above(0, 100, "metres per second");
        Range fraction = Range.fromBelow(0, 1, "").noting("a fraction of the motion");
        assertAll(
                () -> assertEquals("between 1 and 1000", between.rule()),
                () -> assertTrue(between.test(1) && between.test(1000) && !between.test(1000.5)),
                () -> assertEquals("> 0 metres (0.001 to 10)", positive.rule()),
                () -> assertTrue(positive.test(0.001) && positive.test(10) && !positive.test(0.0005)),
                () -> assertEquals("> 0 metres per second (at most 100)", above.rule()),
                () -> assertTrue(!above.test(0) && above.test(100) && !above.test(100.1)),
                () -> assertEquals(">= 0 and < 1 (a fraction of the motion)", fraction.rule()),
                () -> assertTrue(fraction.test(0) && !fraction.test(1)),
                () -> assertEquals("a finite number", Range.ANY.rule()),
                () -> assertFalse(Range.ANY.test(Double.NaN)),
                () -> assertEquals("between -1000000 and 1000000 motor degrees, or 'argument'",
                        Range.between(-1_000_000, 1_000_000, "motor degrees").noting("or 'argument'").rule()));
    }

    @Test
    void shouldReportAValueOutsideItWithTheKeyTheRuleAndTheValue() {
        MappingReader root = YamlDocument.parse("cycle_hz: 5000\n", "robot.yaml");

        double hz = root.number("cycle_hz", 100, Range.between(1, 1000, ""));

        DescriptionException e = assertThrows(DescriptionException.class, () -> root.problems().throwIfAny());
        assertAll(
                () -> assertEquals(100, hz, "the fallback"),
                () -> assertTrue(e.getMessage().contains("robot.yaml:1:11: 'cycle_hz' must be between 1 and 1000, got '5000'"), e.getMessage()));
    }

    @Test
    void shouldRefuseARangeWithoutValues() {
        assertThrows(IllegalArgumentException.class, () -> Range.between(10, 1, ""));
        assertThrows(IllegalArgumentException.class, () -> Range.positive(0, 1, ""));
    }
}
