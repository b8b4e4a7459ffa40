package io.robomw.config.robot;

import io.robomw.api.CommandPreemptedException;
import io.robomw.api.Pose;
import io.robomw.api.RobotException;
import io.robomw.config.description.RobotDescription;
import io.robomw.config.description.RobotDescriptionLoader;
import org.junit.jupiter.api.Test;

import java.util.concurrent.CompletableFuture;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.ExecutorService;
import java.util.concurrent.Executors;
import java.util.concurrent.Future;
import java.util.concurrent.TimeUnit;

import static org.junit.jupiter.api.Assertions.assertAll;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * The pose trackers listen to their drive's motions: a motion's end is only recorded on the thread
 * that ends it (the platform's action thread), and integrated, exactly, by the next reader.
 */
class PoseListensToMotionsTest {

    private static final double WHEEL = 0.056;
    private static final double TRACK = 0.112;
    private static final long DEADLINE_SECONDS = 10;

    private final FakePlatform platform = new FakePlatform();
    private final RobotDescription description = new RobotDescriptionLoader().parse("""
            name: scout
            platform: nxt
            drive: { wheel_diameter: 0.056, track_width: 0.112, max_speed: 0.3, left: {port: B}, right: {port: C} }
            """, "scout.yaml");
    private final ConfiguredRobot robot = ConfiguredRobot.withComponents(() -> description, platform, null);

    private static double degrees(double metres) {
        return metres * 360 / (Math.PI * WHEEL);
    }

    private void wheels(double leftMetres, double rightMetres) {
        platform.turn("B", degrees(leftMetres));
        platform.turn("C", degrees(rightMetres));
    }

    /** Completes a command's future on a thread of its own, as the platform's action thread would. */
    private static void endOnActionThread(CompletableFuture<Void> command, Throwable failure) throws Exception {
        Thread action = new Thread(() -> {
            if (failure == null) {
                command.complete(null);
            } else {
                command.completeExceptionally(failure);
            }
        }, "scout-action");
        action.start();
        action.join(TimeUnit.SECONDS.toMillis(DEADLINE_SECONDS));
        assertFalse(action.isAlive(), "the action thread ended the command");
    }

    @Test
    void shouldIntegrateAPreemptedMotionUpToItsEndReadOnTheActionThreadNotToTheNextCommand() throws Exception {
        platform.pending = true;
        robot.moveAsync(1.0, 0.2);
        CompletableFuture<Void> move = platform.lastFuture();
        wheels(0.30, 0.30);
        robot.turnAsync(Math.PI / 2, 1.0); // sent at 0.30 m; the move drives on until the turn is admitted
        CompletableFuture<Void> turn = platform.lastFuture();
        wheels(0.32, 0.32);
        endOnActionThread(move, new CommandPreemptedException("move", "turn"));
        double quarter = Math.PI / 2 * TRACK / 2;
        wheels(0.32 - quarter, 0.32 + quarter);
        endOnActionThread(turn, null);

        Pose pose = robot.pose();

        // Integrated from the turn's start (0.30 m) to its end as one arc, the pose would be 7 mm short.
        assertAll(() -> assertEquals(0.32, pose.x(), 1e-9, () -> "x of " + pose),
                () -> assertEquals(0, pose.y(), 1e-9, () -> "y of " + pose),
                () -> assertEquals(Math.PI / 2, pose.heading(), 1e-9, () -> "heading of " + pose));
    }

    @Test
    void shouldEndAMotionOnTheActionThreadWhileAReaderHoldsThePose() throws Exception {
        platform.pending = true;
        CompletableFuture<Void> move = robot.moveAsync(0.5, 0.2);
        CompletableFuture<Void> command = platform.lastFuture();
        wheels(0.5, 0.5);
        CountDownLatch readerInside = new CountDownLatch(1);
        CountDownLatch releaseReader = new CountDownLatch(1);
        platform.beforeRead = port -> {
            if (Thread.currentThread().getName().equals("reader")) {
                readerInside.countDown();
                await(releaseReader);
            }
        };
        ExecutorService reader = Executors.newSingleThreadExecutor(r -> new Thread(r, "reader"));
        try {
            Future<Pose> held = reader.submit(robot::pose);
            assertTrue(readerInside.await(DEADLINE_SECONDS, TimeUnit.SECONDS), "the reader reads the encoders, holding the pose");

            endOnActionThread(command, null);

            assertTrue(move.isDone(), "the motion's end was recorded without waiting for the reader");
            assertFalse(held.isDone(), "the reader still holds the pose");
            releaseReader.countDown();
            assertEquals(0.5, held.get(DEADLINE_SECONDS, TimeUnit.SECONDS).x(), 1e-9);
        } finally {
            releaseReader.countDown();
            reader.shutdownNow();
        }
        assertEquals(0.5, robot.pose().x(), 1e-9);
    }

    @Test
    void shouldKeepThePoseWhenAnEncoderCannotBeReadAtAMotionsEnd() throws Exception {
        platform.pending = true;
        CompletableFuture<Void> move = robot.moveAsync(0.5, 0.2);
        wheels(0.5, 0.5);
        platform.beforeRead = port -> {
            if (Thread.currentThread().getName().equals("scout-action")) {
                throw new RobotException("the link closed");
            }
        };

        endOnActionThread(platform.lastFuture(), null);
        platform.beforeRead = port -> { };

        assertAll(() -> assertTrue(move.isDone() && !move.isCompletedExceptionally(), "the motion completed as its command did"),
                () -> assertEquals(0.5, robot.pose().x(), 1e-9, "the next reading integrates across the lost boundary"));
    }

    private static void await(CountDownLatch latch) {
        try {
            if (!latch.await(DEADLINE_SECONDS, TimeUnit.SECONDS)) {
                throw new AssertionError("not released within " + DEADLINE_SECONDS + " s");
            }
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
            throw new AssertionError(e);
        }
    }
}
