package io.robomw.sim.legged;

import io.robomw.sim.legged.UrbiParser.Assign;
import io.robomw.sim.legged.UrbiParser.Block;
import io.robomw.sim.legged.UrbiParser.Call;
import io.robomw.sim.legged.UrbiParser.Evaluate;
import io.robomw.sim.legged.UrbiParser.Every;
import io.robomw.sim.legged.UrbiParser.Keyword;
import io.robomw.sim.legged.UrbiParser.Neg;
import io.robomw.sim.legged.UrbiParser.Num;
import io.robomw.sim.legged.UrbiParser.Ref;
import io.robomw.sim.legged.UrbiParser.Statement;
import io.robomw.sim.legged.UrbiParser.Stop;
import io.robomw.sim.legged.UrbiParser.UrbiSyntaxException;
import org.junit.jupiter.api.Test;

import java.util.List;
import java.util.Map;
import java.util.Set;

import static org.junit.jupiter.api.Assertions.assertAll;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/** The URBI subset the emulated Aibo answers, as the driver and the documents write it. */
class UrbiParserTest {

    @Test
    void shouldReadATaggedBlockWithTheEndFlag() throws Exception {
        Statement s = UrbiParser.parse("c12+end: { robot.walk(0.5, -0.15) }", ',');

        assertAll(
                () -> assertEquals("c12", s.tag()),
                () -> assertEquals(Set.of("end"), s.flags()),
                () -> assertEquals(',', s.terminator()),
                () -> assertEquals(new Block(List.of(new Statement("", Set.of(),
                        new Evaluate(new Call("robot.walk", List.of(new Num(0.5, false), new Neg(new Num(0.15, false))))), ';'))), s.command()));
    }

    @Test
    void shouldReadAnAssignmentWithItsModifiersAndTimes() throws Exception {
        Statement s = UrbiParser.parse("headPan.val = 30 time:1000 speed: 2s", ';');

        Assign a = (Assign) s.command();
        assertEquals("headPan.val", a.target());
        assertEquals(new Num(30, false), a.value());
        assertEquals(Map.of("time", new Num(1000, false), "speed", new Num(2, true)), a.modifiers());
        assertEquals(1.0, ((Num) a.modifiers().get("time")).seconds(), "a bare time is milliseconds, as in URBI 1");
    }

    @Test
    void shouldReadStreamsStopsAndKeywords() throws Exception {
        assertEquals(new Every(0.1, new Statement("", Set.of(), new Evaluate(new Ref("accelX.val")), ';')),
                UrbiParser.parse("s3: every(100ms) accelX.val", ',').command());
        assertEquals(new Stop("c12"), UrbiParser.parse("stop c12", ',').command());
        assertEquals(new Keyword("motoron"), UrbiParser.parse("motors on", ';').command());
        assertEquals(new Keyword("ping"), UrbiParser.parse("r9: ping", ';').command());
    }

    @Test
    void shouldKeepTheTagOfAStatementItCannotParse() {
        UrbiSyntaxException e = assertThrows(UrbiSyntaxException.class, () -> UrbiParser.parse("c4: robot.walk(0.5,", ','));

        assertEquals("c4", e.tag());
        assertTrue(e.getMessage().startsWith("syntax error: expected a value at the end"), e.getMessage());
    }

    @Test
    void shouldRefuseWhatIsNotInTheSubset() {
        assertAll(
                () -> assertThrows(UrbiSyntaxException.class, () -> UrbiParser.parse("this is not urbi", ';')),
                () -> assertThrows(UrbiSyntaxException.class, () -> UrbiParser.parse("x = 3 parsecs", ';')),
                () -> assertThrows(UrbiSyntaxException.class, () -> UrbiParser.parse("every(x) ping", ';')),
                () -> assertThrows(UrbiSyntaxException.class, () -> UrbiParser.parse("x = \"open", ';')),
                () -> assertThrows(UrbiSyntaxException.class, () -> UrbiParser.parse("x\uFFFD", ';')),
                () -> assertThrows(UrbiSyntaxException.class, () -> UrbiParser.parse("x = 1e999", ';')));
    }

    @Test
    void shouldReadNestingUpToTheLimit() throws Exception {
        String parens = "x = " + "(".repeat(60) + "1" + ")".repeat(60);
        String blocks = "{".repeat(60) + "ping" + "}".repeat(60);

        assertEquals(new Num(1, false), ((Assign) UrbiParser.parse(parens, ';').command()).value());
        assertTrue(UrbiParser.parse(blocks, ';').command() instanceof Block);
    }

    @Test
    void shouldRefuseNestingDeeperThanTheLimitWithoutOverflowingTheStack() {
        String deep = "{".repeat(10_000) + "}".repeat(10_000);
        String parens = "x = " + "(".repeat(10_000) + "1" + ")".repeat(10_000);

        UrbiSyntaxException blocks = assertThrows(UrbiSyntaxException.class, () -> UrbiParser.parse(deep, ';'));
        UrbiSyntaxException exprs = assertThrows(UrbiSyntaxException.class, () -> UrbiParser.parse(parens, ';'));

        assertTrue(blocks.getMessage().contains("nesting deeper than 64"), blocks.getMessage());
        assertTrue(exprs.getMessage().contains("nesting deeper than 64"), exprs.getMessage());
    }
}
