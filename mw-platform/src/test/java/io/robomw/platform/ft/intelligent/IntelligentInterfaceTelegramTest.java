package io.robomw.platform.ft.intelligent;

import org.junit.jupiter.api.Test;

import java.util.HexFormat;

import static org.junit.jupiter.api.Assertions.assertArrayEquals;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;

/** The byte examples of the protocol notes (section 4.1), exactly. */
class IntelligentInterfaceTelegramTest {

    @Test
    void shouldEncodeM1CounterClockwiseAndM2ClockwiseWithEx() {
        int motors = IntelligentInterfaceTelegram.withMotor(0, 0, IntelligentInterfaceTelegram.CCW);
        motors = IntelligentInterfaceTelegram.withMotor(motors, 1, IntelligentInterfaceTelegram.CW);
        assertArrayEquals(HexFormat.of().parseHex("C509"), IntelligentInterfaceTelegram.request(IntelligentInterfaceTelegram.ANALOG_EX, motors));
    }

    @Test
    void shouldDecodeDigitalInputsAndBigEndianAnalog() {
        byte[] reply = HexFormat.of().parseHex("0501F4");
        assertEquals(0b101, reply[0] & 0xFF, "E1 and E3 set");
        assertEquals(500, IntelligentInterfaceTelegram.analog(reply));
    }

    @Test
    void shouldEncodeAllOffDigitalRead() {
        assertArrayEquals(HexFormat.of().parseHex("C100"), IntelligentInterfaceTelegram.request(IntelligentInterfaceTelegram.DIGITAL, 0));
        assertEquals(1, IntelligentInterfaceTelegram.replyLength(IntelligentInterfaceTelegram.DIGITAL));
    }

    @Test
    void shouldReadMotorBitsPerMotorAndTreatBothBitsAsOff() {
        assertEquals(IntelligentInterfaceTelegram.CCW, IntelligentInterfaceTelegram.direction(0x09, 0));
        assertEquals(IntelligentInterfaceTelegram.CW, IntelligentInterfaceTelegram.direction(0x09, 1));
        assertEquals(0, IntelligentInterfaceTelegram.direction(0x09, 2));
        assertEquals(0, IntelligentInterfaceTelegram.direction(0xC0, 3), "both bits set: off");
        assertEquals(0x80, IntelligentInterfaceTelegram.withMotor(0xC0, 3, IntelligentInterfaceTelegram.CW), "replaces, not adds");
    }

    @Test
    void shouldKnowEveryCommandsLengthsAndRefuseOthers() {
        assertEquals(2, IntelligentInterfaceTelegram.requestLength(0xC9));
        assertEquals(3, IntelligentInterfaceTelegram.requestLength(0xC6));
        assertEquals(4, IntelligentInterfaceTelegram.replyLength(0xCA));
        assertEquals(2, IntelligentInterfaceTelegram.replyLength(0xC2));
        assertEquals(-1, IntelligentInterfaceTelegram.requestLength(0x42));
        assertThrows(IllegalArgumentException.class, () -> IntelligentInterfaceTelegram.replyLength(0x42));
    }

    @Test
    void shouldNameDigitalInputs() {
        assertEquals(0, IntelligentInterfaceTelegram.digitalInput("E1"));
        assertEquals(7, IntelligentInterfaceTelegram.digitalInput("E8"));
        assertEquals(-1, IntelligentInterfaceTelegram.digitalInput("EX"));
    }
}
