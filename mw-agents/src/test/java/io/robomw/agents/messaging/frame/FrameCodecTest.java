package io.robomw.agents.messaging.frame;

import io.robomw.agents.messaging.DropReason;
import org.junit.jupiter.api.Test;

import java.nio.charset.StandardCharsets;
import java.util.Arrays;
import java.util.HexFormat;
import java.util.List;
import java.util.UUID;

import static org.junit.jupiter.api.Assertions.assertArrayEquals;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

class FrameCodecTest {

    private static final int MAX = 1 << 20;

    private static Frame sample(byte[] payload) {
        return new Frame(FrameKind.PUBLISH, 5, 0x1122334455667788L, 9, new UUID(1, 2), 1_000_000L, "a", "b", "t", "f", 2, payload, false);
    }

    @Test
    void shouldEncodeTheDocumentedLayout() {
        byte[] bytes = FrameCodec.encode(sample("xy".getBytes(StandardCharsets.UTF_8)), false);
        String expected = "524d" + "01" + "04" + "0000004e" + "0000000000000005"
                + "00" + "02" + "0001" + "0001" + "0001" + "0001" + "0000" + "00000002"
                + "1122334455667788" + "0000000000000009" + "0000000000000001" + "0000000000000002" + "00000000000f4240"
                + "61" + "62" + "74" + "66" + "7879";
        assertEquals(expected, HexFormat.of().formatHex(bytes));
    }

    @Test
    void shouldDecodeWhatItEncodes() throws FrameException {
        Frame f = sample(new byte[] {1, 2, 3});
        Frame back = FrameCodec.decode(FrameCodec.encode(f, false), 0, FrameCodec.encode(f, false).length, MAX);
        assertEquals(f.kind(), back.kind());
        assertEquals(f.source(), back.source());
        assertEquals(f.correlationId(), back.correlationId());
        assertEquals("t", back.topic());
        assertArrayEquals(f.payload(), back.payload());
    }

    @Test
    void aReadingThreadsNameCacheGivesEachFrameItsOwnNames() throws FrameException {
        NameCache names = new NameCache(n -> n.equals("left") ? "left" : n); // "left" as the node registered it
        String[][] sent = {{"a", "left", "fn"}, {"a", "left", "fn"}, {"b", "righ", "fn"}, {"a", "left", "gn"}, {"a", "left", "fn"}, {"", "", ""}};
        for (String[] n : sent) {
            Frame f = new Frame(FrameKind.PUBLISH, 1, 2, 3, new UUID(2, 3), 4, n[0], "", n[1], n[2], 1, new byte[] {9}, false);
            byte[] bytes = FrameCodec.encode(f, false);
            Frame back = FrameCodec.decode(bytes, 0, bytes.length, MAX, names);
            assertEquals(List.of(n[0], n[1], n[2]), List.of(back.sender(), back.topic(), back.function()));
            if (n[1].equals("left")) {
                assertTrue(back.topic() == "left", "the topic decoded is the String it is registered under");
            }
        }
    }

    @Test
    void shouldReserveAndFlagTheMac() throws FrameException {
        byte[] bytes = FrameCodec.encode(sample(new byte[0]), true);
        assertEquals(FrameCodec.HEADER_LENGTH + 4 + FrameCodec.MAC_LENGTH, bytes.length);
        assertTrue(FrameCodec.decode(bytes, 0, bytes.length, MAX).authenticated());
    }

    @Test
    void shouldRejectATruncatedFrame() {
        byte[] bytes = FrameCodec.encode(sample(new byte[10]), false);
        FrameException e = assertThrows(FrameException.class, () -> FrameCodec.decode(bytes, 0, bytes.length - 1, MAX));
        assertEquals(DropReason.TRUNCATED, e.reason());
    }

    @Test
    void shouldRejectAFrameAboveTheMaximum() {
        byte[] bytes = FrameCodec.encode(sample(new byte[2000]), false);
        FrameException e = assertThrows(FrameException.class, () -> FrameCodec.decode(bytes, 0, bytes.length, 1024));
        assertEquals(DropReason.OVERSIZED, e.reason());
    }

