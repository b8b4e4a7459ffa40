package io.robomw.config.description;

import org.junit.jupiter.api.Test;

import java.util.List;
import java.util.OptionalDouble;

import static org.junit.jupiter.api.Assertions.assertEquals;

class ConversionTest {

    private static Conversion linear(double scale, double offset) {
        return new Conversion(scale, offset, List.of(), OptionalDouble.empty(), false, OptionalDouble.empty());
    }

    private static Conversion table(double[]... points) {
        return new Conversion(1, 0, java.util.Arrays.stream(points).map(p -> new Conversion.Point(p[0], p[1])).toList(),
                OptionalDouble.empty(), false, OptionalDouble.empty());
    }

    @Test
    void shouldInvertLinearConversionSoApplyGivesTheValueBack() {
        Conversion sonarCm = linear(0.01, 0);
        assertEquals(60.0, sonarCm.invert(0.60), 1e-12);
        Conversion light = linear(1 / 1023.0, 0.05);
        assertEquals(0.42, light.apply(light.invert(0.42)), 1e-12);
    }

    @Test
    void shouldInvertFallingTableOfDistanceSensor() {
        Conversion ir = table(new double[]{80, 0.80}, new double[]{150, 0.40}, new double[]{300, 0.20});
        assertEquals(115.0, ir.invert(0.60), 1e-9);
        assertEquals(0.60, ir.apply(ir.invert(0.60)), 1e-12);
        assertEquals(225.0, ir.invert(0.30), 1e-9);
    }

    @Test
    void shouldGiveTableEndsForValuesBeyondTheTable() {
        Conversion ir = table(new double[]{80, 0.80}, new double[]{300, 0.20});
        assertEquals(80.0, ir.invert(5.0));
        assertEquals(300.0, ir.invert(0.01));
    }
}
