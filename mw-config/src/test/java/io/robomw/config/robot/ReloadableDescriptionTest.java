package io.robomw.config.robot;

import io.robomw.api.spi.FailurePolicy;
import io.robomw.config.description.DescriptionException;
import io.robomw.config.description.DifferentialDrive;
import io.robomw.config.description.RobotDescription;
import io.robomw.config.description.RobotDescriptionLoader;
import io.robomw.config.robot.ReloadableDescription.ReloadOutcome;
import io.robomw.testkit.Await;
import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.nio.file.StandardCopyOption;
import java.util.ArrayList;
import java.util.List;
import java.util.Optional;
import java.time.Duration;
import java.util.concurrent.CopyOnWriteArrayList;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.atomic.AtomicInteger;
import java.util.concurrent.TimeUnit;
import java.util.function.Predicate;

import static org.junit.jupiter.api.Assertions.assertAll;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertSame;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;
import static org.junit.jupiter.api.Assertions.fail;

class ReloadableDescriptionTest {

    private static final long DEADLINE_SECONDS = 10;
    private static final Duration DEADLINE = Duration.ofSeconds(DEADLINE_SECONDS);

    @TempDir
    Path dir;

    private final List<ReloadableDescription> opened = new ArrayList<>();

    @AfterEach
    void closeAll() {
        opened.forEach(ReloadableDescription::close);
    }

    private static String robot(String name, String platform, double wheelDiameter, String leftPort) {
        return """
                name: %s
                platform: %s
                drive:
                  wheel_diameter: %s
                  track_width: 0.112
                  max_speed: 0.3
                  left: {port: %s}
                  right: {port: C}
                sensors:
                  - {name: sonar, type: sonar, position: front, port: 4, conversion: {scale: 0.01}}
                """.formatted(name, platform, wheelDiameter, leftPort);
    }

    private static String robot(double wheelDiameter) {
        return robot("scout", "nxt", wheelDiameter, "B");
    }

    private Path write(String yaml) throws IOException {
        return Files.writeString(dir.resolve("scout.yaml"), yaml);
    }

    private ReloadableDescription open(String yaml) throws IOException {
        ReloadableDescription d = new ReloadableDescription(write(yaml), new RobotDescriptionLoader());
        opened.add(d);
        return d;
    }

    private ReloadableDescription open(String yaml, ReloadableDescription.Loader loader, FailurePolicy policy) throws IOException {
        ReloadableDescription d = new ReloadableDescription(write(yaml), loader, policy);
        opened.add(d);
        return d;
    }

    /** A failure policy that keeps what it is told, as {@code owner: failure}. */
    private static final class RecordingPolicy implements FailurePolicy {
        final List<String> survived = new CopyOnWriteArrayList<>();
        final List<String> died = new CopyOnWriteArrayList<>();

        @Override
        public void survived(String owner, Throwable failure) {
            survived.add(owner + ": " + failure);
        }

        @Override
        public void died(String owner, Throwable failure) {
            died.add(owner + ": " + failure);
        }

        @Override
        public long count() {
            return survived.size() + died.size();
        }
    }

    private static double wheelDiameter(RobotDescription d) {
        return d.drive().map(DifferentialDrive::wheelDiameter).orElseThrow();
    }

    /** A latch that opens when a description matching {@code condition} is accepted. */
    private static CountDownLatch whenAccepted(ReloadableDescription d, Predicate<RobotDescription> condition) {
        CountDownLatch latch = new CountDownLatch(1);
        d.addListener(next -> {
            if (condition.test(next)) {
                latch.countDown();
            }
        });
        return latch;
    }

    private static void await(CountDownLatch latch, String what) throws InterruptedException {
        if (!latch.await(DEADLINE_SECONDS, TimeUnit.SECONDS)) {
            fail("not within " + DEADLINE_SECONDS + " s: " + what);
        }
    }

    private static Optional<Thread> watchThread(String robotName) {
        return Thread.getAllStackTraces().keySet().stream().filter(t -> t.getName().equals("robomw-reload-" + robotName)).findFirst();
    }

    // ---- reload() ----

