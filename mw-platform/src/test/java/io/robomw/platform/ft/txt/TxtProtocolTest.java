package io.robomw.platform.ft.txt;

import org.junit.jupiter.api.Test;

import java.util.HexFormat;

import static org.junit.jupiter.api.Assertions.assertArrayEquals;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * The TXT message table (shared/protocols/README.md section 4.4, ftrobopy's struct formats) byte
 * for byte: ids, sizes, fixed encodings, and round trips in both directions.
 */
class TxtProtocolTest {

    private static byte[] hex(String s) {
        return HexFormat.of().parseHex(s.replace(" ", ""));
    }

    private static String zeros(int bytes) {
        return "00".repeat(bytes);
    }

    /** An exchange: M1 forward at full power, M2 reverse at half, both 179 pulses, in step. */
    private static final String EXCHANGE_BYTES = "BA9735CC"
            + "0002 0000 0000 0001 0000 0000 0000 0000"
            + "0200 0100 0000 0000"
            + "B300 B300 0000 0000"
            + "0100 0100 0000 0000"
            + "0000 0000 0000 0000"
            + "0000 0000 0000 0000";

    private static TxtProtocol.Exchange exchange() {
        return new TxtProtocol.Exchange(new int[]{512, 0, 0, 256, 0, 0, 0, 0}, new int[]{2, 1, 0, 0}, new int[]{179, 179, 0, 0},
                new int[]{1, 1, 0, 0}, new int[4], 0, 0, 0);
    }

    /** A reply: I1 switch pressed, I2 57 cm, C1 179, C2 180, C4 at -1 (wrapped), M1 and M2 distance commands 1 done. */
    private static final String REPLY_BYTES = "41ACEF4E"
            + "0100 3900 0000 0000 0000 0000 0000 0000"
            + "0100 0000 0000 0000"
            + "B300 B400 0000 FFFF"
            + "0200 0000 0000 0000"
            + "0100 0100 0000 0000"
            + "0500"
            + zeros(25) + "00";

    private static TxtProtocol.ExchangeReply reply() {
        return new TxtProtocol.ExchangeReply(new int[]{1, 57, 0, 0, 0, 0, 0, 0}, new int[]{1, 0, 0, 0}, new int[]{179, 180, 0, -1},
                new int[]{2, 0, 0, 0}, new int[]{1, 1, 0, 0}, 5, new byte[TxtProtocol.IR_LENGTH]);
    }

    /** ftrobopy's configuration after ftrobopy(): every output a motor, every input a digital switch, counters mode 1. */
    private static final String CONFIG_BYTES = "7EF20E06" + "0100" + "0000" + "00" + "00" + "0000"
            + "01010101"
            + "01010000".repeat(8)
            + "01000000".repeat(4)
            + zeros(32);

    private static TxtProtocol.Config config() {
        return new TxtProtocol.Config(1, 0, new int[]{1, 1, 1, 1}, new int[]{1, 1, 1, 1, 1, 1, 1, 1}, new int[]{1, 1, 1, 1, 1, 1, 1, 1},
                new int[]{1, 1, 1, 1}, new int[16]);
    }

    @Test
    void shouldGiveEveryRequestOfTheTableItsLengthAndReply() {
        assertEquals(4, TxtProtocol.requestLength(0xDC21219AL));
        assertEquals(68, TxtProtocol.requestLength(0x163FF61DL));
        assertEquals(96, TxtProtocol.requestLength(0x060EF27EL));
        assertEquals(60, TxtProtocol.requestLength(0xCC3597BAL));
        assertEquals(4, TxtProtocol.requestLength(0x9BE5082CL));
        assertEquals(0xBAC9723EL, TxtProtocol.replyId(0xDC21219AL));
        assertEquals(0xCA689F75L, TxtProtocol.replyId(0x163FF61DL));
        assertEquals(0x9689A68CL, TxtProtocol.replyId(0x060EF27EL));
        assertEquals(0x4EEFAC41L, TxtProtocol.replyId(0xCC3597BAL));
        assertEquals(0xFBF600D2L, TxtProtocol.replyId(0x9BE5082CL));
        assertEquals(24, TxtProtocol.replyLength(TxtProtocol.QUERY_STATUS));
        assertEquals(4, TxtProtocol.replyLength(TxtProtocol.START_ONLINE));
        assertEquals(4, TxtProtocol.replyLength(TxtProtocol.UPDATE_CONFIG));
        assertEquals(80, TxtProtocol.replyLength(TxtProtocol.EXCHANGE));
        assertEquals(4, TxtProtocol.replyLength(TxtProtocol.STOP_ONLINE));
    }

    @Test
    void shouldRejectIdsOutsideTheTable() {
        assertEquals(-1, TxtProtocol.requestLength(0xFBC56F98L), "the compressed exchange is not used");
        assertEquals(-1, TxtProtocol.requestLength(TxtProtocol.EXCHANGE_REPLY), "a reply id is not a request");
        IllegalArgumentException e = assertThrows(IllegalArgumentException.class, () -> TxtProtocol.replyId(0x882A40A6L));
        assertTrue(e.getMessage().contains("0x882A40A6"), e.getMessage());
        assertThrows(IllegalArgumentException.class, () -> TxtProtocol.replyLength(0x12345678L));
    }

    @Test
    void shouldEncodeMessagesWithoutFieldsExactly() {
        assertArrayEquals(hex("9A2121DC"), TxtProtocol.queryStatus());
        assertArrayEquals(hex("1DF63F16" + zeros(64)), TxtProtocol.startOnline());
        assertArrayEquals(hex("2C08E59B"), TxtProtocol.stopOnline());
        assertArrayEquals(hex("759F68CA"), TxtProtocol.ack(TxtProtocol.START_ONLINE_REPLY));
        assertArrayEquals(hex("8CA68996"), TxtProtocol.ack(TxtProtocol.UPDATE_CONFIG_REPLY));
        assertArrayEquals(hex("D200F6FB"), TxtProtocol.ack(TxtProtocol.STOP_ONLINE_REPLY));
        assertThrows(IllegalArgumentException.class, () -> TxtProtocol.ack(TxtProtocol.EXCHANGE_REPLY));
    }

    @Test
    void shouldReadTheMessageIdLittleEndian() {
        assertEquals(TxtProtocol.EXCHANGE, TxtProtocol.messageId(hex(EXCHANGE_BYTES)));
        assertEquals(0xFFFF_FFFEL, TxtProtocol.messageId(hex("FEFFFFFF")), "unsigned, not negative");
        assertThrows(IllegalArgumentException.class, () -> TxtProtocol.messageId(hex("9A2121")));
    }

    @Test
    void shouldDecodeTheStatusReplyLikeFtrobopyServerSendsIt() {
        byte[] reply = hex("3E72C9BA" + "545832303133" + zeros(10) + "00000704");
        TxtProtocol.Status s = TxtProtocol.Status.decode(reply);
        assertEquals("TX2013", s.deviceName());
        assertEquals(0x04070000L, s.version());
        assertEquals("4.7.0", s.versionText());
        assertArrayEquals(reply, s.encode(), "and back");
    }

    @Test
    void shouldEncodeTheStatusReplyAndReadItBack() {
        TxtProtocol.Status s = new TxtProtocol.Status("TXT-emulator", 0x04060600L);
        byte[] bytes = s.encode();
        assertEquals(TxtProtocol.QUERY_STATUS_REPLY_LENGTH, bytes.length);
        assertEquals(s, TxtProtocol.Status.decode(bytes));
        assertEquals("4.6.6", s.versionText());
        assertThrows(IllegalArgumentException.class, () -> new TxtProtocol.Status("a name longer than 16", 1));
    }

    @Test
    void shouldEncodeFtrobopysDefaultConfigurationExactly() {
        assertArrayEquals(hex(CONFIG_BYTES), config().encode());
        assertEquals(TxtProtocol.UPDATE_CONFIG_LENGTH, hex(CONFIG_BYTES).length);
    }

    @Test
    void shouldRoundTripTheConfigurationBothWays() {
        TxtProtocol.Config c = new TxtProtocol.Config(-2, 1, new int[]{1, 0, 1, 0}, new int[]{1, 3, 0, 1, 1, 1, 1, 0},
                new int[]{1, 0, 0, 0, 1, 1, 1, 0}, new int[]{1, 1, 1, 1}, new int[]{0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, -15});
        assertEquals(c, TxtProtocol.Config.decode(c.encode()));
        byte[] bytes = hex(CONFIG_BYTES);
        assertArrayEquals(bytes, TxtProtocol.Config.decode(bytes).encode());
        TxtProtocol.Config ultrasonic = TxtProtocol.Config.decode(c.encode());
        assertEquals(3, ultrasonic.inputMode()[1]);
        assertEquals(0, ultrasonic.inputDigital()[1]);
    }

    @Test
    void shouldEncodeTheExchangeRequestExactly() {
        assertArrayEquals(hex(EXCHANGE_BYTES), exchange().encode());
        assertEquals(TxtProtocol.EXCHANGE_LENGTH, hex(EXCHANGE_BYTES).length);
    }

    @Test
    void shouldRoundTripTheExchangeRequestBothWays() {
        TxtProtocol.Exchange x = exchange();
        assertEquals(x, TxtProtocol.Exchange.decode(x.encode()));
        TxtProtocol.Exchange sound = new TxtProtocol.Exchange(new int[8], new int[4], new int[4], new int[]{7, 0, 0, 0}, new int[]{0, 0, 0, 3},
                2, 26, 65535);
        assertEquals(sound, TxtProtocol.Exchange.decode(sound.encode()), "unsigned sound fields survive");
        byte[] bytes = hex(EXCHANGE_BYTES);
        assertArrayEquals(bytes, TxtProtocol.Exchange.decode(bytes).encode());
    }

    @Test
    void shouldDecodeTheExchangeReply() {
        TxtProtocol.ExchangeReply r = TxtProtocol.ExchangeReply.decode(hex(REPLY_BYTES));
        assertEquals(1, r.input(0), "I1 pressed");
        assertEquals(57, r.input(1), "I2 57 cm");
        assertArrayEquals(new int[]{179, 180, 0, -1}, r.counterValue(), "counter values are signed 16-bit");
        assertArrayEquals(new int[]{2, 0, 0, 0}, r.counterCmdId());
        assertArrayEquals(new int[]{1, 1, 0, 0}, r.motorCmdId());
        assertEquals(5, r.soundCmdId());
        assertEquals(reply(), r);
    }

    @Test
    void shouldRoundTripTheExchangeReplyBothWays() {
        assertArrayEquals(hex(REPLY_BYTES), reply().encode());
        byte[] ir = new byte[TxtProtocol.IR_LENGTH];
        ir[0] = -15;
        ir[24] = 3;
        TxtProtocol.ExchangeReply r = new TxtProtocol.ExchangeReply(new int[]{10000, 15000, 1023, 0, 0, 0, 0, -1}, new int[]{0, 1, 0, 1},
                new int[]{32767, -32768, 1, 2}, new int[]{7, 6, 5, 4}, new int[]{3, 2, 1, 0}, 15, ir);
        assertEquals(r, TxtProtocol.ExchangeReply.decode(r.encode()));
    }

    @Test
    void shouldRejectMessagesOfTheWrongLengthOrId() {
        byte[] bytes = hex(REPLY_BYTES);
        IllegalArgumentException shortReply = assertThrows(IllegalArgumentException.class,
                () -> TxtProtocol.ExchangeReply.decode(java.util.Arrays.copyOf(bytes, 79)));
        assertTrue(shortReply.getMessage().contains("80 bytes, got 79"), shortReply.getMessage());
        IllegalArgumentException wrongId = assertThrows(IllegalArgumentException.class, () -> TxtProtocol.Exchange.decode(
                hex("00000000" + zeros(56))));
        assertTrue(wrongId.getMessage().contains("0xCC3597BA"), wrongId.getMessage());
        assertThrows(IllegalArgumentException.class, () -> TxtProtocol.Config.decode(hex(EXCHANGE_BYTES)));
        assertThrows(IllegalArgumentException.class, () -> TxtProtocol.Status.decode(TxtProtocol.queryStatus()));
    }

    @Test
    void shouldRejectFieldArraysOfTheWrongSize() {
        IllegalArgumentException e = assertThrows(IllegalArgumentException.class, () -> new TxtProtocol.Exchange(new int[4], new int[4],
                new int[4], new int[4], new int[4], 0, 0, 0));
        assertTrue(e.getMessage().contains("pwm has 8 entries, got 4"), e.getMessage());
        assertThrows(IllegalArgumentException.class, () -> new TxtProtocol.ExchangeReply(new int[8], new int[4], new int[4], new int[4],
                new int[4], 0, new byte[24]));
    }

    @Test
    void shouldCopyFieldArraysSoMessagesStayUnchanged() {
        int[] pwm = {512, 0, 0, 0, 0, 0, 0, 0};
        TxtProtocol.Exchange x = new TxtProtocol.Exchange(pwm, new int[4], new int[4], new int[4], new int[4], 0, 0, 0);
        pwm[0] = 0;
        x.pwm()[0] = 1;
        assertEquals(512, x.pwm()[0]);
    }
    @Test
    void aStatusWhoseNameIsNotUtf8IsReadByteByByteAndKeepsItsSixteenBytes() {
        // Found by fuzzing (BrickRepliesFuzzTest#txtReply): 0xFF decoded as a replacement character took 3 bytes,
        // and the name no longer fitted its 16, so the driver's handshake failed with an IllegalArgumentException.
        byte[] reply = new TxtProtocol.Status("TXT-emulator", 0x04060600L).encode();
        reply[4 + 3] = (byte) 0xFF;
        TxtProtocol.Status s = TxtProtocol.Status.decode(reply);
        assertEquals("TXT?emulator", s.deviceName());
        assertEquals(0x04060600L, s.version());
        byte[] utf8 = new TxtProtocol.Status("TXT-été", 1).encode();
        assertEquals("TXT-été", TxtProtocol.Status.decode(utf8).deviceName(), "a UTF-8 name as it is");
    }
}
