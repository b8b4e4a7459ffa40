package io.robomw.platform.command;

import io.robomw.api.CommandPreemptedException;
import io.robomw.api.ManualClock;
import io.robomw.api.RobotException;
import io.robomw.api.RobotLinkException;
import io.robomw.api.spi.CommandPriority;
import io.robomw.api.spi.HighLevelCommand;
import io.robomw.platform.exec.ExecutionActionThread;
import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.Test;

import java.io.IOException;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.Map;
import java.util.Set;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.ExecutionException;
import java.util.concurrent.TimeUnit;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertInstanceOf;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * High-level commands under the execution action thread's rules, on a manual clock, with a driver
 * that records what it would send: clash (newest wins), priorities (a safety stop is never
 * pre-empted), the watchdog of continuous commands, refreshes, errors and overruns.
 */
class HighLevelCommandPlatformTest {

    private static final Duration PERIOD = Duration.ofMillis(10);

    private final ManualClock clock = new ManualClock();
    private final ExecutionActionThread thread = new ExecutionActionThread("dog", clock, PERIOD);
    private final RecordingPlatform platform = new RecordingPlatform(clock);

    /** Records start, refresh and stop as lines, and lets the test report runs done or failed. */
    private static final class RecordingPlatform extends HighLevelCommandPlatform {
        final List<String> sent = new ArrayList<>();
        final List<Run> runs = new ArrayList<>();
        /** What a stop waits for: everything sent so far written to the link. */
        CompletableFuture<Void> written = CompletableFuture.completedFuture(null);
        final List<String> asked = new ArrayList<>();

        RecordingPlatform(ManualClock clock) {
            super("dog", clock);
        }

        @Override
        protected void start(Run run) {
            runs.add(run);
            sent.add("start " + run.command().text());
        }

        @Override
        protected void refresh(Run run) {
            sent.add("refresh " + run.command().text());
        }

        @Override
        protected void stop(Run run) {
            sent.add("stop " + run.command().text() + (run.command().stopText().isEmpty() ? "" : " then " + run.command().stopText()));
        }

        @Override
        protected CompletableFuture<Void> sentSoFar() {
            asked.add("after " + sent.size() + " sent");
            return written;
        }

        void done(int i) {
            finished(runs.get(i));
        }

        void error(int i, String message) {
            failed(runs.get(i), message);
        }
    }

    @AfterEach
    void close() {
        thread.close();
    }

    private static HighLevelCommand walk(String text, double seconds) {
        return new HighLevelCommand("move", text, Map.of(), Set.of("legs"), Duration.ofMillis(Math.round(seconds * 1000)), false,
                CommandPriority.NORMAL, Duration.ZERO, "robot.stop()");
    }

    private static HighLevelCommand drive(String text, Duration watchdog) {
        return new HighLevelCommand("drive", text, Map.of(), Set.of("legs"), Duration.ZERO, true, CommandPriority.NORMAL, watchdog, "robot.stop()");
    }

    private static HighLevelCommand head(String text) {
        return new HighLevelCommand("head.pan", text, Map.of(), Set.of("head"), Duration.ofMillis(400), false, CommandPriority.NORMAL,
                Duration.ZERO, "");
    }

    private CompletableFuture<Void> submit(HighLevelCommand c) {
        return thread.submit(platform.container(c));
    }

    private void cycle(int n) {
        for (int i = 0; i < n; i++) {
            thread.cycle();
            clock.advance(PERIOD);
        }
    }

    private static Throwable failure(CompletableFuture<Void> f) {
        return assertThrows(ExecutionException.class, () -> f.get(0, TimeUnit.SECONDS)).getCause();
    }

    @Test
    void shouldSendACommandAndFinishWhenTheRobotReportsItDone() throws Exception {
        CompletableFuture<Void> f = submit(walk("robot.walk(0.5, 0.1)", 5));
        cycle(1);
        assertEquals(List.of("start robot.walk(0.5, 0.1)"), platform.sent);
        assertFalse(f.isDone());

        platform.done(0);
        cycle(1);

        f.get(0, TimeUnit.SECONDS);
        assertEquals(List.of("start robot.walk(0.5, 0.1)"), platform.sent, "a finished command needs no stop");
    }

    @Test
    void shouldLetTheNewestCommandOnTheLegsWinAndStopTheOlderOne() {
        CompletableFuture<Void> first = submit(walk("robot.walk(0.5, 0.1)", 5));
        cycle(1);
        CompletableFuture<Void> second = submit(walk("robot.turn(1.57, 1)", 1.57));
        cycle(1);

        assertInstanceOf(CommandPreemptedException.class, failure(first));
        assertFalse(second.isDone());
        assertEquals(List.of("start robot.walk(0.5, 0.1)", "stop robot.walk(0.5, 0.1) then robot.stop()", "start robot.turn(1.57, 1)"),
                platform.sent, "the older walk is ended on the robot before the newer one starts");
    }

    @Test
    void shouldRunCommandsOnOtherActuatorGroupsSideBySide() {
        CompletableFuture<Void> walk = submit(walk("robot.walk(0.5, 0.1)", 5));
        CompletableFuture<Void> pan = submit(head("headPan.val = 30 time:400"));
        cycle(1);
        platform.done(1);
        cycle(1);

        assertTrue(pan.isDone() && !pan.isCompletedExceptionally());
        assertFalse(walk.isDone(), "panning the head does not interrupt the walk");
    }