    @Test
    void shouldRefuseToOpenInvalidFile() throws IOException {
        Path file = write("name: scout\n");

        assertThrows(DescriptionException.class, () -> new ReloadableDescription(file, new RobotDescriptionLoader()));
    }

    @Test
    void shouldAcceptChangedWheelDiameter() throws IOException {
        ReloadableDescription d = open(robot(0.056));
        write(robot(0.081));

        ReloadOutcome outcome = d.reload();

        assertEquals(ReloadOutcome.SWAPPED, outcome);
        assertEquals(0.081, wheelDiameter(d.current()));
    }

    @Test
    void shouldTellListenersAboutAcceptedChange() throws IOException {
        ReloadableDescription d = open(robot(0.056));
        List<RobotDescription> seen = new ArrayList<>();
        d.addListener(seen::add);
        write(robot(0.081));

        d.reload();

        assertEquals(List.of(d.current()), seen);
    }

    @Test
    void shouldRejectYamlErrorWithFileLineAndColumnAndKeepOldDescription() throws IOException {
        ReloadableDescription d = open(robot(0.056));
        RobotDescription before = d.current();
        write("""
                name: scout
                platform: nxt
                cycle_hz: 50
                  watchdog: 1
                """);

        ReloadOutcome outcome = d.reload();

        assertEquals(ReloadOutcome.Result.REJECTED, outcome.result());
        assertTrue(outcome.message().startsWith(d.file() + ":4:11: not valid YAML"), outcome.message());
        assertSame(before, d.current());
    }

    @Test
    void shouldRejectInvalidValueAndKeepOldDescription() throws IOException {
        ReloadableDescription d = open(robot(0.056));
        RobotDescription before = d.current();
        write(robot(-0.056));

        ReloadOutcome outcome = d.reload();

        assertFalse(outcome.accepted());
        assertTrue(outcome.message().startsWith(d.file() + ":4:19: 'drive.wheel_diameter' must be > 0"), outcome.message());
        assertSame(before, d.current());
    }

    @Test
    void shouldRejectPlatformChangeSayingRestart() throws IOException {
        ReloadableDescription d = open(robot(0.056));
        RobotDescription before = d.current();
        write(robot("scout", "ev3", 0.056, "B"));

        ReloadOutcome outcome = d.reload();

        assertFalse(outcome.accepted());
        assertTrue(outcome.message().contains("platform (nxt -> ev3)"), outcome.message());
        assertTrue(outcome.message().contains("restart"), outcome.message());
        assertSame(before, d.current());
    }

    @Test
    void shouldRejectMotorPortChangeSayingRestart() throws IOException {
        ReloadableDescription d = open(robot(0.056));
        RobotDescription before = d.current();
        write(robot("scout", "nxt", 0.056, "A"));

        ReloadOutcome outcome = d.reload();

        assertFalse(outcome.accepted());
        assertTrue(outcome.message().contains("motor ports ([B, C] -> [A, C])"), outcome.message());
        assertTrue(outcome.message().contains("restart"), outcome.message());
        assertSame(before, d.current());
    }

    @Test
    void shouldRejectMessagingChangeSayingRestart() throws IOException {
        ReloadableDescription d = open(robot(0.056));
        RobotDescription before = d.current();
        write(robot(0.056) + "messaging: {listen: tcp://127.0.0.1:7100}\n");

        ReloadOutcome outcome = d.reload();

        assertFalse(outcome.accepted());
        assertTrue(outcome.message().contains("messaging section") && outcome.message().contains("restart"), outcome.message());
        assertSame(before, d.current());
    }

    @Test
    void shouldRejectNameChangeSayingRestart() throws IOException {
        ReloadableDescription d = open(robot(0.056));
        write(robot("rover", "nxt", 0.056, "B"));

        ReloadOutcome outcome = d.reload();

        assertFalse(outcome.accepted());
        assertTrue(outcome.message().contains("restart"), outcome.message());
        assertEquals("scout", d.current().name());
    }

    /** A legged robot whose walking command is {@code move}, over {@code drive}. */
    private static String dog(String move, String drive) {
        return """
                name: dog
                platform: aibo
                %s
                sensors:
                  - {name: head_far, type: infrared, position: front, port: distanceFar, conversion: {scale: 0.001}}
                """.formatted(drive.formatted(move));
    }

