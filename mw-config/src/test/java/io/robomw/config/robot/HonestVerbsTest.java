package io.robomw.config.robot;

import io.robomw.api.Futures;
import io.robomw.api.Position;
import io.robomw.api.ReturnType;
import io.robomw.api.RobotException;
import io.robomw.api.RobotLinkException;
import io.robomw.api.SensorType;
import io.robomw.config.description.RobotDescription;
import io.robomw.config.description.RobotDescriptionLoader;
import io.robomw.testkit.Await;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.params.ParameterizedTest;
import org.junit.jupiter.params.provider.ValueSource;

import java.time.Duration;
import java.util.List;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.CopyOnWriteArrayList;
import java.util.concurrent.ExecutorService;
import java.util.concurrent.Executors;
import java.util.concurrent.Future;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicReference;

import static org.junit.jupiter.api.Assertions.assertAll;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertSame;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * The verbs' contracts at the Configuration Layer, on the fake platforms: a blocking verb that
 * stops waiting ends its command, every {@code ...Async} future cancels the platform's command,
 * and {@code stop()} returns only once the platform has the stop, after which a command is admitted.
 */
class HonestVerbsTest {

    private static final Duration DEADLINE = Duration.ofSeconds(10);

    private final FakePlatform platform = new FakePlatform();
    private final RobotDescription description = new RobotDescriptionLoader().parse("""
            name: scout
            platform: nxt
            drive: { wheel_diameter: 0.056, track_width: 0.112, max_speed: 0.3, left: {port: B}, right: {port: C} }
            sensors:
              - {name: sonar, type: sonar, position: front, port: 4, conversion: {scale: 0.01}}
            actuators:
              - {name: gripper, port: A, actions: {open: {degrees: 90, speed: 180}}}
            """, "scout.yaml");
    private final ConfiguredRobot robot = ConfiguredRobot.withComponents(() -> description, platform, null);
    private final ExecutorService caller = Executors.newSingleThreadExecutor(r -> new Thread(r, "program"));

    @org.junit.jupiter.api.AfterEach
    void shutDown() {
        caller.shutdownNow();
    }

    // ---- a blocking verb that stops waiting ends its command ----

    @Test
    void shouldCancelThePlatformsCommandWhenTheThreadOfABlockingMoveIsInterrupted() throws Exception {
        platform.pending = true;
        AtomicReference<Thread> program = new AtomicReference<>();
        AtomicReference<Boolean> stillInterrupted = new AtomicReference<>();
        Future<?> move = caller.submit(() -> {
            program.set(Thread.currentThread());
            try {
                robot.move(1.0, 0.2);
            } finally {
                stillInterrupted.set(Thread.currentThread().isInterrupted());
            }
        });
        Await.until("the move's command reaches the platform", DEADLINE, () -> platform.commands.size() == 1);

        program.get().interrupt();

        java.util.concurrent.ExecutionException e = assertThrows(java.util.concurrent.ExecutionException.class,
                () -> move.get(DEADLINE.toSeconds(), TimeUnit.SECONDS));
        assertAll(
                () -> assertTrue(e.getCause() instanceof RobotException && e.getCause().getMessage().contains("interrupted"), e.getCause().toString()),
                () -> assertTrue(platform.futures.get(0).isCancelled(), "the platform's command was cancelled: its motors brake"),
                () -> assertTrue(stillInterrupted.get(), "the thread keeps its interrupt status"));
    }

    @Test
    void shouldCancelThePlatformsCommandWhenTheWaitsDeadlinePasses() {
        platform.pending = true;

        RobotException e = assertThrows(RobotException.class,
                () -> Futures.await(robot.moveAsync(1.0, 0.2), Duration.ofMillis(50), "move(1.000, 0.200)"));

        assertAll(
                () -> assertTrue(e.getMessage().contains("did not complete within 50 ms"), e.getMessage()),
                () -> assertTrue(platform.futures.get(0).isCancelled(), "the platform's command was cancelled"));
    }

