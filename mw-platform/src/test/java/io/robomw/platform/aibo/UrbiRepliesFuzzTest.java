package io.robomw.platform.aibo;

import com.code_intelligence.jazzer.api.FuzzedDataProvider;
import com.code_intelligence.jazzer.junit.FuzzTest;

import java.io.ByteArrayOutputStream;
import java.nio.charset.StandardCharsets;
import java.util.ArrayList;
import java.util.List;
import java.util.OptionalDouble;

/**
 * Fuzz test of what the Aibo's driver reads from an URBI server (docs/fuzzing.md): any bytes as
 * the server's stream, fed to {@link UrbiReplyDecoder} as the driver's reader feeds it, in
 * whatever chunks the network cuts it into. The decoder refuses nothing by throwing: a line that
 * is not a message is reported to {@link UrbiReplyDecoder.Listener#malformed} and skipped. So:
 * <ul>
 *   <li>it decodes the same messages and reports the same malformed lines however the bytes are
 *   cut (the input's last bytes say where: a count, then that many chunk sizes; no count is one
 *   byte at a time), and with the driver's own limits as with small ones;</li>
 *   <li>what it yields survives the server's own format: each message, written back as
 *   {@link UrbiReply#describe()} (its bytes after a {@code BIN} header), decodes to itself (but
 *   for a text ending in a carriage return, which the decoder drops before a newline by
 *   design), its number, if any, is finite, and its tag is one the driver could have sent.</li>
 * </ul>
 */
class UrbiRepliesFuzzTest {

    /** Small limits, so that a fuzzed input reaches them: a line of 256 bytes, a binary value of 1 KiB. */
    private static final int MAX_LINE = 256;
    private static final int MAX_BINARY = 1024;

    /** What a decoder reported, in order. */
    private static final class Collected implements UrbiReplyDecoder.Listener {
        final List<Object> events = new ArrayList<>();
        final List<UrbiReply> replies = new ArrayList<>();

        @Override
        public void reply(UrbiReply reply) {
            events.add(reply);
            replies.add(reply);
        }

        @Override
        public void malformed(String why, String excerpt) {
            if (excerpt.length() > 83) {
                throw new AssertionError("an excerpt longer than 80 characters and '...': " + excerpt.length());
            }
            events.add("malformed: " + why + ": " + excerpt);
        }
    }

    @FuzzTest
    void urbiReply(FuzzedDataProvider data) {
        int[] chunks = new int[data.consumeInt(0, 7)];
        for (int i = 0; i < chunks.length; i++) {
            chunks[i] = data.consumeInt(1, 256);
        }
        byte[] bytes = data.consumeRemainingAsBytes();

        Collected whole = new Collected();
        UrbiReplyDecoder one = new UrbiReplyDecoder(MAX_LINE, MAX_BINARY);
        one.feed(bytes, 0, bytes.length, whole);

        Collected cut = new Collected();
        UrbiReplyDecoder pieces = new UrbiReplyDecoder(MAX_LINE, MAX_BINARY);
        for (int at = 0, i = 0; at < bytes.length; i++) {
            int n = Math.min(bytes.length - at, chunks.length == 0 ? 1 : chunks[i % chunks.length]);
            pieces.feed(bytes, at, n, cut);
            at += n;
        }
        if (!cut.events.equals(whole.events)) {
            throw new AssertionError("cut into chunks " + java.util.Arrays.toString(chunks) + " the stream decodes to " + cut.events
                    + ", whole to " + whole.events);
        }
        if (pieces.midMessage() != one.midMessage()) {
            throw new AssertionError("cut into chunks, the decoder is " + (pieces.midMessage() ? "" : "not ") + "in the middle of a message; whole, it is "
                    + (one.midMessage() ? "" : "not"));
        }

        Collected driver = new Collected();
        new UrbiReplyDecoder().feed(bytes, 0, bytes.length, driver);

        for (UrbiReply r : whole.replies) {
            check(r);
        }
        for (UrbiReply r : driver.replies) {
            check(r);
        }
    }

    /** What the driver does with a message, and the server's format written back. */
    private static void check(UrbiReply r) {
        OptionalDouble n = r.number();
        if (n.isPresent() && !Double.isFinite(n.getAsDouble())) {
            throw new AssertionError("a number that is not finite: " + n + " from " + r.describe());
        }
        r.isEnd();
        if (r.tagged() && (r.tag().length() > UrbiProtocol.MAX_TAG_LENGTH || !r.tag().matches("[A-Za-z0-9_.]+"))) {
            throw new AssertionError("a tag no URBI client sends: '" + r.tag() + "'");
        }
        if (r.kind() != UrbiReply.Kind.BINARY && r.data().length != 0) {
            throw new AssertionError("a " + r.kind() + " message with binary data: " + r);
        }
        if (r.text().endsWith("\r")) {
            return; // a carriage return before the newline is dropped: such a text cannot be written back as it is
        }
        ByteArrayOutputStream written = new ByteArrayOutputStream();
        written.writeBytes((r.describe() + "\n").getBytes(StandardCharsets.UTF_8));
        written.writeBytes(r.data());
        byte[] again = written.toByteArray();
        Collected back = new Collected();
        UrbiReplyDecoder d = new UrbiReplyDecoder();
        d.feed(again, 0, again.length, back);
        if (!back.events.equals(List.of(r)) || d.midMessage()) {
            throw new AssertionError("the message " + r + " written back as the server writes it decodes to " + back.events);
        }
    }
}
