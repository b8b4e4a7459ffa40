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
}