    @ParameterizedTest
    @ValueSource(strings = {"move", "turn", "arc", "perform"})
    void shouldCancelThePlatformsCommandWhenTheFutureOfAnAsyncVerbIsCancelled(String verb) {
        platform.pending = true;
        CompletableFuture<Void> future = switch (verb) {
            case "move" -> robot.moveAsync(1.0, 0.2);
            case "turn" -> robot.turnAsync(Math.PI, 1.0);
            case "arc" -> robot.arcAsync(0.5, Math.PI, 0.2);
            default -> robot.performAsync("gripper.open");
        };

        assertTrue(future.cancel(true));

        assertTrue(platform.lastFuture().isCancelled(), verb + ": the platform's command was cancelled");
    }

    @Test
    void shouldCancelThePlatformsReadWhenTheFutureOfAReadingIsCancelled() {
        platform.pending = true;
        CompletableFuture<Double> reading = robot.getValueAsync(Position.FRONT, SensorType.RANGE, ReturnType.CENTIMETERS);

        reading.cancel(true);

        assertTrue(platform.reads.get(0).isCancelled());
    }

    // ---- stop ----

    @Test
    void shouldReturnFromStopOnlyOnceThePlatformHasTheStopAndReadNothingBefore() throws Exception {
        CompletableFuture<Void> handed = new CompletableFuture<>();
        platform.stopFuture = handed;
        robot.pose(); // odometry under way: the stop must not read the encoders before the stop is handed over
        List<String> readsWhileStopping = new CopyOnWriteArrayList<>();
        platform.beforeRead = port -> {
            if (!handed.isDone()) {
                readsWhileStopping.add(port);
            }
        };

        Future<?> stop = caller.submit(robot::stop);
        Await.until("the stop reaches the platform", DEADLINE, () -> platform.stops == 1);
        assertFalse(stop.isDone(), "stop() waits while the platform has not handed the stop to the hardware");
        handed.complete(null);
        stop.get(DEADLINE.toSeconds(), TimeUnit.SECONDS);

        assertEquals(List.of(), readsWhileStopping, "nothing was read before the stop was handed over");
    }

    @Test
    void shouldAdmitAMoveAfterStopReturns() throws Exception {
        CompletableFuture<Void> handed = new CompletableFuture<>();
        platform.stopFuture = handed;
        Future<?> stop = caller.submit(robot::stop);
        Await.until("the stop reaches the platform", DEADLINE, () -> platform.stops == 1);
        Thread action = new Thread(() -> handed.complete(null), "scout-action"); // the platform takes the stop on its own thread
        action.start();
        stop.get(DEADLINE.toSeconds(), TimeUnit.SECONDS);

        robot.move(0.1, 0.1);

        assertEquals("move(0.100, 0.100)", platform.commands.get(0).name());
    }

    @Test
    void shouldAdmitAMoveAfterStoppingAnIdleRobot() {
        robot.stop();

        robot.turn(Math.PI / 2, 1.0);

        assertEquals(1, platform.commands.size());
    }

    @Test
    void shouldFailAStopNotHandedToTheHardwareInTimeWithALinkErrorNamingTheRobotWithoutCancellingIt() {
        CompletableFuture<Void> handed = new CompletableFuture<>();

        RobotLinkException e = assertThrows(RobotLinkException.class, () -> Stops.awaitHanded(handed, Duration.ofMillis(20), "scout"));

        assertAll(
                () -> assertTrue(e.getMessage().contains("robot 'scout': its stop was not handed to the hardware within 20 ms"), e.getMessage()),
                () -> assertFalse(handed.isCancelled(), "the stop goes on"));
    }

    @Test
    void shouldPassOnThePlatformsLinkErrorFromStop() {
        RobotLinkException down = new RobotLinkException("robot 'scout': link /dev/rfcomm0 is down", null);
        platform.stopFuture = CompletableFuture.failedFuture(down);

        RobotLinkException e = assertThrows(RobotLinkException.class, robot::stop);

        assertSame(down, e);
    }
}
