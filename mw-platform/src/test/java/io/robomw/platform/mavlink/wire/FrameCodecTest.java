package io.robomw.platform.mavlink.wire;

import org.junit.jupiter.api.Test;

import java.time.Instant;
import java.time.InstantSource;
import java.util.ArrayList;
import java.util.Arrays;
import java.util.HexFormat;
import java.util.List;

import static org.junit.jupiter.api.Assertions.assertArrayEquals;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

/** The byte examples of the MAVLink facts (shared/protocols/mavlink.md §1.1, checked there with pymavlink 2.4.50), and the decoder's rules. */
class FrameCodecTest {

    private static final HexFormat HEX = HexFormat.ofDelimiter(" ");
    /** HEARTBEAT(type 2, autopilot 3, base_mode 0x81, custom_mode 4, status 4, version 3) from 1/1, seq 0. */
    static final byte[] HEARTBEAT = HEX.parseHex("fd 09 00 00 00 01 01 00 00 00 04 00 00 00 02 03 81 04 03 03 56");
    /** COMMAND_ACK(400, ACCEPTED) cut to two payload bytes. */
    static final byte[] COMMAND_ACK = HEX.parseHex("fd 02 00 00 00 01 01 4d 00 00 90 01 a0 58");
    /** An all-zero HEARTBEAT: one payload byte stays. */
    static final byte[] ZERO_HEARTBEAT = HEX.parseHex("fd 01 00 00 00 01 01 00 00 00 00 d5 2c");
    /** HEARTBEAT signed with SHA-256("robomw"), link 0, timestamp 1000. */
    static final byte[] SIGNED_HEARTBEAT = HEX.parseHex(
            "fd 09 01 00 00 01 01 00 00 00 04 00 00 00 02 03 81 04 03 e4 ae 00 e8 03 00 00 00 00 ef b5 2d 04 26 16");

    static Payload heartbeat() {
        return Payload.of(Messages.Heartbeat.MESSAGE).set(Messages.Heartbeat.TYPE, 2).set(Messages.Heartbeat.AUTOPILOT, 3)
                .set(Messages.Heartbeat.BASE_MODE, 0x81).set(Messages.Heartbeat.CUSTOM_MODE, 4).set(Messages.Heartbeat.SYSTEM_STATUS, 4)
                .set(Messages.Heartbeat.MAVLINK_VERSION, 3);
    }

    private static List<Frame> decode(byte[]... chunks) {
        List<Frame> out = new ArrayList<>();
        FrameDecoder d = new FrameDecoder(out::add);
        for (byte[] c : chunks) {
            d.feed(c);
        }
        return out;
    }

    private static byte[] concat(byte[]... parts) {
        int n = Arrays.stream(parts).mapToInt(p -> p.length).sum();
        byte[] all = new byte[n];
        int at = 0;
        for (byte[] p : parts) {
            System.arraycopy(p, 0, all, at, p.length);
            at += p.length;
        }
        return all;
    }

    @Test
    void heartbeatEncodesToTheKnownAnswer() {
        assertArrayEquals(HEARTBEAT, new FrameEncoder(1, 1).encode(heartbeat()));
    }

    @Test
    void commandAckIsCutToItsTwoNonZeroBytes() {
        Payload ack = Payload.of(Messages.CommandAck.MESSAGE).set(Messages.CommandAck.COMMAND, MavCmd.COMPONENT_ARM_DISARM.code())
                .set(Messages.CommandAck.RESULT, MavResult.ACCEPTED.code());
        assertArrayEquals(COMMAND_ACK, new FrameEncoder(1, 1).encode(ack));
    }

    @Test
    void anAllZeroPayloadKeepsItsFirstByte() {
        assertArrayEquals(ZERO_HEARTBEAT, new FrameEncoder(1, 1).encode(Payload.of(Messages.Heartbeat.MESSAGE)));
    }

    @Test
    void signedHeartbeatIsTheKnownAnswer() {
        Signer signer = new Signer(SigningKey.fromPassphrase("robomw"), 0, InstantSource.fixed(Instant.EPOCH)).startingAt(1000);
        assertArrayEquals(SIGNED_HEARTBEAT, new FrameEncoder(1, 1).signWith(signer).encode(heartbeat()));
    }

    @Test
    void sequenceNumbersCountAndWrapAt256() {
        FrameEncoder e = new FrameEncoder(1, 1);
        for (int i = 0; i < 300; i++) {
            byte[] f = e.encode(heartbeat());
            assertEquals(i % 256, f[Framing.SEQ] & 0xFF);
        }
    }

