package io.robomw.sim.legged;

import org.junit.jupiter.api.Test;

import java.nio.charset.StandardCharsets;
import java.util.ArrayList;
import java.util.List;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

/** Cutting a client's bytes into URBI statements, whatever they hold. */
class UrbiStatementSplitterTest {

    private final List<String> out = new ArrayList<>();
    private final List<String> errors = new ArrayList<>();
    private final UrbiStatementSplitter.Listener listener = new UrbiStatementSplitter.Listener() {
        @Override
        public void statement(String text, char terminator) {
            out.add(text + terminator);
        }

        @Override
        public void error(String message) {
            errors.add(message);
        }
    };

    private void feed(UrbiStatementSplitter s, String text) {
        byte[] b = text.getBytes(StandardCharsets.ISO_8859_1);
        s.feed(b, 0, b.length, listener);
    }

    @Test
    void shouldCutAtTopLevelTerminatorsOnly() {
        UrbiStatementSplitter s = new UrbiStatementSplitter();

        feed(s, "c1+end: { robot.walk(0.5, 0.15); robot.sit() },\nr2: distanceNear.val;x = \"a;b,c\" | y & s3: every(100ms) accelX.val,");

        assertEquals(List.of("c1+end: { robot.walk(0.5, 0.15); robot.sit() },", "r2: distanceNear.val;", "x = \"a;b,c\"|", "y&",
                "s3: every(100ms) accelX.val,"), out);
        assertFalse(s.midStatement());
    }

    @Test
    void shouldJoinAStatementSplitAtEveryByte() {
        UrbiStatementSplitter s = new UrbiStatementSplitter();
        String wire = "c7+end: { headPan.val = 30 time:400 },\n";

        for (byte b : wire.getBytes(StandardCharsets.US_ASCII)) {
            s.feed(new byte[] {b}, 0, 1, listener);
        }

        assertEquals(List.of("c7+end: { headPan.val = 30 time:400 },"), out);
    }

    @Test
    void shouldBeMidStatementInsideAnOpenCommentWhichSwallowsWhatFollows() {
        UrbiStatementSplitter s = new UrbiStatementSplitter();

        feed(s, "p1: ping; /* not ended");
        assertTrue(s.midStatement(), "a block comment is open");
        feed(s, " p2: ping; */ // a line comment");
        assertTrue(s.midStatement(), "a line comment is open");
        feed(s, "\n");

        assertFalse(s.midStatement());
        assertEquals(List.of("p1: ping;"), out);
    }

    @Test
    void shouldSkipCommentsAndEmptyStatements() {
        UrbiStatementSplitter s = new UrbiStatementSplitter();

        feed(s, "// motoroff;\n ; ping /* stop; it */ ;,\n");

        assertEquals(List.of("ping;"), out);
    }

    @Test
    void shouldSkipTheBytesOfABinaryValueSoTheyAreNotReadAsCommands() {
        UrbiStatementSplitter s = new UrbiStatementSplitter();

        feed(s, "speaker.val = BIN 9 raw 2 16000;stop c1;,ping;");

        assertEquals(List.of("speaker.val = BIN 9 raw 2 16000;", "ping;"), out);
    }

    @Test
    void shouldReportAClosingBraceThatClosesNothingAndGoOn() {
        UrbiStatementSplitter s = new UrbiStatementSplitter();

        feed(s, "x: }; ping;");

        assertEquals(List.of("ping;"), out);
        assertEquals(1, errors.size());
        assertTrue(errors.get(0).contains("'}' closes nothing"), errors::toString);
    }

    @Test
    void shouldSkipAStatementLongerThanTheLimitToTheNextLine() {
        UrbiStatementSplitter s = new UrbiStatementSplitter(32);

        feed(s, "robot.walk(" + "1".repeat(100) + ");still skipped;\nping;");

        assertEquals(List.of("ping;"), out);
        assertTrue(errors.get(0).contains("longer than 32 bytes"), errors::toString);
    }

    @Test
    void shouldTurnBytesOutsidePrintableAsciiIntoAReplacementTheParserRefuses() {
        UrbiStatementSplitter s = new UrbiStatementSplitter();

        s.feed(new byte[] {'x', (byte) 0xFF, 0, ';'}, 0, 4, listener);

        assertEquals(List.of("x\uFFFD\uFFFD;"), out);
    }

    @Test
    void shouldAbandonAStatementHeldOpenByABraceAtTheEmergencyEscapeAndCutAfreshAfterIt() {
        UrbiStatementSplitter s = new UrbiStatementSplitter();
        feed(s, "p1: ping; h1: { robot.walk(0.3, 0.1); (x1: ping;");
        assertTrue(s.midStatement(), "the brace holds the statement open: the ping is part of it");

        feed(s, "$$\n");

        assertFalse(s.midStatement());
        feed(s, "x2: ping;");
        assertEquals(List.of("p1: ping;", "x2: ping;"), out, "the held statement was abandoned, the next one cut as usual");
        assertEquals(List.of(), errors, "silently, as the kernel does");
        assertEquals(1, s.escapes());
    }

    @Test
    void shouldDropWhatCameAfterTheEscapeInTheSameReadAndKeepWhatEndedBeforeIt() {
        UrbiStatementSplitter s = new UrbiStatementSplitter();

        feed(s, "p1: ping; { robot.sit(); $$ x3: ping; x4: ping;");
        feed(s, "x5: ping;");

        assertEquals(List.of("p1: ping;", "x5: ping;"), out, "the kernel clears its whole receive queue at the escape");
    }

    @Test
    void shouldNotTakeDollarsInAStringOrACommentForTheEscape() {
        UrbiStatementSplitter s = new UrbiStatementSplitter();

        feed(s, "x = \"a$$b\"; // $$ here\np1: ping; /* $$ */ p2: ping; # $$ there\np3: ping;");

        assertEquals(List.of("x = \"a$$b\";", "p1: ping;", "p2: ping;", "p3: ping;"), out);
        assertEquals(0, s.escapes());
    }

    @Test
    void shouldTakeOneDollarAndTwoSplitBetweenReadsAsText() {
        UrbiStatementSplitter s = new UrbiStatementSplitter();

        feed(s, "x = a$b; { y $");
        feed(s, "$ z };");

        assertEquals(List.of("x = a$b;", "{ y $$ z };"), out, "the kernel looks for the second $ among the bytes received with the first");
        assertEquals(0, s.escapes());
    }

    @Test
    void shouldNotScanTheBytesOfABinaryValueForTheEscape() {
        UrbiStatementSplitter s = new UrbiStatementSplitter();

        feed(s, "speaker.val = BIN 4 raw;a$$b ping;");

        assertEquals(List.of("speaker.val = BIN 4 raw;", "ping;"), out);
    }

    @Test
    void shouldSkipAHashCommentToTheEndOfItsLine() {
        UrbiStatementSplitter s = new UrbiStatementSplitter();

        feed(s, "# motoroff; robot.walk(1, 0.1);\nping;");

        assertEquals(List.of("ping;"), out);
    }
}