    private static final String LEGGED = """
            drive: {type: legged, max_speed: 0.2, max_turn_rate: 1.2, commands: {move: "%s", turn: "robot.turn(${angle}, ${speed})"}}""";

    @Test
    void shouldApplyAnotherFirmwaresWalkingCommandToTheNextWalk() throws IOException {
        ReloadableDescription d = open(dog("robot.walk(${distance}, ${speed})", LEGGED));
        FakeHighLevelPlatform platform = new FakeHighLevelPlatform();
        ConfiguredRobot robot = ConfiguredRobot.withComponents(d::current, platform, null);
        robot.moveAsync(0.5, 0.1);
        write(dog("walk ${distance:mm} ${speed:mm}", LEGGED));

        ReloadOutcome outcome = d.reload();
        robot.moveAsync(0.5, 0.1);

        assertTrue(outcome.accepted(), outcome.message());
        assertEquals(List.of("robot.walk(0.5, 0.1)", "walk 500 100"), platform.commands.stream().map(c -> c.text()).toList());
    }

    @Test
    void shouldRejectChangingLegsForWheelsSayingRestart() throws IOException {
        ReloadableDescription d = open(dog("robot.walk(${distance}, ${speed})", LEGGED));
        RobotDescription before = d.current();
        write(dog("", "drive: {wheel_diameter: 0.056, track_width: 0.112, max_speed: 0.3, left: {port: B}, right: {port: C}}%s"));

        ReloadOutcome outcome = d.reload();

        assertFalse(outcome.accepted());
        assertTrue(outcome.message().contains("drive's type (legged -> differential)") && outcome.message().contains("restart"), outcome.message());
        assertSame(before, d.current());
    }

    @Test
    void shouldRejectReloadOfDeletedFileAndKeepOldDescription() throws IOException {
        ReloadableDescription d = open(robot(0.056));
        RobotDescription before = d.current();
        Files.delete(d.file());

        ReloadOutcome outcome = d.reload();

        assertFalse(outcome.accepted());
        assertTrue(outcome.message().contains("no such file"), outcome.message());
        assertSame(before, d.current());
    }

    @Test
    void shouldReportUnchangedFileAsAcceptedWithoutChange() throws IOException {
        ReloadableDescription d = open(robot(0.056));
        RobotDescription before = d.current();

        ReloadOutcome outcome = d.reload();

        assertEquals(ReloadOutcome.UNCHANGED, outcome);
        assertSame(before, d.current());
    }

    @Test
    void shouldTreatCommentOnlyEditAsUnchanged() throws IOException {
        ReloadableDescription d = open(robot(0.056));
        write("# tuned on Monday\n" + robot(0.056));

        ReloadOutcome outcome = d.reload();

        assertEquals(ReloadOutcome.Result.UNCHANGED, outcome.result());
    }

    // ---- watch() ----

    @Test
    void shouldReloadWhenWatchedFileIsRewritten() throws Exception {
        ReloadableDescription d = open(robot(0.056));
        CountDownLatch reloaded = whenAccepted(d, next -> wheelDiameter(next) == 0.081);
        d.watch();

        write(robot(0.081));

        await(reloaded, "the rewritten file is reloaded");
        assertEquals(0.081, wheelDiameter(d.current()));
    }

    @Test
    void shouldReloadWhenWatchedFileIsReplacedByRename() throws Exception {
        ReloadableDescription d = open(robot(0.056));
        CountDownLatch reloaded = whenAccepted(d, next -> wheelDiameter(next) == 0.081);
        d.watch();

        Path next = Files.writeString(dir.resolve("scout.yaml.tmp"), robot(0.081));
        Files.move(next, d.file(), StandardCopyOption.REPLACE_EXISTING, StandardCopyOption.ATOMIC_MOVE);

        await(reloaded, "the replaced file is reloaded");
        assertEquals(0.081, wheelDiameter(d.current()));
    }

