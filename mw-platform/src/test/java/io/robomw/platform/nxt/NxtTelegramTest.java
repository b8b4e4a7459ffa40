package io.robomw.platform.nxt;

import io.robomw.platform.brick.LittleEndian;
import org.junit.jupiter.api.Test;

import java.util.HexFormat;

import static org.junit.jupiter.api.Assertions.assertArrayEquals;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/** The byte examples of the protocol notes (shared/protocols/README.md, sections 1.6 and 1.7), exactly. */
class NxtTelegramTest {

    private static byte[] hex(String s) {
        return HexFormat.of().parseHex(s.replace(" ", ""));
    }

    @Test
    void shouldEncodeSetOutputStateLikeTheFirmwareExample() {
        assertArrayEquals(hex("8004004b0701002068010000"), NxtTelegram.setOutputState(false, 0, 75,
                NxtTelegram.MODE_MOTORON | NxtTelegram.MODE_BRAKE | NxtTelegram.MODE_REGULATED, NxtTelegram.REGULATION_SPEED, 0,
                NxtTelegram.RUN_RUNNING, 360));
    }

    @Test
    void shouldEncodeNegativePowerAndTurnAndFullLimitLikeNxtPython() {
        assertArrayEquals(hex("8004 01 9c 01 00 fb 20 01020304"), NxtTelegram.setOutputState(false, 1, -100, NxtTelegram.MODE_MOTORON,
                NxtTelegram.REGULATION_IDLE, -5, NxtTelegram.RUN_RUNNING, 0x04030201L));
    }

    @Test
    void shouldEncodeTheOtherDocumentedRequests() {
        assertArrayEquals(hex("000600"), NxtTelegram.getOutputState(0));
        assertArrayEquals(hex("8005000120"), NxtTelegram.setInputMode(false, 0, NxtTelegram.TYPE_SWITCH, NxtTelegram.MODE_BOOLEAN));
        assertArrayEquals(hex("000700"), NxtTelegram.getInputValues(0));
        assertArrayEquals(hex("8003b801f401"), NxtTelegram.playTone(false, 440, 500));
        assertArrayEquals(hex("000a0000"), NxtTelegram.resetMotorPosition(true, 0, false));
        assertArrayEquals(hex("000b"), NxtTelegram.getBatteryLevel());
        assertArrayEquals(hex("000d"), NxtTelegram.keepAlive());
        assertArrayEquals(hex("000a0101"), NxtTelegram.resetMotorPosition(true, 1, true), "block tacho count of B");
        assertArrayEquals(hex("002102"), NxtTelegram.updateResetCount(true, 2), "UPDATE_RESET_COUNT (0x21) of C, as c_cmd.iom numbers it");
    }

    @Test
    void shouldEncodeTheUltrasonicSequenceWithLengthPrefixes() {
        assertArrayEquals(hex("05 00 80 05 03 0B 00"), NxtTelegram.withLengthPrefix(
                NxtTelegram.setInputMode(false, 3, NxtTelegram.TYPE_LOWSPEED_9V, NxtTelegram.MODE_RAW)));
        assertArrayEquals(hex("07 00 00 0F 03 02 01 02 42"), NxtTelegram.withLengthPrefix(NxtTelegram.lsWrite(true, 3, 1, (byte) 0x02, (byte) 0x42)));
        assertArrayEquals(hex("03 00 00 0E 03"), NxtTelegram.withLengthPrefix(NxtTelegram.lsGetStatus(3)));
        assertArrayEquals(hex("03 00 00 10 03"), NxtTelegram.withLengthPrefix(NxtTelegram.lsRead(3)));
    }

    @Test
    void shouldDecodeGetOutputStateReply() {
        byte[] reply = hex("020600004b0701002068010000d2040000d2040000d2040000");
        assertEquals(NxtTelegram.GETOUTPUTSTATE_REPLY, reply.length);
        assertEquals(75, reply[4]);
        assertEquals(360, LittleEndian.u32(reply, 9), "tacho limit");
        assertEquals(1234, LittleEndian.s32(reply, 13), "tacho count");
        assertEquals(1234, LittleEndian.s32(reply, 17), "block tacho count");
        assertEquals(1234, LittleEndian.s32(reply, 21), "rotation count");
    }

    @Test
    void shouldDecodeGetInputValuesReply() {
        byte[] reply = hex("0207000001000120b700b7000100b700");
        assertEquals(NxtTelegram.GETINPUTVALUES_REPLY, reply.length);
        assertEquals(1, reply[4], "valid");
        assertEquals(183, LittleEndian.u16(reply, 8), "raw");
        assertEquals(183, LittleEndian.u16(reply, 10), "normalized");
        assertEquals(1, LittleEndian.s16(reply, 12), "scaled");
    }

    @Test
    void shouldDecodeBatteryKeepAliveAndUltrasonicReplies() {
        assertEquals(8123, LittleEndian.u16(hex("020b00bb1f"), 3));
        assertEquals(600_000, LittleEndian.u32(hex("020d00c0270900"), 3));
        byte[] lsRead = hex("1400 02 10 00 01 2A 000000000000000000000000000000");
        assertEquals(NxtTelegram.LSREAD_REPLY, LittleEndian.u16(lsRead, 0));
        assertEquals(42, lsRead[6] & 0xFF, "42 cm");
        assertEquals(0x20, hex("04 00 02 0E 20 00")[4], "pending");
    }

    @Test
    void shouldRefuseI2cTransactionsLongerThanSixteenBytes() {
        assertThrows(IllegalArgumentException.class, () -> NxtTelegram.lsWrite(true, 0, 1, new byte[17]));
    }

    @Test
    void shouldMapSpeedsToPowerAndPortsToOutputs() {
        assertEquals(50, NxtMotorDriver.power(450));
        assertEquals(-100, NxtMotorDriver.power(-5000));
        assertEquals(2, NxtMotorDriver.outputPort("C"));
        assertEquals(3, NxtSensorPlatform.inputPort("S4"));
        IllegalArgumentException e = assertThrows(IllegalArgumentException.class, () -> NxtMotorDriver.outputPort("D"));
        assertTrue(e.getMessage().contains("A, B and C"));
    }

    @Test
    void shouldNameCommandPortAndStatusInErrors() {
        NxtException e = new NxtException("nxt-1", NxtTelegram.GETOUTPUTSTATE, 5, 0xC0);
        assertTrue(e.getMessage().contains("GETOUTPUTSTATE") && e.getMessage().contains("port 5") && e.getMessage().contains("0xC0"), e.getMessage());
    }
}
