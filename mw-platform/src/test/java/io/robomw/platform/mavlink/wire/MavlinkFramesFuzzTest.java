package io.robomw.platform.mavlink.wire;

import com.code_intelligence.jazzer.api.FuzzedDataProvider;
import com.code_intelligence.jazzer.junit.FuzzTest;

import java.time.Instant;
import java.time.InstantSource;
import java.util.ArrayList;
import java.util.Arrays;
import java.util.List;

/**
 * Fuzz test of the MAVLink decoder (docs/fuzzing.md): any bytes as what a vehicle, a ground
 * station or a noisy radio sends. The decoder refuses nothing by throwing: bad bytes are skipped
 * and counted. So:
 * <ul>
 *   <li>{@code stream}: the bytes fed as a serial link delivers them, in chunks the input's last
 *   bytes choose, give the same frames as fed at once; the decoder never holds more than one
 *   frame's worth of bytes waiting;</li>
 *   <li>{@code datagram}: the bytes as one UDP datagram leave nothing behind;</li>
 *   <li>each frame it yields is of a known message with a good checksum; its payload, encoded
 *   again by the codec's encoder, decodes to the same fields; a signed frame's signature is
 *   checked (against a key it was not made with) without an error.</li>
 * </ul>
 */
class MavlinkFramesFuzzTest {

    private static final SignatureCheck CHECK = new SignatureCheck(SigningKey.fromPassphrase("fuzz"),
            InstantSource.fixed(Instant.parse("2026-01-01T00:00:00Z")));

    @FuzzTest
    void stream(FuzzedDataProvider data) {
        int[] chunks = new int[data.consumeInt(0, 7)];
        for (int i = 0; i < chunks.length; i++) {
            chunks[i] = data.consumeInt(1, 300);
        }
        byte[] bytes = data.consumeRemainingAsBytes();
        List<Frame> whole = new ArrayList<>();
        new FrameDecoder(whole::add).feed(bytes);
        List<Frame> cut = new ArrayList<>();
        FrameDecoder d = new FrameDecoder(cut::add);
        int at = 0;
        int k = 0;
        while (at < bytes.length) {
            int n = chunks.length == 0 ? 1 : Math.min(bytes.length - at, chunks[k++ % chunks.length]);
            d.feed(bytes, at, n);
            at += n;
            if (d.pending() > Framing.MAX_FRAME) {
                throw new AssertionError("the decoder holds " + d.pending() + " bytes, more than one frame");
            }
        }
        if (whole.size() != cut.size()) {
            throw new AssertionError("fed at once: " + whole.size() + " frames, fed in chunks: " + cut.size());
        }
        for (int i = 0; i < whole.size(); i++) {
            if (!Arrays.equals(whole.get(i).bytes(), cut.get(i).bytes())) {
                throw new AssertionError("frame " + i + " differs when the bytes are cut");
            }
            checkFrame(whole.get(i));
        }
    }

    @FuzzTest
    void datagram(byte[] input) {
        List<Frame> frames = new ArrayList<>();
        FrameDecoder d = new FrameDecoder(frames::add);
        d.feedDatagram(input, 0, input.length);
        if (d.pending() != 0) {
            throw new AssertionError("a datagram left " + d.pending() + " bytes behind");
        }
        for (Frame f : frames) {
            checkFrame(f);
        }
    }

    private static void checkFrame(Frame f) {
        MessageType type = f.type().orElseThrow(() -> new AssertionError("a frame without a known type was handed on: " + f));
        int header = f.version() == Frame.Version.V2 ? Framing.HEADER_V2 : Framing.HEADER_V1;
        byte[] b = f.bytes();
        int crc = Crc.accumulate(Crc.accumulate(Crc.INITIAL, b, 1, header - 1 + f.payloadLength()), type.crcExtra());
        if (crc != f.checksum()) {
            throw new AssertionError("a frame with a bad checksum was handed on: " + f);
        }
        Payload p = f.payload();
        List<Frame> again = new ArrayList<>();
        new FrameDecoder(again::add).feed(new FrameEncoder(Math.max(1, f.systemId()), f.componentId()).encode(p));
        if (again.size() != 1 || !Arrays.equals(again.get(0).payload().bytes(), p.bytes())) {
            throw new AssertionError("a payload does not survive its own encoding: " + p);
        }
        p.toString();
        if (f.signed()) {
            CHECK.check(f);
        }
    }
}
