package io.robomw.platform.nxt;

import io.robomw.platform.brick.LittleEndian;
import org.junit.jupiter.api.Test;

import java.util.Arrays;
import java.util.HexFormat;
import java.util.List;
import java.util.Set;

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
        assertArrayEquals(hex("8004004b0701002068010000"), NxtTelegram.setOutputState(false,
                OutputState.running(0, 75, OutputState.Regulation.SPEED, 360)));
    }

    @Test
    void shouldEncodeNegativePowerAndTurnAndFullLimitLikeNxtPython() {
        assertArrayEquals(hex("8004 01 9c 01 00 fb 20 01020304"), NxtTelegram.setOutputState(false, new OutputState(1, -100,
                Set.of(OutputState.Mode.MOTORON), OutputState.Regulation.IDLE, -5, OutputState.RunState.RUNNING, 0x04030201L)));
    }

    /** The three telegrams of a move on two wheels, as the review's walk shows them on the wire (shared/protocols §1.3, §1.4). */
    @Test
    void shouldEncodeTheDriversRunBrakeAndCoastStatesByteForByte() {
        assertArrayEquals(hex("0C00 0004 01 2D 07 02 00 20 FF030000"), NxtTelegram.withLengthPrefix(NxtTelegram.setOutputState(true,
                OutputState.running(1, 45, OutputState.Regulation.SYNC, 1023))), "B at power 45, in step, limit 1023°");
        assertArrayEquals(hex("0C00 0004 02 00 07 01 00 20 00000000"), NxtTelegram.withLengthPrefix(NxtTelegram.setOutputState(true,
                OutputState.braked(2))), "C held at power 0");
        assertArrayEquals(hex("0C00 0004 00 00 00 00 00 00 00000000"), NxtTelegram.withLengthPrefix(NxtTelegram.setOutputState(true,
                OutputState.coasting(0))), "A idle, as closing leaves it");
    }

    @Test
    void shouldGiveEveryModeRegulationAndRunStateTheFirmwaresByte() {
        assertEquals(List.of(0x01, 0x02, 0x04), Arrays.stream(OutputState.Mode.values()).map(OutputState.Mode::bit).toList());
        assertEquals(List.of(0x00, 0x01, 0x02, 0x04), Arrays.stream(OutputState.Regulation.values()).map(OutputState.Regulation::code).toList());
        assertEquals(List.of(0x00, 0x10, 0x20, 0x40), Arrays.stream(OutputState.RunState.values()).map(OutputState.RunState::code).toList());
        assertEquals(Set.of(OutputState.Mode.MOTORON, OutputState.Mode.REGULATED), OutputState.Mode.fromBits(0xF5),
                "the enhanced firmware's top nibble is not a mode of the standard one");
    }

    @Test
    void shouldRefuseCodesTheFirmwareDoesNotHaveNamingThem() {
        IllegalArgumentException run = assertThrows(IllegalArgumentException.class, () -> OutputState.RunState.fromCode(0x30));
        assertTrue(run.getMessage().contains("0x30"), run.getMessage());
        IllegalArgumentException regulation = assertThrows(IllegalArgumentException.class, () -> OutputState.Regulation.fromCode(3));
        assertTrue(regulation.getMessage().contains("0x03"), regulation.getMessage());
        IllegalArgumentException mode = assertThrows(IllegalArgumentException.class, () -> OutputState.Mode.fromBits(0x09));
        assertTrue(mode.getMessage().contains("0x08"), mode.getMessage());
        IllegalArgumentException power = assertThrows(IllegalArgumentException.class, () -> OutputState.running(1, 101, OutputState.Regulation.SPEED, 0));
        assertTrue(power.getMessage().contains("101"), power.getMessage());
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
        assertEquals(NxtTelegram.GETOUTPUTSTATE, NxtTelegram.opcode(reply));
        assertEquals(NxtStatus.SUCCESS, NxtTelegram.status(reply));
        NxtTelegram.OutputReading r = NxtTelegram.outputReading(reply);
        assertEquals(OutputState.running(0, 75, OutputState.Regulation.SPEED, 360), r.state(), "what SETOUTPUTSTATE set");
        assertEquals(1234, r.tachoCount());
        assertEquals(1234, r.blockTachoCount());
        assertEquals(1234, r.rotationCount());
    }

    @Test
    void shouldRefuseAGetOutputStateReplyThatIsTooShortOrCarriesAnUnknownRunState() {
        assertThrows(IllegalArgumentException.class, () -> NxtTelegram.outputReading(hex("020600004b07010020")));
        IllegalArgumentException e = assertThrows(IllegalArgumentException.class,
                () -> NxtTelegram.outputReading(hex("020600004b0701003068010000d2040000d2040000d2040000")));
        assertTrue(e.getMessage().contains("run state 0x30"), e.getMessage());
    }

    @Test
    void shouldDecodeGetInputValuesReply() {
        byte[] reply = hex("0207000001000120b700b7000100b700");
        int d = NxtTelegram.DATA_OFFSET;
        assertEquals(NxtTelegram.GETINPUTVALUES_REPLY, reply.length);
        assertEquals(1, reply[d + NxtTelegram.IN_VALID], "valid");
        assertEquals(183, LittleEndian.u16(reply, d + NxtTelegram.IN_RAW), "raw");
        assertEquals(183, LittleEndian.u16(reply, d + NxtTelegram.IN_NORMALIZED), "normalized");
        assertEquals(1, LittleEndian.s16(reply, d + NxtTelegram.IN_SCALED), "scaled");
    }

    @Test
    void shouldDecodeBatteryKeepAliveAndUltrasonicReplies() {
        int d = NxtTelegram.DATA_OFFSET;
        assertEquals(8123, LittleEndian.u16(hex("020b00bb1f"), d + NxtTelegram.BATTERY_MILLIVOLTS));
        assertEquals(600_000, LittleEndian.u32(hex("020d00c0270900"), d + NxtTelegram.SLEEP_LIMIT_MILLIS));
        byte[] lsRead = hex("02 10 00 01 2A 000000000000000000000000000000");
        assertEquals(NxtTelegram.LSREAD_REPLY, lsRead.length);
        assertEquals(1, lsRead[d + NxtTelegram.LS_BYTES_READ], "one byte read");
        assertEquals(42, lsRead[d + NxtTelegram.LS_DATA] & 0xFF, "42 cm");
        assertEquals(NxtStatus.PENDING, NxtTelegram.status(hex("02 0E 20 00")), "pending");
        assertEquals(1, hex("02 0E 00 01")[d + NxtTelegram.LS_BYTES_READY], "one byte ready");
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
