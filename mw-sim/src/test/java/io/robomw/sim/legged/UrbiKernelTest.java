package io.robomw.sim.legged;

import org.junit.jupiter.api.Test;

import java.util.ArrayList;
import java.util.List;
import java.util.OptionalDouble;

import static org.junit.jupiter.api.Assertions.assertAll;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * The emulated dog's URBI server core, stepped by hand at 100 Hz: what each statement prints, when
 * its end is reported, and its errors.
 */
class UrbiKernelTest {

    private long nanos;
    private final Quadruped dog = new Quadruped(QuadrupedTest.drive(0, 0), 1);
    private final UrbiKernel kernel = new UrbiKernel("dog", dog, d -> d.equals("distanceNear") ? OptionalDouble.of(421) : OptionalDouble.empty(),
            () -> nanos);
    private final List<String> out = new ArrayList<>();
    private final UrbiKernel.Session session = kernel.open("test", (millis, tag, kind, text) -> out.add(
            "[" + millis + (tag.isEmpty() ? "" : ":" + tag) + "] " + switch (kind) {
                case SYSTEM -> "*** " + text;
                case ERROR -> "!!! " + text;
                case VALUE -> text;
            }));

    private void step(double seconds) {
        for (int i = 0; i < Math.round(seconds * 100); i++) {
            nanos += 10_000_000L;
            dog.advance(0.01);
            kernel.step();
        }
    }

    @Test
    void shouldAnswerReadsWithTheirTagAndSixDecimals() {
        session.submit("r1: distanceNear.val, r2: headPan.val; r3: 1 + 2 * 3;");
        step(0.01);

        assertEquals(List.of("[10:r1] 421.000000", "[10:r2] 0.000000", "[10:r3] 7.000000"), out);
    }

    @Test
    void shouldReportTheEndOfATaggedWalkWhenTheWalkIsDone() {
        session.submit("motoron; c1+end: { robot.walk(0.2, 0.1) },");
        step(1.99);
        assertEquals(List.of(), out);

        step(0.03);

        assertEquals(List.of("[2010:c1] *** end"), out, "one step after it was sent, as the walk started");
    }

    @Test
    void shouldHoldTheNextStatementUntilASequentialOneEnds() {
        session.submit("motoron; robot.walk(0.1, 0.1); r1: ping,");
        step(0.5);
        assertEquals(List.of(), out, "ping waits for the walk");

        step(0.55);

        assertEquals(1, out.size());
        assertTrue(out.get(0).startsWith("[1010:r1] *** pong time=1.010s"), out::toString);
    }

    @Test
    void shouldStopATaggedCommandAndItsWalk() {
        session.submit("motoron; c1+end: robot.walk(1, 0.1),");
        step(0.5);
        assertTrue(dog.walking());

        session.submit("stop c1,");
        step(0.01);

        assertFalse(dog.walking());
        assertEquals(List.of("[510:c1] *** end"), out);
    }

    @Test
    void shouldStreamWithEveryUntilStopped() {
        session.submit("s1: every(100ms) distanceNear.val,");
        step(0.35);
        session.submit("stop s1,");
        step(0.5);

        assertEquals(List.of("[10:s1] 421.000000", "[110:s1] 421.000000", "[210:s1] 421.000000", "[310:s1] 421.000000"), out);
    }

    @Test
    void shouldAnswerMistakesWithTaggedErrorsAndGoOn() {
        session.submit("""
                c1+end: robot.walk(0.1, 0.1);
                motoron;
                c2: robot.walk(0.1, 0.5);
                c3: robot.fly();
                c4: tailWag.val = 3;
                c5: distanceFar.val = 3;
                c6: robot.walk(1);
                c7: robot.walk 0.5;
                this is not urbi;
                c8: ping;
                """);
        step(0.01);

        assertAll(
                () -> assertEquals("[10:c1] !!! robot.walk: the motors are off (send motoron)", out.get(0)),
                () -> assertEquals("[10:c1] *** end", out.get(1), "a command that failed has ended"),
                () -> assertEquals("[10:c2] !!! robot.walk: the speed 0.500 m/s is above the gait's 0.200 m/s", out.get(2)),
                () -> assertEquals("[10:c3] !!! unknown function: robot.fly", out.get(3)),
                () -> assertEquals("[10:c4] !!! unknown identifier: tailWag.val", out.get(4)),
                () -> assertEquals("[10:c5] !!! distanceFar.val is a sensor; it cannot be assigned", out.get(5)),
                () -> assertEquals("[10:c6] !!! robot.walk expects 2 arguments, got 1", out.get(6)),
                () -> assertTrue(out.get(7).startsWith("[10:c7] !!! syntax error: expected the end of the statement"), out.get(7)),
                () -> assertTrue(out.get(8).startsWith("[10] !!! syntax error"), out.get(8)),
                () -> assertTrue(out.get(9).startsWith("[10:c8] *** pong"), out.get(9)));
    }

