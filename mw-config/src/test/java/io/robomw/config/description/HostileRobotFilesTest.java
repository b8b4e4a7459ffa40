package io.robomw.config.description;

import io.robomw.config.description.DescriptionException.Problem;
import io.robomw.config.yaml.YamlDocument;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

import java.io.IOException;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.List;

import static org.junit.jupiter.api.Assertions.assertAll;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTimeoutPreemptively;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * Robot files from the bad-input campaign of issue 15: each one used to crash the loader (a stack
 * overflow, an {@code IllegalArgumentException} with a trace), be read without end, or be accepted
 * wrongly (a sensor silently dropped, a duplicate key, infinite sizes). Each is now refused with
 * file, line and column, what is wrong and what to write, and nothing else: no Java exception's
 * name, no line break inside one problem.
 */
class HostileRobotFilesTest {

    private static final String SOURCE = "robot.yaml";
    private static final Duration QUICK = Duration.ofSeconds(10);

    private final RobotDescriptionLoader loader = new RobotDescriptionLoader();

    @TempDir
    Path dir;

    private DescriptionException refused(String yaml) {
        return assertTimeoutPreemptively(QUICK, () -> assertThrows(DescriptionException.class, () -> loader.parse(yaml, SOURCE)));
    }

    private DescriptionException refusedFile(Path file) {
        return assertTimeoutPreemptively(QUICK, () -> assertThrows(DescriptionException.class, () -> loader.load(file)));
    }

    private static Problem only(DescriptionException e) {
        assertEquals(1, e.problems().size(), e::getMessage);
        return e.problems().get(0);
    }

    private static void assertAt(int line, int column, String fragment, Problem p) {
        assertAll(
                () -> assertEquals(line, p.line(), () -> "line of " + p),
                () -> assertEquals(column, p.column(), () -> "column of " + p),
                () -> assertTrue(p.message().contains(fragment), () -> "expected '" + fragment + "' in " + p));
        assertPlain(p);
    }

    /** One line, and words for a user: no Java exception named. */
    private static void assertPlain(Problem p) {
        assertFalse(p.message().contains("\n"), p::toString);
        assertFalse(p.message().matches("(?s).*(Exception|Error|java\\.).*"), p::toString);
    }

    // ---- aliases ----

    @Test
    void selfReferencingAliasInConnectionIsRefusedAtTheAlias() {
        Problem p = only(refused("""
                name: x
                platform: nxt
                connection: &c { self: *c }
                """));

        assertAt(3, 24, "the alias *c is inside the value anchored &c", p);
    }

    @Test
    void selfReferencingAliasInSensorOptionsIsRefusedAtTheAlias() {
        Problem p = only(refused("""
                name: x
                platform: nxt
                sensors:
                  - name: s
                    type: touch
                    position: front
                    port: S1
                    options: &o
                      deeper: [1, 2, { again: *o }]
                """));

        assertAt(9, 31, "*o", p);
    }

    @Test
    void aliasToNoAnchorIsRefusedAtTheAlias() {
        assertAt(3, 13, "refers to no anchor", only(refused("name: x\nplatform: nxt\nconnection: *nowhere\n")));
    }

    @Test
    void aliasBombIsRefusedAtTheAliasWhereItPassesTheLimit() {
        StringBuilder yaml = new StringBuilder("name: x\nplatform: nxt\nconnection:\n  a0: &a0 [lol, lol, lol, lol, lol, lol, lol, lol, lol, lol]\n");
        for (int i = 1; i < 9; i++) {
            yaml.append("  a").append(i).append(": &a").append(i).append(" [").append(("*a" + (i - 1) + ", ").repeat(4)).append("*a").append(i - 1).append("]\n");
        }

        Problem p = only(refused(yaml.toString()));

        assertTrue(p.message().contains("alias"), p::toString);
        assertTrue(p.line() > 4, p::toString);
        assertPlain(p);
    }

    @Test
    void deepNestingIsRefusedWhereItGoesTooDeep() {
        String yaml = "name: x\nplatform: nxt\nconnection: " + "[".repeat(5000) + "]".repeat(5000) + "\n";

        Problem p = only(refused(yaml));

        assertTrue(p.message().contains("nested more than " + YamlDocument.MAX_DEPTH), p::toString);
        assertEquals(3, p.line());
        assertPlain(p);
    }

