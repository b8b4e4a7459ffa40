package io.robomw.platform.aibo;

import org.junit.jupiter.api.Test;

import java.nio.charset.StandardCharsets;
import java.util.ArrayList;
import java.util.List;
import java.util.OptionalDouble;

import static org.junit.jupiter.api.Assertions.assertAll;
import static org.junit.jupiter.api.Assertions.assertArrayEquals;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * URBI 1.x on the wire, byte for byte: the commands the driver sends and the server's messages it
 * reads, from the forms of the URBI documents (protocols README §5, liburbi.xml, k1-to-k2.tex,
 * k1-bin.chk).
 */
class UrbiCodecTest {

    private static byte[] ascii(String s) {
        return s.getBytes(StandardCharsets.ISO_8859_1);
    }

    /** Collects what a decoder reports. */
    private static final class Collected implements UrbiReplyDecoder.Listener {
        final List<UrbiReply> replies = new ArrayList<>();
        final List<String> malformed = new ArrayList<>();

        @Override
        public void reply(UrbiReply reply) {
            replies.add(reply);
        }

        @Override
        public void malformed(String why, String excerpt) {
            malformed.add(why + ": " + excerpt);
        }
    }

    private static Collected decode(byte[]... chunks) {
        UrbiReplyDecoder d = new UrbiReplyDecoder(64, 32);
        Collected c = new Collected();
        for (byte[] chunk : chunks) {
            d.feed(chunk, 0, chunk.length, c);
        }
        return c;
    }

    // ---- client to server ----

    @Test
    void shouldSendAHighLevelCommandAsATaggedBackgroundBlockThatReportsItsEnd() {
        assertArrayEquals(ascii("c12+end: { robot.walk(0.5, 0.15) },\n"), UrbiProtocol.command("c12", "robot.walk(0.5, 0.15)"));
        assertArrayEquals(ascii("o1+end: { motoron; robot.watchdogInterval = 0.5 },\n"),
                UrbiProtocol.command("o1", "  motoron; robot.watchdogInterval = 0.5 "));
    }

    @Test
    void shouldSendReadsStreamsAndStopsAsTheUrbiDocumentsWriteThem() {
        assertAll(
                () -> assertArrayEquals(ascii("r13: distanceNear.val,\n"), UrbiProtocol.read("r13", "distanceNear")),
                () -> assertArrayEquals(ascii("s3: every(100ms) accelX.val,\n"), UrbiProtocol.stream("s3", "accelX", 100)),
                () -> assertArrayEquals(ascii("stop c12,\n"), UrbiProtocol.stop("c12")));
    }

    @Test
    void shouldRefuseTagsDevicesAndCommandsThatWouldBreakTheFraming() {
        assertAll(
                () -> assertThrows(IllegalArgumentException.class, () -> UrbiProtocol.command("1c", "x")),
                () -> assertThrows(IllegalArgumentException.class, () -> UrbiProtocol.command("c".repeat(65), "x")),
                () -> assertThrows(IllegalArgumentException.class, () -> UrbiProtocol.command("c1", "robot.walk(1)\nrobot.sit()")),
                () -> assertThrows(IllegalArgumentException.class, () -> UrbiProtocol.command("c1", " ")),
                () -> assertThrows(IllegalArgumentException.class, () -> UrbiProtocol.read("r1", "head pan")),
                () -> assertThrows(IllegalArgumentException.class, () -> UrbiProtocol.stream("s1", "accelX", 0)));
        assertTrue(UrbiProtocol.validTag("c".repeat(64)));
    }

    // ---- server to client ----

    @Test
    void shouldReadTaggedValuesSystemMessagesAndErrors() {
        Collected c = decode(ascii("""
                [00012345:r13] 421.000000
                [00012346:c12] *** end
                [00012347:c14] !!! unknown identifier: robot.fly
                [00000000] *** URBI Kernel 1.x
                """));

        assertEquals(List.of(
                new UrbiReply(12345, "r13", UrbiReply.Kind.VALUE, "421.000000", null),
                new UrbiReply(12346, "c12", UrbiReply.Kind.SYSTEM, "end", null),
                new UrbiReply(12347, "c14", UrbiReply.Kind.ERROR, "unknown identifier: robot.fly", null),
                new UrbiReply(0, "", UrbiReply.Kind.SYSTEM, "URBI Kernel 1.x", null)), c.replies);
        assertEquals(OptionalDouble.of(421), c.replies.get(0).number());
        assertTrue(c.replies.get(1).isEnd());
        assertEquals(List.of(), c.malformed);
    }

    @Test
    void shouldReadABinaryValueByItsLengthWhateverBytesItHolds() {
        byte[] wire = ascii("[00000001:img] BIN 10 raw 2 1\n0\n2]\r[9:x]\n[00000002:r1] 7\n");

        Collected c = decode(wire);

        assertEquals(2, c.replies.size(), c.replies::toString);
        UrbiReply bin = c.replies.get(0);
        assertAll(
                () -> assertEquals(UrbiReply.Kind.BINARY, bin.kind()),
                () -> assertEquals("img", bin.tag()),
                () -> assertEquals("raw 2 1", bin.text()),
                () -> assertArrayEquals(ascii("0\n2]\r[9:x]"), bin.data()),
                () -> assertEquals(new UrbiReply(2, "r1", UrbiReply.Kind.VALUE, "7", null), c.replies.get(1)));
    }