    @Test
    void aCutPayloadIsZeroExtendedWhenRead() {
        List<Frame> frames = decode(COMMAND_ACK);
        assertEquals(1, frames.size());
        Frame f = frames.get(0);
        assertEquals(2, f.payloadLength());
        Payload p = f.payload();
        assertEquals(400, p.getLong(Messages.CommandAck.COMMAND));
        assertEquals(0, p.getLong(Messages.CommandAck.RESULT));
        assertEquals(0, p.getLong(Messages.CommandAck.TARGET_SYSTEM));
        assertEquals(Messages.CommandAck.MESSAGE.maxLength(), p.bytes().length);
    }

    @Test
    void theKnownAnswersDecodeToTheirFields() {
        List<Frame> frames = decode(concat(HEARTBEAT, ZERO_HEARTBEAT, SIGNED_HEARTBEAT));
        assertEquals(3, frames.size());
        Payload hb = frames.get(0).payload();
        assertEquals(2, hb.getLong(Messages.Heartbeat.TYPE));
        assertEquals(0x81, hb.getLong(Messages.Heartbeat.BASE_MODE));
        assertEquals(4, hb.getLong(Messages.Heartbeat.CUSTOM_MODE));
        assertEquals(0, frames.get(1).payload().getLong(Messages.Heartbeat.MAVLINK_VERSION));
        Frame signed = frames.get(2);
        assertTrue(signed.signed());
        assertEquals(1000, signed.signature().orElseThrow().timestamp());
        assertEquals(0, signed.signature().orElseThrow().linkId());
        assertEquals(hb.toString(), signed.payload().toString());
    }

    @Test
    void aFrameFedOneByteAtATimeIsFoundOnce() {
        List<Frame> out = new ArrayList<>();
        FrameDecoder d = new FrameDecoder(out::add);
        for (byte b : SIGNED_HEARTBEAT) {
            d.feed(new byte[]{b});
        }
        assertEquals(1, out.size());
        assertEquals(0, d.pending());
    }

    @Test
    void garbageAndFalseStartBytesBeforeAFrameAreSkipped() {
        byte[] noise = {0x00, 0x11, (byte) 0xFD, 0x05, 0x00, (byte) 0xFE, 0x42, 0x13, (byte) 0xFD, 0x09};
        List<Frame> out = new ArrayList<>();
        FrameDecoder d = new FrameDecoder(out::add);
        d.feed(concat(noise, HEARTBEAT, noise, COMMAND_ACK));
        // a false start byte holds what follows until the length it claims has come (the link goes on streaming)
        for (int i = 0; i < 10; i++) {
            d.feed(HEARTBEAT);
        }
        assertEquals(List.of("HEARTBEAT", "COMMAND_ACK", "HEARTBEAT", "HEARTBEAT"),
                out.subList(0, 4).stream().map(f -> f.type().map(MessageType::name).orElse("?")).toList());
        assertTrue(out.size() >= 10, "frames found: " + out.size());
        assertTrue(d.counts().droppedBytes() > 0);
    }

    @Test
    void aDamagedFrameIsDroppedAndTheNextOneIsFound() {
        byte[] damaged = HEARTBEAT.clone();
        damaged[12] ^= 0x40;
        List<Frame> out = new ArrayList<>();
        FrameDecoder d = new FrameDecoder(out::add);
        d.feed(concat(damaged, COMMAND_ACK));
        assertEquals(1, out.size());
        assertTrue(out.get(0).is(Messages.CommandAck.MESSAGE));
        assertEquals(1, d.counts().badChecksums());
    }

    @Test
    void aFrameHiddenBehindAFalseStartWithALongLengthIsFound() {
        // FD FF ... claims a 255-byte payload; the heartbeat inside must not be swallowed.
        byte[] falseStart = {(byte) 0xFD, (byte) 0xFF, 0, 0, 0, 1, 1, 0, 0, 0};
        byte[] tail = new byte[300];
        List<Frame> out = decode(concat(falseStart, HEARTBEAT, tail));
        assertEquals(1, out.size());
        assertTrue(out.get(0).is(Messages.Heartbeat.MESSAGE));
    }

    @Test
    void anUnknownMessagePassesByAndTheFrameBehindItIsFound() {
        byte[] unknown = HEX.parseHex("fd 03 00 00 07 2a 01 39 30 00 aa bb cc 12 34"); // id 12345: its checksum cannot be checked
        List<Frame> out = new ArrayList<>();
        FrameDecoder d = new FrameDecoder(out::add);
        d.feed(concat(unknown, HEARTBEAT));
        assertEquals(1, out.size());
        assertTrue(out.get(0).is(Messages.Heartbeat.MESSAGE));
        assertEquals(1, d.counts().unknown());
    }