    @Test
    void shouldAcceptAFrameAtExactlyTheMaximum() throws FrameException {
        byte[] bytes = FrameCodec.encode(sample(new byte[1024 - FrameCodec.HEADER_LENGTH - 4]), false);
        assertEquals(1024, bytes.length);
        assertEquals(1024, FrameCodec.decode(bytes, 0, bytes.length, 1024).payload().length + FrameCodec.HEADER_LENGTH + 4);
    }

    @Test
    void shouldRejectWrongMagic() {
        byte[] bytes = FrameCodec.encode(sample(new byte[0]), false);
        bytes[0] = 'X';
        assertEquals(DropReason.MALFORMED, assertThrows(FrameException.class, () -> FrameCodec.decode(bytes, 0, bytes.length, MAX)).reason());
    }

    @Test
    void shouldRejectLengthsThatDoNotAddUp() {
        byte[] bytes = FrameCodec.encode(sample(new byte[4]), false);
        bytes[FrameCodec.TOPIC_LENGTH_OFFSET + 1] = 3;
        assertEquals(DropReason.MALFORMED, assertThrows(FrameException.class, () -> FrameCodec.decode(bytes, 0, bytes.length, MAX)).reason());
    }

    @Test
    void shouldRejectAnUnknownKind() {
        byte[] bytes = FrameCodec.encode(sample(new byte[0]), false);
        bytes[FrameCodec.KIND_OFFSET] = 99;
        assertEquals(DropReason.MALFORMED, assertThrows(FrameException.class, () -> FrameCodec.decode(bytes, 0, bytes.length, MAX)).reason());
    }

    @org.junit.jupiter.params.ParameterizedTest
    @org.junit.jupiter.params.provider.EnumSource(FrameKind.class)
    void shouldWriteEveryKindAsTheCodeOfTheTableAndReadItBack(FrameKind kind) throws FrameException {
        java.util.Map<FrameKind, Integer> table = java.util.Map.ofEntries(java.util.Map.entry(FrameKind.MESSAGE, 1),
                java.util.Map.entry(FrameKind.REPLY, 2), java.util.Map.entry(FrameKind.ERROR, 3), java.util.Map.entry(FrameKind.PUBLISH, 4),
                java.util.Map.entry(FrameKind.SUBSCRIBE, 5), java.util.Map.entry(FrameKind.UNSUBSCRIBE, 6), java.util.Map.entry(FrameKind.KEEPALIVE, 7),
                java.util.Map.entry(FrameKind.SHM_ASK, 8), java.util.Map.entry(FrameKind.SHM_OFFER, 9), java.util.Map.entry(FrameKind.SHM_ACCEPT, 10),
                java.util.Map.entry(FrameKind.PUBLISH_SHARED, 11));
        Frame f = new Frame(kind, 5, 1, 9, new UUID(1, 2), 1_000_000L, "a", "b", "t", "f", 2, new byte[0], false);
        byte[] bytes = FrameCodec.encode(f, false);
        assertEquals(table.get(kind), bytes[FrameCodec.KIND_OFFSET] & 0xFF);
        assertEquals(kind, FrameCodec.decode(bytes, 0, bytes.length, MAX).kind());
    }

    @Test
    void shouldNameAnUnknownKindCode() {
        byte[] bytes = FrameCodec.encode(sample(new byte[0]), false);
        bytes[FrameCodec.KIND_OFFSET] = (byte) 0xAB;
        FrameException e = assertThrows(FrameException.class, () -> FrameCodec.decode(bytes, 0, bytes.length, MAX));
        assertTrue(e.getMessage().contains("unknown frame kind code 171"), e.getMessage());
    }

    @Test
    void shouldDecodeAFrameInTheMiddleOfABuffer() throws FrameException {
        byte[] frame = FrameCodec.encode(sample(new byte[] {7}), false);
        byte[] buf = new byte[frame.length + 20];
        System.arraycopy(frame, 0, buf, 10, frame.length);
        assertEquals(7, FrameCodec.decode(buf, 10, frame.length, MAX).payload()[0]);
        assertEquals(frame.length, FrameCodec.declaredLength(Arrays.copyOfRange(buf, 10, 18), 0, MAX));
    }
}