    // ---- numbers ----

    @Test
    void gearRatioThatOverflowsToInfinityIsRefusedNotThrown() {
        Problem p = only(refused("""
                name: x
                platform: nxt
                drive:
                  wheel_diameter: 0.056
                  track_width: 0.1
                  gear_ratio: 1.0e+400
                  max_speed: 0.3
                  left: {port: B}
                  right: {port: C}
                """));

        assertAt(6, 15, "'drive.gear_ratio' must be > 0 (0.001 to 10000), got '1.0e+400', a number too large to use", p);
    }

    @Test
    void fourHundredDigitIntegerIsRefusedAndQuotedShortly() {
        String digits = "9".repeat(401);
        Problem p = only(refused("name: x\nplatform: nxt\nbody: {length: " + digits + "}\n"));

        assertAt(3, 16, "'body.length' must be > 0 metres (0.001 to 100)", p);
        assertTrue(p.message().length() < 300, p::toString);
    }

    @Test
    void absurdFiniteSizesAreCheckedAgainstTheirDocumentedRanges() {
        DescriptionException e = refused("""
                name: x
                platform: nxt
                drive:
                  wheel_diameter: 0.056
                  track_width: 0.1
                  gear_ratio: 1.0e+300
                  max_speed: 0.3
                  encoder_ticks_per_revolution: 2000000000
                  left: {port: B}
                  right: {port: C}
                body: {length: 1.0e+300, width: 0.1, mass: 1.0e+300, friction: 1.0e+300}
                actuators:
                  - name: arm
                    port: A
                    actions:
                      up: {degrees: 1.0e+300, speed: 1.0e+300}
                """);

        List<String> where = e.problems().stream().map(p -> p.line() + ":" + p.message().substring(0, p.message().indexOf('\'', 1) + 1)).toList();
        assertEquals(List.of("6:'drive.gear_ratio'", "8:'drive.encoder_ticks_per_revolution'", "11:'body.length'", "11:'body.mass'",
                "11:'body.friction'", "16:'actuators[0].actions.up.degrees'", "16:'actuators[0].actions.up.speed'"), where, e::getMessage);
        e.problems().forEach(HostileRobotFilesTest::assertPlain);
    }

    @Test
    void infiniteNumberInsideConnectionIsRefused() {
        assertAt(3, 20, "'connection.baud' is '1e999', a number too large to use",
                only(refused("name: x\nplatform: nxt\nconnection: {baud: 1e999}\n")));
    }

    // ---- empty values, duplicate keys ----

    @Test
    void sensorWithEmptyPortIsAnErrorNotADroppedSensor() {
        Problem p = only(refused("""
                name: x
                platform: nxt
                sensors:
                  - {name: s, type: touch, position: front, port: ~}
                """));

        assertAt(4, 45, "'sensors[0].port' has no value; write a text value", p);
    }

    @Test
    void requiredNumberWithNoValueIsAnErrorNotAMissingDrive() {
        Problem p = only(refused("""
                name: x
                platform: nxt
                drive:
                  wheel_diameter:
                  track_width: 0.1
                  max_speed: 0.3
                  left: {port: B}
                  right: {port: C}
                """));

        assertAt(4, 3, "'drive.wheel_diameter' has no value; write a number > 0 metres", p);
    }

    @Test
    void optionalKeyWithNoValueSaysToWriteOneOrLeaveItOut() {
        assertAt(3, 1, "'cycle_hz' has no value; write a number between 1 and 1000, or leave the key out",
                only(refused("name: x\nplatform: nxt\ncycle_hz:\n")));
    }

    @Test
    void emptyValueInsideConnectionIsAnError() {
        assertAt(3, 23, "'connection.baud' has no value", only(refused("name: x\nplatform: nxt\nconnection: {port: a, baud: }\n")));
    }

    @Test
    void duplicateKeyInsideConnectionIsAnError() {
        assertAt(3, 23, "key 'connection.port' appears twice", only(refused("name: x\nplatform: nxt\nconnection: {port: a, port: b}\n")));
    }

