package io.robomw.platform.link;

import org.junit.jupiter.api.Test;

import static io.robomw.platform.link.SerialSettings.Parity.NONE;
import static io.robomw.platform.link.SerialSettings.Parity.ODD;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

class SerialSettingsTest {

    @Test
    void shouldPrintTheUsualShortForm() {
        assertEquals("9600 8N1", SerialSettings.of(9600, 8, NONE, 1).toString());
        assertEquals("2400 8O1", SerialSettings.of(2400, 8, ODD, 1).toString());
    }

    @Test
    void shouldRejectNonPositiveBaud() {
        IllegalArgumentException e = assertThrows(IllegalArgumentException.class, () -> SerialSettings.of(0, 8, NONE, 1));
        assertEquals("baud must be positive, baud=0", e.getMessage());
    }

    @Test
    void shouldRejectDataBitsOutsideFiveToEight() {
        assertThrows(IllegalArgumentException.class, () -> SerialSettings.of(9600, 4, NONE, 1));
        IllegalArgumentException e = assertThrows(IllegalArgumentException.class, () -> SerialSettings.of(9600, 9, NONE, 1));
        assertTrue(e.getMessage().contains("dataBits=9"), e.getMessage());
    }

    @Test
    void shouldRejectStopBitsOtherThanOneOrTwo() {
        IllegalArgumentException e = assertThrows(IllegalArgumentException.class, () -> SerialSettings.of(9600, 8, NONE, 3));
        assertTrue(e.getMessage().contains("stopBits=3"), e.getMessage());
    }

    @Test
    void shouldRejectMissingParity() {
        assertThrows(NullPointerException.class, () -> SerialSettings.of(9600, 8, null, 1));
    }
}
