package io.robomw.agents.net;

import org.junit.jupiter.api.Test;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/** A table of wire codes built from an enum: codes back to constants, unknown codes and code mistakes named. */
class WireCodesTableTest {

    enum Colour implements WireCode {
        RED(3), GREEN(0), BLUE(9);

        private final int code;

        Colour(int code) {
            this.code = code;
        }

        @Override
        public int code() {
            return code;
        }
    }

    enum Twice implements WireCode {
        ONE, OTHER;

        @Override
        public int code() {
            return 4;
        }
    }

    enum Negative implements WireCode {
        BELOW;

        @Override
        public int code() {
            return -1;
        }
    }

    @Test
    void eachCodeReadsBackAsItsConstantNotItsPosition() {
        WireCodes<Colour> codes = WireCodes.of(Colour.class, "colour");
        for (Colour c : Colour.values()) {
            assertEquals(c, codes.get(c.code()));
        }
        assertTrue(codes.find(1).isEmpty(), "a gap in the codes is no constant");
        assertTrue(codes.find(-5).isEmpty() && codes.find(10).isEmpty(), "outside the table");
    }

    @Test
    void anUnknownCodeIsAnErrorNamingItAndTheCodesKnown() {
        IllegalArgumentException e = assertThrows(IllegalArgumentException.class, () -> WireCodes.of(Colour.class, "colour").get(7));
        assertEquals("unknown colour code 7 (known: 3 RED, 0 GREEN, 9 BLUE)", e.getMessage());
    }

    @Test
    void aCodeGivenTwiceOrOutOfRangeIsRefusedWhenTheTableIsBuilt() {
        IllegalStateException twice = assertThrows(IllegalStateException.class, () -> WireCodes.of(Twice.class, "twice"));
        assertTrue(twice.getMessage().contains("code 4 is given twice, to ONE and OTHER"), twice.getMessage());
        IllegalStateException negative = assertThrows(IllegalStateException.class, () -> WireCodes.of(Negative.class, "negative"));
        assertTrue(negative.getMessage().contains("BELOW has code -1"), negative.getMessage());
    }
}