    @Test
    void duplicateKeyInsideSensorOptionsIsAnError() {
        Problem p = only(refused("""
                name: x
                platform: nxt
                sensors:
                  - {name: s, type: touch, position: front, port: S1, options: {rate_hz: 1, rate_hz: 2}}
                """));

        assertAt(4, 77, "key 'sensors[0].options.rate_hz' appears twice", p);
    }

    @Test
    void keyWithLineBreaksStaysOnOneLineOfTheReport() {
        Problem p = only(refused("name: x\nplatform: nxt\n\"bad\\nkey\\u0007\": 1\n"));

        assertTrue(p.message().contains("unknown key 'bad\\nkey\\u0007'"), p::toString);
        assertPlain(p);
    }

    // ---- files ----

    @Test
    void fileLargerThanOneMebibyteIsRefusedWithoutReadingItAll() throws IOException {
        Path big = dir.resolve("big.yaml");
        Files.writeString(big, "name: x\nplatform: nxt\nconnection: {port: '" + "a".repeat(10_000_000) + "'}\n");

        Problem p = only(refusedFile(big));

        assertEquals(1, p.line());
        assertTrue(p.message().contains("larger than 1 MiB"), p::toString);
    }

    @Test
    void endlessDeviceIsRefusedWithoutReadingIt() {
        Path zero = Path.of("/dev/zero");
        assertTrue(Files.exists(zero), "this test runs where /dev/zero exists (Linux, macOS)");

        Problem p = only(refusedFile(zero));

        assertTrue(p.message().contains("not a regular file"), p::toString);
    }

    /** Issue 37: opening a FIFO nobody writes to waits forever; it is refused at once. */
    @Test
    void fifoIsRefusedAtOnce() throws Exception {
        Path fifo = dir.resolve("robot.yaml");
        Process mkfifo = new ProcessBuilder("mkfifo", fifo.toString()).start();
        org.junit.jupiter.api.Assumptions.assumeTrue(mkfifo.waitFor(10, java.util.concurrent.TimeUnit.SECONDS) && mkfifo.exitValue() == 0,
                "mkfifo is available (Linux, macOS)");

        Problem p = java.util.concurrent.CompletableFuture.supplyAsync(() -> only(refusedFile(fifo))).get(10, java.util.concurrent.TimeUnit.SECONDS);

        assertTrue(p.message().contains("not a regular file (a FIFO"), p::toString);
    }

    @Test
    void fileOfExactlyTheLimitIsStillRead() throws IOException {
        Path file = dir.resolve("limit.yaml");
        String head = "name: x\nplatform: nxt\n# ";
        Files.writeString(file, head + "c".repeat(YamlDocument.MAX_FILE_BYTES - head.length() - 1) + "\n");

        assertEquals("x", loader.load(file).name());
    }

    @Test
    void nonUtf8FileIsRefusedAtTheFirstBadByte() throws IOException {
        Path latin1 = dir.resolve("latin1.yaml");
        Files.write(latin1, "name: x\nplatform: nxt\nconnection: {port: 'Gr\u00fcn'}\n".getBytes(StandardCharsets.ISO_8859_1));

        Problem p = only(refusedFile(latin1));

        assertAt(3, 23, "not UTF-8 text: byte 0xFC", p);
        assertTrue(p.message().contains("save the file as UTF-8"), p::toString);
    }

    @Test
    void directoryAndMissingFileAreNamedInWords() {
        assertAt(1, 1, "a directory", only(refusedFile(dir)));
        assertAt(1, 1, "no such file", only(refusedFile(dir.resolve("nowhere.yaml"))));
    }

    @Test
    void manyProblemsAreListedUpToALimit() {
        StringBuilder yaml = new StringBuilder("name: x\nplatform: nxt\n");
        for (int i = 0; i < 5000; i++) {
            yaml.append("k").append(i).append(": 1\n");
        }

        DescriptionException e = refused(yaml.toString());

        assertEquals(101, e.problems().size());
        assertTrue(e.problems().get(100).message().contains("and 4900 more problems"), e::getMessage);
    }
}