    @Test
    void shouldStopEveryCommandOfASessionThatCloses() {
        session.submit("motoron; robot.drive(0.1, 0.5),");
        step(0.1);
        assertTrue(dog.walking());

        session.close();
        step(0.01);

        assertFalse(dog.walking());
    }

    @Test
    void shouldMoveAJointOverTheTimeGivenAndReportItsEnd() {
        session.submit("motoron; c1+end: headPan.val = 30 time:400,");
        step(0.21);
        assertEquals(15, dog.joint("headPan").angle(), 1e-6, "half way after 0.2 s");

        step(0.2);

        assertEquals(30, dog.joint("headPan").angle(), 1e-9);
        assertEquals(List.of("[410:c1] *** end"), out);
    }

    @Test
    void shouldSurviveRandomBytesAndAnswerTheStatementsThatFollow() {
        java.util.SplittableRandom random = new java.util.SplittableRandom(16);
        byte[] alphabet = "{}();,|&:+-*/=. \n\"0123456789robot.walkheadPan.valstopeveryloopmsBIN".getBytes(java.nio.charset.StandardCharsets.US_ASCII);
        for (int round = 0; round < 500; round++) {
            byte[] chunk = new byte[random.nextInt(1, 64)];
            for (int i = 0; i < chunk.length; i++) {
                chunk[i] = random.nextBoolean() ? alphabet[random.nextInt(alphabet.length)] : (byte) random.nextInt(256);
            }
            session.submit(chunk, 0, chunk.length);
            step(0.01);
        }
        UrbiKernel.Session fresh = kernel.open("after", (millis, tag, kind, text) -> out.add(tag + " " + text));
        out.clear();

        fresh.submit("p1: ping;");
        step(0.01);

        assertTrue(out.stream().anyMatch(line -> line.startsWith("p1 pong time=")), out::toString);
    }

    @Test
    void shouldDropAFloodBeyondItsQueueWithOneErrorAndAnswerTheRest() {
        session.submit("p: ping;".repeat(UrbiKernel.MAX_PENDING + 5000));
        step(0.01);

        long pongs = out.stream().filter(line -> line.contains(":p] *** pong")).count();
        List<String> errors = out.stream().filter(line -> line.contains("!!!")).toList();
        assertEquals(UrbiKernel.MAX_PENDING, pongs);
        assertEquals(List.of("[10] !!! too many commands waiting (" + UrbiKernel.MAX_PENDING + "); 5000 dropped"), errors);

        out.clear();
        session.submit("p1: ping;");
        step(0.01);
        assertEquals(1, out.size(), out::toString);
    }

    /**
     * Nested loops start a new inner loop at every turn of each outer one: without a bound on the
     * session's jobs, eight of them multiply to tens of thousands of jobs (and pongs) within a
     * tenth of a second, and thirty to billions. The session keeps to {@value UrbiKernel#MAX_JOBS}
     * jobs, refuses what would exceed them, and a stop ends them all.
     */
    @Test
    void shouldKeepNestedLoopsWithinTheSessionsJobsAndStopThemOnRequest() {
        session.submit("l1: " + "loop ".repeat(8) + "ping,");
        step(0.1);
        assertTrue(session.jobs() <= UrbiKernel.MAX_JOBS, () -> session.jobs() + " jobs");
        out.clear();

        step(0.01);
        assertTrue(out.size() <= UrbiKernel.MAX_JOBS, () -> out.size() + " messages in one step");
        session.submit("r1: 1 + 2,");
        step(0.01);
        assertTrue(out.stream().anyMatch(line -> line.endsWith(":r1] !!! too many commands running (" + UrbiKernel.MAX_JOBS + "); stop some first")),
                () -> out.subList(Math.max(0, out.size() - 5), out.size()).toString());

        session.submit("stop l1,");
        step(0.01);
        assertEquals(0, session.jobs());
        out.clear();
        session.submit("r2: 1 + 2,");
        step(0.01);
        assertEquals(List.of("[140:r2] 3.000000"), out);
    }