    @Test
    void shouldApplyValidRewriteThatFollowsInvalidOne() throws Exception {
        ReloadableDescription d = open(robot(0.056));
        CountDownLatch reloaded = whenAccepted(d, next -> wheelDiameter(next) == 0.081);
        d.watch();

        write(robot(-1));
        write(robot(0.081));

        await(reloaded, "the valid rewrite is reloaded");
        assertEquals(0.081, wheelDiameter(d.current()));
    }

    @Test
    void shouldStartOneWatchThreadWhenWatchIsCalledTwice() throws Exception {
        ReloadableDescription d = open(robot("twice", "nxt", 0.056, "B"));

        d.watch();
        d.watch();

        assertEquals(1, Thread.getAllStackTraces().keySet().stream().filter(t -> t.getName().equals("robomw-reload-twice")).count());
    }

    @Test
    void shouldStopWatchThreadOnClose() throws Exception {
        ReloadableDescription d = open(robot("closing", "nxt", 0.056, "B"));
        d.watch();
        Thread watcher = watchThread("closing").orElseThrow(() -> new AssertionError("watch() started no thread"));

        d.close();

        watcher.join(TimeUnit.SECONDS.toMillis(DEADLINE_SECONDS));
        assertFalse(watcher.isAlive(), "the watch thread still runs after close()");
    }

    @Test
    void shouldReportAListenersFailureToThePolicyAndGoOnWatching() throws Exception {
        RecordingPolicy policy = new RecordingPolicy();
        ReloadableDescription d = open(robot("listened", "nxt", 0.056, "B"), new RobotDescriptionLoader()::load, policy);
        IllegalStateException broken = new IllegalStateException("a listener's bug");
        d.addListener(next -> {
            if (wheelDiameter(next) == 0.081) {
                throw broken;
            }
        });
        CountDownLatch second = whenAccepted(d, next -> wheelDiameter(next) == 0.1);
        d.watch();

        write(robot("listened", "nxt", 0.081, "B"));
        Await.until("the listener's failure reaches the policy", DEADLINE, () -> !policy.survived.isEmpty());
        write(robot("listened", "nxt", 0.1, "B"));

        await(second, "the next change is still reloaded and heard by the other listener");
        assertAll(
                () -> assertEquals(List.of("robomw-reload-listened: " + broken), policy.survived),
                () -> assertEquals(List.of(), policy.died));
    }

    @Test
    void shouldReportAnUncheckedFailureOfTheLoaderToThePolicyAndGoOnWatching() throws Exception {
        RecordingPolicy policy = new RecordingPolicy();
        RobotDescriptionLoader real = new RobotDescriptionLoader();
        AtomicInteger loads = new AtomicInteger();
        IllegalStateException broken = new IllegalStateException("the loader's bug");
        ReloadableDescription d = open(robot("loaded", "nxt", 0.056, "B"), file -> {
            if (loads.incrementAndGet() == 2) {
                throw broken; // the first reload
            }
            return real.load(file);
        }, policy);
        CountDownLatch reloaded = whenAccepted(d, next -> wheelDiameter(next) == 0.1);
        d.watch();

        write(robot("loaded", "nxt", 0.081, "B"));
        Await.until("the loader's failure reaches the policy", DEADLINE, () -> !policy.survived.isEmpty());
        write(robot("loaded", "nxt", 0.1, "B"));

        await(reloaded, "the next change is still reloaded");
        assertAll(
                () -> assertEquals("robomw-reload-loaded: " + broken, policy.survived.get(0)),
                () -> assertTrue(watchThread("loaded").isPresent(), "the watcher still runs"));
    }

    @Test
    void shouldNotReloadAfterClose() throws Exception {
        ReloadableDescription d = open(robot(0.056));
        d.watch();
        d.close();
        // A second watcher on the same file shows when the change has been seen.
        ReloadableDescription witness = new ReloadableDescription(d.file(), new RobotDescriptionLoader());
        opened.add(witness);
        CountDownLatch witnessed = whenAccepted(witness, next -> wheelDiameter(next) == 0.081);
        witness.watch();

        write(robot(0.081));

        await(witnessed, "the witness sees the change");
        assertEquals(0.056, wheelDiameter(d.current()));
    }
}