    @Test
    void shouldReadMessagesSplitAtEveryByteAndMergedInOneChunk() {
        byte[] wire = ascii("[00000001:a] 1.5\r\n[00000002:img] BIN 3\nxyz[00000003] *** pong time=0.003s\n\n");
        List<UrbiReply> whole = decode(wire).replies;

        UrbiReplyDecoder d = new UrbiReplyDecoder(64, 32);
        Collected split = new Collected();
        for (byte b : wire) {
            d.feed(new byte[] {b}, 0, 1, split);
        }

        assertEquals(3, whole.size(), whole::toString);
        assertEquals(whole, split.replies);
        assertEquals("1.5", whole.get(0).text(), "the carriage return is dropped");
        assertFalse(d.midMessage());
    }

    @Test
    void shouldSkipLinesThatAreNotMessagesAndReadTheNext() {
        Collected c = decode(ascii("""
                hello
                [12a] 1
                [1234567890123456789] 1
                [1:bad tag] 1
                [1:tag
                [5:img] BIN x
                [6:ok] 6
                """));

        assertEquals(List.of(new UrbiReply(6, "ok", UrbiReply.Kind.VALUE, "6", null)), c.replies);
        assertEquals(6, c.malformed.size(), c.malformed::toString);
        assertTrue(c.malformed.get(0).contains("starts with '[timestamp]'"), c.malformed::toString);
        assertTrue(c.malformed.get(3).contains("the tag must be"), c.malformed::toString);
        assertTrue(c.malformed.get(5).contains("'BIN <length> [keywords]'"), c.malformed::toString);
    }

    @Test
    void shouldSkipALineLongerThanTheLimitUpToItsNewline() {
        Collected c = decode(ascii("[1:a] " + "x".repeat(200)), ascii("yyy\n[2:b] 2\n"));

        assertEquals(List.of(new UrbiReply(2, "b", UrbiReply.Kind.VALUE, "2", null)), c.replies);
        assertEquals(1, c.malformed.size());
        assertTrue(c.malformed.get(0).contains("longer than 64 bytes"), c.malformed::toString);
    }

    @Test
    void shouldSkipTheBytesOfABinaryValueAboveTheLimitAndKeepTheFraming() {
        Collected c = decode(ascii("[1:img] BIN 40 jpeg\n" + "z".repeat(40) + "[2:b] 2\n"));

        assertEquals(List.of(new UrbiReply(2, "b", UrbiReply.Kind.VALUE, "2", null)), c.replies);
        assertTrue(c.malformed.get(0).contains("40 bytes is longer than 32"), c.malformed::toString);
    }

    @Test
    void shouldReadNumbersOnlyFromPlainNumericValues() {
        assertAll(
                () -> assertEquals(OptionalDouble.of(-3.5e-5), value("-3.5e-05").number()),
                () -> assertEquals(OptionalDouble.of(0.25), value(" .25 ").number()),
                () -> assertEquals(OptionalDouble.empty(), value("\"421\"").number()),
                () -> assertEquals(OptionalDouble.empty(), value("NaN").number()),
                () -> assertEquals(OptionalDouble.empty(), value("1e99999").number()),
                () -> assertEquals(OptionalDouble.empty(), new UrbiReply(1, "", UrbiReply.Kind.ERROR, "1", null).number()));
    }

    private static UrbiReply value(String text) {
        return new UrbiReply(1, "t", UrbiReply.Kind.VALUE, text, null);
    }

    @Test
    void shouldSurviveRandomBytesAndReadTheMessageThatFollows() {
        java.util.SplittableRandom random = new java.util.SplittableRandom(16);
        UrbiReplyDecoder d = new UrbiReplyDecoder(256, 1024);
        Collected c = new Collected();
        byte[] alphabet = ascii("[]:0123456789 *!BIN\n\rabc_.\"");
        for (int round = 0; round < 2000; round++) {
            byte[] chunk = new byte[random.nextInt(1, 64)];
            for (int i = 0; i < chunk.length; i++) {
                chunk[i] = random.nextBoolean() ? alphabet[random.nextInt(alphabet.length)] : (byte) random.nextInt(256);
            }
            d.feed(chunk, 0, chunk.length, c);
        }
        c.replies.clear();
        // Whatever state the garbage left: a newline ends a line, a BIN length is bounded by 1024 bytes.
        byte[] flush = new byte[1025];
        java.util.Arrays.fill(flush, (byte) '\n');
        d.feed(flush, 0, flush.length, c);
        c.replies.clear();
        d.feed(ascii("[42:ok] 1\n"), 0, 10, c);

        assertEquals(List.of(new UrbiReply(42, "ok", UrbiReply.Kind.VALUE, "1", null)), c.replies);
    }
}