    @Test
    void noiseThatLooksLikeAnUnknownMessageDoesNotSwallowTheFrameBehindIt() {
        byte[] noise = {(byte) 0xFD, 0x30, 0, 0, 0, 9, 9, 0x55, 0x66, 0x77}; // claims 48 bytes: the heartbeat is inside them
        List<Frame> out = decode(concat(noise, HEARTBEAT, new byte[60]));
        assertEquals(1, out.size());
        assertTrue(out.get(0).is(Messages.Heartbeat.MESSAGE));
    }

    @Test
    void aDatagramEndingInAFalseStartDoesNotHoldTheNextDatagram() {
        List<Frame> out = new ArrayList<>();
        FrameDecoder d = new FrameDecoder(out::add);
        byte[] first = concat(HEARTBEAT, new byte[]{(byte) 0xFD, (byte) 0xFF, 0});
        d.feedDatagram(first, 0, first.length);
        assertEquals(0, d.pending());
        d.feedDatagram(COMMAND_ACK, 0, COMMAND_ACK.length);
        assertEquals(List.of(Messages.Heartbeat.MESSAGE, Messages.CommandAck.MESSAGE), out.stream().map(f -> f.type().orElseThrow()).toList());
    }

    @Test
    void aFrameWithAnUnknownIncompatibilityFlagIsDropped() {
        byte[] flagged = HEARTBEAT.clone();
        flagged[Framing.INCOMPAT_FLAGS] = 0x02;
        int crc = Crc.accumulate(Crc.accumulate(Crc.INITIAL, flagged, 1, 9 + 9), Messages.Heartbeat.MESSAGE.crcExtra());
        flagged[19] = (byte) crc;
        flagged[20] = (byte) (crc >> 8);
        List<Frame> out = new ArrayList<>();
        FrameDecoder d = new FrameDecoder(out::add);
        d.feed(concat(flagged, COMMAND_ACK));
        assertEquals(1, out.size());
        assertEquals(1, d.counts().incompatible());
    }

    @Test
    void aMavlink1FrameIsRecognised() {
        // pymavlink 2.4.50, MAVLink 1: HEARTBEAT(type 2, autopilot 3, base_mode 0x81, custom_mode 4, status 4, version 3) from 1/1, seq 0
        byte[] v1 = HEX.parseHex("fe 09 00 01 01 00 04 00 00 00 02 03 81 04 03 99 95");
        List<Frame> out = decode(v1);
        assertEquals(1, out.size());
        assertEquals(Frame.Version.V1, out.get(0).version());
        assertEquals(4, out.get(0).payload().getLong(Messages.Heartbeat.CUSTOM_MODE));
    }

    @Test
    void theLargestFrameIsDecodedWhole() {
        MessageType big = MessageType.define("BIG", 0x7F7F7F, 42, "uint8_t[255] data");
        Payload p = Payload.of(big);
        byte[] data = new byte[255];
        Arrays.fill(data, (byte) 0xFD);
        p.setBytes(big.field("data"), data);
        byte[] frame = new FrameEncoder(1, 1).signWith(new Signer(SigningKey.fromPassphrase("x"), 3, InstantSource.system())).encode(p);
        assertEquals(Framing.MAX_FRAME, frame.length);
        List<Frame> out = new ArrayList<>();
        FrameDecoder d = new FrameDecoder(id -> id == big.id() ? big : Messages.byId(id), out::add);
        d.feed(concat(frame, frame, HEARTBEAT));
        assertEquals(3, out.size());
        assertArrayEquals(data, out.get(1).payload().getBytes(big.field("data")));
    }

    @Test
    void textIsReadUpToItsFirstNulAndWrittenCut() {
        Payload p = Payload.of(Messages.Statustext.MESSAGE).setText(Messages.Statustext.TEXT, "x".repeat(60));
        assertEquals(50, p.getText(Messages.Statustext.TEXT).length());
        p.setText(Messages.Statustext.TEXT, "Arming");
        assertEquals("Arming", p.getText(Messages.Statustext.TEXT));
    }

    @Test
    void nanSurvivesAFloatField() {
        Payload p = Payload.of(Messages.CommandLong.MESSAGE).set(Messages.CommandLong.PARAM7, Double.NaN);
        Frame f = decode(new FrameEncoder(255, 190).encode(p)).get(0);
        assertTrue(Double.isNaN(f.payload().getDouble(Messages.CommandLong.PARAM7)));
    }
}
