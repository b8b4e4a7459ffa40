package io.robomw.platform.ev3;

import io.robomw.platform.brick.LittleEndian;
import io.robomw.platform.brick.BrickChannel;
import io.robomw.platform.link.Communicator;
import io.robomw.platform.link.LinkLostException;
import io.robomw.platform.link.LinkTimeoutException;
import io.robomw.platform.testkit.Answer;
import io.robomw.platform.testkit.ScriptedLink;
import org.junit.jupiter.api.Test;

import java.io.IOException;
import java.time.Duration;
import java.util.List;
import java.util.function.Function;

import static io.robomw.platform.ev3.Ev3CodecTest.hex;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * {@link Ev3Brick} over a scripted link: message counters, replies read by their length
 * however the stream splits them, late replies skipped, error replies and broken framing reported.
 */
class Ev3BrickTest {

    private static final Ev3Command GET_COUNT_A = Ev3Command.withReply(4).outputGetCount(0, 0).build();

    private ScriptedLink link;

    /** @return a brick whose far end answers each frame written with what {@code responder} makes of it */
    private Ev3Brick brick(Function<byte[], Answer> responder) throws IOException {
        link = new ScriptedLink().named("ev3 link").answeringWith(responder);
        Communicator c = new Communicator(link);
        c.open();
        return new Ev3Brick("ev3-test", new BrickChannel("ev3-test", c, Duration.ofMillis(200)));
    }

    /**
     * @param frame a command frame
     * @param globals its reply's globals
     * @return a DIRECT_REPLY echoing its counter
     */
    static byte[] okReply(byte[] frame, byte[] globals) {
        return Ev3Reply.ok(Ev3Frame.counter(frame), globals).encode();
    }

    private static byte[] count(int degrees) {
        byte[] g = new byte[4];
        LittleEndian.putU32(g, 0, degrees);
        return g;
    }

    @Test
    void shouldNumberRequestsFromFortyTwoAndReadTheMatchingReply() throws IOException {
        Ev3Brick brick = brick(f -> Answer.of(okReply(f, count(360))));
        assertEquals(360, brick.request(GET_COUNT_A).data32(0));
        assertEquals(0x2B, brick.request(GET_COUNT_A).counter());
        assertEquals("09 00 2A 00 00 04 00 B3 00 00 60", hex(link.eachWrite().get(0)));
        assertEquals("09 00 2B 00 00 04 00 B3 00 00 60", hex(link.eachWrite().get(1)));
    }

    @Test
    void shouldSkipLateReplyCarryingAnEarlierCounter() throws IOException {
        Ev3Brick brick = brick(f -> Answer.inPieces(List.of(
                Ev3Reply.ok(Ev3Frame.counter(f) - 1, count(-1)).encode(),
                okReply(f, count(720)))));
        assertEquals(720, brick.request(GET_COUNT_A).data32(0));
        assertEquals(1, brick.skippedReplies());
    }

    @Test
    void shouldReadReplyDeliveredOneByteAtATime() throws IOException {
        Ev3Brick brick = brick(f -> Answer.oneByteAtATime(okReply(f, count(-123456))));
        assertEquals(-123456, brick.request(GET_COUNT_A).data32(0));
    }

    @Test
    void shouldReadTwoRepliesMergedIntoOnePieceAsTwo() throws IOException {
        Ev3Brick brick = brick(f -> {
            if (Ev3Frame.counter(f) == 0x2A) {
                byte[] a = okReply(f, count(1));
                byte[] b = Ev3Reply.ok(0x2B, count(2)).encode();
                byte[] both = new byte[a.length + b.length];
                System.arraycopy(a, 0, both, 0, a.length);
                System.arraycopy(b, 0, both, a.length, b.length);
                return Answer.of(both);
            }
            return Answer.none();
        });
        assertEquals(1, brick.request(GET_COUNT_A).data32(0));
        assertEquals(2, brick.request(GET_COUNT_A).data32(0));
    }