    /**
     * Mutation fuzzing from valid input: every statement the driver sends and a person at a terminal
     * types, each mutated 200 times (bytes changed, inserted from URBI's punctuation, deleted,
     * pieces repeated, cut short), is sent to a session of its own. The server core must answer each
     * with its normal replies or {@code !!!} errors, never with an internal error (which closes the
     * session), and must stay bounded; afterwards it answers as usual.
     */
    @Test
    void shouldAnswerMutatedStatementsWithRepliesOrErrorsNeverAnInternalError() {
        List<String> seeds = List.of(
                "o1+end: { motoron; robot.watchdogInterval = 0.5 },\n",
                "c7+end: { robot.walk(0.5, 0.15) },\n",
                "c8+end: { robot.turn(-1.570796, 1) },\n",
                "c9+end: { robot.arc(0.3, 1.5, 0.1) },\n",
                "c10+end: { robot.drive(0.1, 0.5) },\n",
                "stop c7,\nx9+end: { robot.stop() },\n",
                "s2: every(100ms) distanceFar.val,\n",
                "r3: headPan.val;\n",
                "c11+end: { headPan.val = 30 time:400 },\n",
                "c12+end: { headPan.val = 0 time:400 & headTilt.val = 0 time:400 },\n",
                "c13+end: { tailPan.val = 40 time:250; tailPan.val = -40 time:500; tailPan.val = 0 time:250 },\n",
                "legLF1.val = 10 speed:30; loop accelX.val, robot.sit(); robot.stand(); robot.lie(); robot.kick();\n",
                "p: ping; motoroff; motors on; x = 2 * (3 + -1) / 4; // a comment\n",
                "speaker.val = BIN 4 raw\nabcd;\n");
        byte[] punctuation = "{}();,|&:+-*/=.\"\n 0123456789".getBytes(java.nio.charset.StandardCharsets.US_ASCII);
        java.util.SplittableRandom random = new java.util.SplittableRandom(1616);
        int inputs = 0;
        for (String seed : seeds) {
            byte[] valid = seed.getBytes(java.nio.charset.StandardCharsets.US_ASCII);
            for (int round = 0; round < 200; round++) {
                byte[] input = mutate(valid, random, punctuation);
                List<String> said = new ArrayList<>();
                UrbiKernel.Session s = kernel.open("fuzz", (millis, tag, kind, text) -> said.add(kind + " " + text));
                s.submit(input, 0, input.length);
                step(0.05);
                s.close();
                step(0.01);
                inputs++;
                assertTrue(said.stream().noneMatch(line -> line.contains("internal error")),
                        () -> "input " + printable(input) + " caused " + said);
            }
        }
        out.clear();
        session.submit("p1: ping;");
        step(0.01);

        assertEquals(seeds.size() * 200, inputs);
        assertTrue(out.stream().anyMatch(line -> line.startsWith("[") && line.contains(":p1] *** pong time=")), out::toString);
    }

    /** One to four mutations of a valid input. */
    private static byte[] mutate(byte[] valid, java.util.SplittableRandom random, byte[] punctuation) {
        byte[] x = valid.clone();
        for (int m = random.nextInt(1, 5); m > 0; m--) {
            int at = x.length == 0 ? 0 : random.nextInt(x.length);
            x = switch (random.nextInt(5)) {
                case 0 -> {                                   // change a byte
                    if (x.length > 0) {
                        x[at] = random.nextBoolean() ? punctuation[random.nextInt(punctuation.length)] : (byte) random.nextInt(256);
                    }
                    yield x;
                }
                case 1 -> splice(x, at, at, new byte[] {punctuation[random.nextInt(punctuation.length)]});   // insert
                case 2 -> splice(x, at, Math.min(x.length, at + random.nextInt(1, 4)), new byte[0]);         // delete
                case 3 -> splice(x, at, at, java.util.Arrays.copyOfRange(x, at, Math.min(x.length, at + random.nextInt(1, 12)))); // repeat
                default -> java.util.Arrays.copyOf(x, at);     // cut short
            };
        }
        return x;
    }

    private static byte[] splice(byte[] x, int from, int to, byte[] with) {
        byte[] y = new byte[x.length - (to - from) + with.length];
        System.arraycopy(x, 0, y, 0, from);
        System.arraycopy(with, 0, y, from, with.length);
        System.arraycopy(x, to, y, from + with.length, x.length - to);
        return y;
    }

    private static String printable(byte[] input) {
        StringBuilder sb = new StringBuilder("\"");
        for (byte v : input) {
            int c = v & 0xFF;
            sb.append(c >= 32 && c < 127 ? String.valueOf((char) c) : String.format("\\x%02x", c));
        }
        return sb.append('"').toString();
    }
}
