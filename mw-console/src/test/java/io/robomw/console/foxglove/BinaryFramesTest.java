package io.robomw.console.foxglove;

import org.junit.jupiter.api.Test;

import java.nio.ByteBuffer;
import java.nio.charset.StandardCharsets;
import java.util.HexFormat;

import static org.junit.jupiter.api.Assertions.assertArrayEquals;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/** The binary frames, byte for byte as the protocol writes them (the bytes here are written from the specification, not by the encoder). */
class BinaryFramesTest {

    private static byte[] bytes(ByteBuffer b) {
        byte[] a = new byte[b.remaining()];
        b.duplicate().get(a);
        return a;
    }

    private static byte[] hex(String h) {
        return HexFormat.of().parseHex(h.replace(" ", ""));
    }

    @Test
    void messageDataIsOpcodeSubscriptionLogTimeAndPayloadLittleEndian() {
        byte[] payload = "{\"x\":1}".getBytes(StandardCharsets.UTF_8);
        byte[] expected = hex("01 2a000000 0807060504030201 7b2278223a317d");
        assertArrayEquals(expected, bytes(BinaryFrames.messageData(42, 0x0102030405060708L, payload)));
    }

    @Test
    void aSubscriptionIdAboveTwoToTheThirtyOneIsWrittenUnsigned() {
        assertArrayEquals(hex("01 feffffff 0000000000000000"), bytes(BinaryFrames.messageData(0xFFFF_FFFEL, 0, new byte[0])));
        assertThrows(IllegalArgumentException.class, () -> BinaryFrames.messageData(1L << 32, 0, new byte[0]));
        assertThrows(IllegalArgumentException.class, () -> BinaryFrames.messageData(-1, 0, new byte[0]));
    }

    @Test
    void timeIsOpcodeTwoAndNanoseconds() {
        assertArrayEquals(hex("02 00e40b5402000000"), bytes(BinaryFrames.time(10_000_000_000L)));
    }

    @Test
    void aClientMessageCarriesItsChannelAndPayload() throws Exception {
        BinaryFrames.ClientMessage m = BinaryFrames.parseClient(ByteBuffer.wrap(hex("01 07000080 7b7d")));
        assertEquals(0x8000_0007L, m.channelId());
        assertArrayEquals("{}".getBytes(StandardCharsets.UTF_8), m.payload());
    }

    @Test
    void aClientMessageWithAnEmptyPayloadIsFiveBytes() throws Exception {
        BinaryFrames.ClientMessage m = BinaryFrames.parseClient(ByteBuffer.wrap(hex("01 03000000")));
        assertEquals(3, m.channelId());
        assertEquals(0, m.payload().length);
    }

    @Test
    void parsingLeavesTheBufferAsItWas() throws Exception {
        ByteBuffer b = ByteBuffer.wrap(hex("01 03000000 7b7d"));
        BinaryFrames.parseClient(b);
        assertEquals(0, b.position());
    }

    @Test
    void anEmptyFrameIsRefused() {
        ClientRequest.BadRequest e = assertThrows(ClientRequest.BadRequest.class, () -> BinaryFrames.parseClient(ByteBuffer.allocate(0)));
        assertTrue(e.getMessage().startsWith("Empty binary message"), e.getMessage());
    }

    @Test
    void aShortFrameIsRefusedSayingHowLongItWas() {
        ClientRequest.BadRequest e = assertThrows(ClientRequest.BadRequest.class, () -> BinaryFrames.parseClient(ByteBuffer.wrap(hex("01 0300"))));
        assertTrue(e.getMessage().startsWith("Buffer too short") && e.getMessage().endsWith("got 3"), e.getMessage());
    }

    @Test
    void anUnknownOpcodeIsRefusedByNumber() {
        ClientRequest.BadRequest e = assertThrows(ClientRequest.BadRequest.class, () -> BinaryFrames.parseClient(ByteBuffer.wrap(hex("ff 00"))));
        assertTrue(e.getMessage().startsWith("Unknown binary opcode 255 (0xff)"), e.getMessage());
    }

    @Test
    void serviceCallsAndPlaybackControlAreKnownButNotServed() {
        assertEquals("Server does not support services",
                assertThrows(ClientRequest.BadRequest.class, () -> BinaryFrames.parseClient(ByteBuffer.wrap(hex("02 01000000")))).getMessage());
        assertEquals("Server does not support playback control capability",
                assertThrows(ClientRequest.BadRequest.class, () -> BinaryFrames.parseClient(ByteBuffer.wrap(hex("03 00")))).getMessage());
    }

    @Test
    void everyClientOpcodeHasItsOwnCode() throws Exception {
        for (BinaryFrames.ClientOpcode op : BinaryFrames.ClientOpcode.values()) {
            assertEquals(op, BinaryFrames.ClientOpcode.fromCode(op.code()));
        }
        assertEquals(1, BinaryFrames.ClientOpcode.MESSAGE_DATA.code());
        assertEquals(2, BinaryFrames.ClientOpcode.SERVICE_CALL_REQUEST.code());
        assertEquals(3, BinaryFrames.ClientOpcode.PLAYBACK_CONTROL_REQUEST.code());
    }
}