    @Test
    void shouldThrowEv3ExceptionNamingOpcodePortAndCounterOnErrorReply() throws IOException {
        Ev3Brick brick = brick(f -> Answer.of(Ev3Reply.error(Ev3Frame.counter(f), new byte[4]).encode()));
        Ev3Exception e = assertThrows(Ev3Exception.class, () -> brick.request(GET_COUNT_A));
        assertEquals(0x2A, e.counter());
        assertTrue(e.getMessage().contains("opOUTPUT_GET_COUNT on output A"), e.getMessage());
        assertTrue(e.getMessage().contains("#42"), e.getMessage());
        assertTrue(e.getMessage().contains("ev3-test"), e.getMessage());
    }

    @Test
    void shouldThrowEv3ExceptionOnBareErrorReplyOfMalformedHeader() throws IOException {
        Ev3Brick brick = brick(f -> Answer.of(hex("03 00 2A 00 04")));
        Ev3Exception e = assertThrows(Ev3Exception.class, () -> brick.request(GET_COUNT_A));
        assertEquals(42, e.counter());
    }

    @Test
    void shouldReportLostFramingWhenReplyAnnouncesImpossibleLength() throws IOException {
        Ev3Brick brick = brick(f -> Answer.of(hex("02 00 2A 00")));
        LinkLostException e = assertThrows(LinkLostException.class, () -> brick.request(GET_COUNT_A));
        assertTrue(e.getMessage().contains("announced 2 bytes"), e.getMessage());
    }

    @Test
    void shouldReportLostFramingOnReplyOfAnotherType() throws IOException {
        Ev3Brick brick = brick(f -> Answer.of(hex("03 00 2A 00 03")));
        assertThrows(LinkLostException.class, () -> brick.request(GET_COUNT_A));
    }

    @Test
    void shouldTimeOutWhenOnlyPartOfTheReplyArrives() throws IOException {
        Ev3Brick brick = brick(f -> Answer.of(hex("07 00 2A 00 02 68")));
        LinkTimeoutException e = assertThrows(LinkTimeoutException.class, () -> brick.request(GET_COUNT_A));
        assertTrue(e.getMessage().contains("4 of 7"), e.getMessage());
    }

    @Test
    void shouldRejectReplyWhoseGlobalsDoNotFitTheCommand() throws IOException {
        Ev3Brick brick = brick(f -> Answer.of(okReply(f, new byte[2])));
        LinkLostException e = assertThrows(LinkLostException.class, () -> brick.request(GET_COUNT_A));
        assertTrue(e.getMessage().contains("carries 2 global bytes"), e.getMessage());
    }

    @Test
    void shouldSendNoReplyCommandWithoutReading() throws IOException {
        Ev3Brick brick = brick(f -> Answer.none());
        brick.send(Ev3Command.withoutReply().soundTone(2, 440, 500).build());
        assertEquals("0E 00 2A 00 80 00 00 94 01 02 82 B8 01 82 F4 01", hex(link.eachWrite().get(0)));
        assertThrows(IllegalArgumentException.class, () -> brick.send(GET_COUNT_A));
        assertThrows(IllegalArgumentException.class, () -> brick.request(Ev3Command.withoutReply().outputStart(1).build()));
    }

    @Test
    void shouldWrapTheMessageCounterAfter65535() throws IOException {
        Ev3Brick brick = brick(f -> Answer.none());
        Ev3Command tone = Ev3Command.withoutReply().soundTone(1, 440, 10).build();
        for (int i = Ev3Brick.FIRST_COUNTER; i <= 0xFFFF; i++) {
            brick.send(tone);
        }
        brick.send(tone);
        List<byte[]> w = link.eachWrite();
        assertEquals(0xFFFF, Ev3Frame.counter(w.get(w.size() - 2)));
        assertEquals(0, Ev3Frame.counter(w.get(w.size() - 1)));
    }

    @Test
    void shouldReadBatteryVoltsAsFloat() throws IOException {
        byte[] volts = new byte[4];
        LittleEndian.putF32(volts, 0, 7.8f);
        Ev3Brick brick = brick(f -> Answer.of(okReply(f, volts)));
        assertEquals(7.8, brick.batteryVolts(), 1e-6);
        assertEquals("08 00 2A 00 00 04 00 81 01 60", hex(link.eachWrite().get(0)));
    }
}
