package io.robomw.platform.mavlink.wire;

import org.junit.jupiter.api.Test;

import java.time.Instant;
import java.time.InstantSource;
import java.util.ArrayList;
import java.util.List;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertNotEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;

class SignatureCheckTest {

    private static final SigningKey KEY = SigningKey.fromPassphrase("sea breeze");
    private static final Instant NOW = Instant.parse("2026-05-01T12:00:00Z");

    private static Frame frame(byte[] bytes) {
        List<Frame> out = new ArrayList<>();
        new FrameDecoder(out::add).feed(bytes);
        return out.get(0);
    }

    private static FrameEncoder sender(int link, Instant at) {
        return new FrameEncoder(255, 190).signWith(new Signer(KEY, link, InstantSource.fixed(at)));
    }

    @Test
    void aFreshSignedFrameIsAccepted() {
        SignatureCheck check = new SignatureCheck(KEY, InstantSource.fixed(NOW));
        assertEquals(SignatureCheck.Verdict.ACCEPTED, check.check(frame(sender(0, NOW).encode(FrameCodecTest.heartbeat()))));
    }

    @Test
    void theSameFrameTwiceIsAReplay() {
        SignatureCheck check = new SignatureCheck(KEY, InstantSource.fixed(NOW));
        Frame f = frame(sender(0, NOW).encode(FrameCodecTest.heartbeat()));
        assertEquals(SignatureCheck.Verdict.ACCEPTED, check.check(f));
        assertEquals(SignatureCheck.Verdict.REPLAYED, check.check(f));
    }

    @Test
    void eachLinkIsItsOwnStream() {
        SignatureCheck check = new SignatureCheck(KEY, InstantSource.fixed(NOW));
        FrameEncoder link1 = sender(1, NOW);
        FrameEncoder link2 = sender(2, NOW);
        assertEquals(SignatureCheck.Verdict.ACCEPTED, check.check(frame(link1.encode(FrameCodecTest.heartbeat()))));
        assertEquals(SignatureCheck.Verdict.ACCEPTED, check.check(frame(link2.encode(FrameCodecTest.heartbeat()))));
        assertEquals(SignatureCheck.Verdict.ACCEPTED, check.check(frame(link1.encode(FrameCodecTest.heartbeat()))));
    }

    @Test
    void aNewStreamMoreThanAMinuteBehindIsTooOld() {
        SignatureCheck check = new SignatureCheck(KEY, InstantSource.fixed(NOW));
        Frame old = frame(sender(0, NOW.minusSeconds(61)).encode(FrameCodecTest.heartbeat()));
        assertEquals(SignatureCheck.Verdict.TOO_OLD, check.check(old));
        Frame recent = frame(sender(0, NOW.minusSeconds(59)).encode(FrameCodecTest.heartbeat()));
        assertEquals(SignatureCheck.Verdict.ACCEPTED, check.check(recent));
    }

    @Test
    void anotherKeyOrAChangedByteIsAWrongSignature() {
        SignatureCheck check = new SignatureCheck(KEY, InstantSource.fixed(NOW));
        byte[] other = new FrameEncoder(255, 190).signWith(new Signer(SigningKey.fromPassphrase("land breeze"), 0, InstantSource.fixed(NOW)))
                .encode(FrameCodecTest.heartbeat());
        assertEquals(SignatureCheck.Verdict.WRONG_SIGNATURE, check.check(frame(other)));
        byte[] tampered = sender(0, NOW).encode(FrameCodecTest.heartbeat());
        tampered[tampered.length - 8] ^= 1; // a timestamp byte: the checksum still holds, the signature does not
        assertEquals(SignatureCheck.Verdict.WRONG_SIGNATURE, check.check(frame(tampered)));
    }

    @Test
    void anUnsignedFrameIsSaidToBeUnsigned() {
        SignatureCheck check = new SignatureCheck(KEY, InstantSource.fixed(NOW));
        assertEquals(SignatureCheck.Verdict.UNSIGNED, check.check(frame(FrameCodecTest.HEARTBEAT)));
    }

    @Test
    void timestampsIncreaseWithinOneSenderEvenOnAFrozenClock() {
        FrameEncoder e = sender(0, NOW);
        long last = -1;
        for (int i = 0; i < 5; i++) {
            long ts = frame(e.encode(FrameCodecTest.heartbeat())).signature().orElseThrow().timestamp();
            assertNotEquals(last, ts);
            assertEquals(last < 0 ? SigningTime.of(NOW) : last + 1, ts);
            last = ts;
        }
    }

    @Test
    void thePassphraseIsNotShownAndAnEmptyOneIsRefused() {
        assertFalse(KEY.toString().contains("sea"));
        assertThrows(IllegalArgumentException.class, () -> SigningKey.fromPassphrase(""));
    }

    @Test
    void signingTimeCountsTenMicrosecondsFrom2015() {
        assertEquals(0, SigningTime.of(Instant.parse("2015-01-01T00:00:00Z")));
        assertEquals(100_001, SigningTime.of(Instant.parse("2015-01-01T00:00:01.000010Z")));
    }
}