    @Test
    void shouldNeverLetANormalCommandPreemptASafetyStop() {
        submit(walk("robot.walk(0.5, 0.1)", 5));
        submit(head("headPan.val = 30 time:400"));
        cycle(1);
        thread.submit(platform.stopContainer());
        CompletableFuture<Void> sneaky = submit(walk("robot.walk(1, 0.1)", 10));
        cycle(1);

        CommandPreemptedException e = assertInstanceOf(CommandPreemptedException.class, failure(sneaky));
        assertTrue(e.getMessage().contains("refused"), e.getMessage());
        assertEquals(4, platform.sent.size(), "the stop ends every running command, on every group, and nothing starts in its cycle: " + platform.sent);
        assertEquals(Set.of("stop robot.walk(0.5, 0.1) then robot.stop()", "stop headPan.val = 30 time:400"),
                Set.copyOf(platform.sent.subList(2, 4)));
    }

    @Test
    void shouldRefreshARunningDriveInsteadOfRestartingIt() throws Exception {
        CompletableFuture<Void> first = submit(drive("robot.drive(0.1, 0)", Duration.ofMillis(500)));
        cycle(1);
        CompletableFuture<Void> again = submit(drive("robot.drive(0.1, 0.2)", Duration.ofMillis(500)));
        cycle(1);

        again.get(0, TimeUnit.SECONDS);
        assertFalse(first.isDone());
        assertEquals(List.of("start robot.drive(0.1, 0)", "refresh robot.drive(0.1, 0.2)"), platform.sent);
        assertEquals("robot.drive(0.1, 0.2)", platform.runs.get(0).command().text());
    }

    @Test
    void shouldStopADriveWhoseRefreshStopsWithinItsWatchdog() {
        CompletableFuture<Void> f = submit(drive("robot.drive(0.1, 0)", Duration.ofMillis(300)));
        cycle(20);
        submit(drive("robot.drive(0.1, 0)", Duration.ofMillis(300)));
        cycle(25);
        assertFalse(f.isDone(), "refreshed at 200 ms, so not stopped at 300 ms");

        cycle(10);

        Throwable e = failure(f);
        assertInstanceOf(RobotException.class, e);
        assertTrue(e.getMessage().contains("watchdog"), e.getMessage());
        assertEquals("stop robot.drive(0.1, 0) then robot.stop()", platform.sent.get(platform.sent.size() - 1));
    }

    @Test
    void shouldFailACommandTheRobotReportsAnErrorForNamingIt() {
        CompletableFuture<Void> f = submit(walk("robot.wlak(0.5, 0.1)", 5));
        cycle(1);
        platform.error(0, "the robot answered \"!!! unknown identifier: robot.wlak\"");
        cycle(1);

        Throwable e = failure(f);
        assertTrue(e.getMessage().contains("'move' (robot.wlak(0.5, 0.1)) failed") && e.getMessage().contains("unknown identifier"), e.getMessage());
        assertEquals("stop robot.wlak(0.5, 0.1) then robot.stop()", platform.sent.get(platform.sent.size() - 1));
    }

    @Test
    void shouldFailACommandThatRunsFarPastItsExpectedDuration() {
        CompletableFuture<Void> f = submit(walk("robot.walk(0.1, 0.1)", 1));
        cycle(400);
        assertFalse(f.isDone(), "3 × 1 s + 2 s is allowed");

        cycle(102);

        Throwable e = failure(f);
        assertTrue(e.getMessage().contains("did not finish within 5.0 s (expected 1.0 s)"), e.getMessage());
    }

    @Test
    void shouldEndEveryCommandWithItsStopWhenTheLinkFails() {
        CompletableFuture<Void> f = submit(walk("robot.walk(0.5, 0.1)", 5));
        cycle(1);
        thread.linkFailed("tcp 127.0.0.1:54000", new IOException("connection reset"));
        cycle(1);

        assertInstanceOf(RobotLinkException.class, failure(f));
        assertEquals("stop robot.walk(0.5, 0.1) then robot.stop()", platform.sent.get(platform.sent.size() - 1));
    }

    @Test
    void aStopCompletesOnceTheStopsOfTheCommandsItEndedAreWrittenToTheLink() throws Exception {
        submit(walk("robot.walk(1, 0.1)", 10));
        cycle(1);
        platform.written = new CompletableFuture<>();
        CompletableFuture<Void> handed = new CompletableFuture<>();
        thread.submit(platform.stopContainer(handed));
        cycle(1);
        assertEquals(List.of("start robot.walk(1, 0.1)", "stop robot.walk(1, 0.1) then robot.stop()"), platform.sent);
        assertEquals(List.of("after 2 sent"), platform.asked, "the stop waits for what was sent up to the walk's stop");
        assertFalse(handed.isDone(), "not while the link has not written it");
        platform.written.complete(null);
        handed.get(0, TimeUnit.SECONDS);
    }

    @Test
    void aStopWhoseStopsTheLinkCannotWriteFailsNamingTheRobot() {
        platform.written = CompletableFuture.failedFuture(new IOException("tcp 127.0.0.1:54000 is down"));
        CompletableFuture<Void> handed = new CompletableFuture<>();
        thread.submit(platform.stopContainer(handed));
        cycle(1);
        RobotLinkException e = assertInstanceOf(RobotLinkException.class, failure(handed));
        assertTrue(e.getMessage().contains("robot 'dog'") && e.getMessage().contains("is down"), e.getMessage());
    }
}
