package io.robomw.platform;

import io.robomw.testkit.Await;
import io.robomw.api.Clock;
import io.robomw.api.RobotException;
import io.robomw.api.RobotLinkException;
import io.robomw.api.spi.ConnectionSettings;
import io.robomw.api.spi.MotorChannel;
import io.robomw.api.spi.MotorCommand;
import io.robomw.api.spi.MotorTarget;
import io.robomw.api.spi.PlatformConfig;
import io.robomw.api.spi.PlatformServices;
import io.robomw.api.spi.SensorChannel;
import io.robomw.platform.motor.FeedbackSink;
import io.robomw.platform.motor.LinkTiming;
import io.robomw.platform.motor.MotorDriver;
import io.robomw.platform.motor.MotorPlatform;
import io.robomw.platform.motor.MotorState;
import io.robomw.platform.sensor.Sensor;
import io.robomw.platform.sensor.SensorPlatform;
import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.Test;

import java.time.Duration;
import java.util.List;
import java.util.Map;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.CopyOnWriteArrayList;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.ExecutionException;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicReference;

import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertInstanceOf;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * A brick platform's link thread, on the wall clock, when its driver throws an error: one it can
 * cause is counted and the thread goes on; one it cannot survive ends the thread, never silently:
 * every command is stopped, the stop reaches the link before the thread exits, and later commands
 * fail saying the robot has failed. A refusal (a brick's error status) ends the commands it
 * concerns, not one admitted while it was on its way.
 */
class LinkThreadFailureTest {

    /**
     * A driver whose feedback poll throws what a test puts in {@link #throwOnce}, or holds the
     * poll until {@link #release} and then refuses it with {@link #refuseHeldPoll}; records what it sends.
     */
    static final class FailingMotors implements MotorDriver {
        final List<List<MotorState>> sent = new CopyOnWriteArrayList<>();
        final AtomicReference<Throwable> throwOnce = new AtomicReference<>();
        final CompletableFuture<Void> thrown = new CompletableFuture<>();
        final AtomicReference<RuntimeException> refuseHeldPoll = new AtomicReference<>();
        final CompletableFuture<Void> pollHeld = new CompletableFuture<>();
        final CountDownLatch release = new CountDownLatch(1);

        @Override
        public LinkTiming timing() {
            return LinkTiming.NONE;
        }

        @Override
        public void send(List<MotorState> motors, FeedbackSink feedback) {
            sent.add(List.copyOf(motors));
        }

        @Override
        public int poll(FeedbackSink feedback) {
            RuntimeException refusal = refuseHeldPoll.getAndSet(null);
            if (refusal != null) {
                pollHeld.complete(null);
                try {
                    if (!release.await(30, TimeUnit.SECONDS)) {
                        throw new IllegalStateException("the test never released the held poll");
                    }
                } catch (InterruptedException e) {
                    Thread.currentThread().interrupt();
                }
                throw refusal;
            }
            Throwable t = throwOnce.getAndSet(null);
            if (t != null) {
                thrown.complete(null);
                if (t instanceof Error e) {
                    throw e;
                }
                throw (RuntimeException) t;
            }
            return 0;
        }
    }

    private final FailingMotors motors = new FailingMotors();
    private BrickPlatform platform;

    private BrickPlatform open() throws Exception {
        PlatformConfig config = new PlatformConfig("failing", "fake", new ConnectionSettings(Map.of(), "test"),
                List.of(MotorChannel.actuator("B"), MotorChannel.actuator("C")), List.of(), Duration.ofMillis(5), Duration.ZERO, Clock.system(),
                PlatformServices.none(), io.robomw.api.spi.Cycling.OWN_THREADS, io.robomw.api.spi.FailurePolicy.logging());
        MotorPlatform motorPlatform = new MotorPlatform(config, motors);
        SensorPlatform sensors = new SensorPlatform(motorPlatform) {
            @Override
            public Sensor createSensor(SensorChannel channel) {
                return () -> CompletableFuture.completedFuture(0.0);
            }
        };
        platform = new BrickPlatform(config, motorPlatform, sensors, null, null).start();
        return platform;
    }

    @AfterEach
    void close() {
        if (platform != null) {
            platform.close();
        }
    }

    private static MotorCommand driveForever() {
        return MotorCommand.of("drive", List.of(MotorTarget.rotate("B", 1e9, 360), MotorTarget.rotate("C", 1e9, 360)));
    }

    private boolean sentRunning(String port) {
        return motors.sent.stream().anyMatch(b -> b.stream().anyMatch(s -> s.port().equals(port) && s.degreesPerSecond() != 0));
    }

    @Test
    void aRefusalInFlightWhenACommandIsAdmittedEndsTheCommandsRunningBeforeItAndNotThatOne() throws Exception {
        open();
        CompletableFuture<Void> before = platform.run(MotorCommand.of("before", List.of(MotorTarget.rotate("B", 1e9, 360))));
        Await.until("motor B was started", Duration.ofSeconds(10), () -> sentRunning("B"));
        RobotException refusal = new RobotException("NXT refused GETOUTPUTSTATE on port 1: status 0xC0 (telegram 00 06 01)");
        motors.refuseHeldPoll.set(refusal);
        motors.pollHeld.get(10, TimeUnit.SECONDS);

        // While the brick's refusal of that poll is on its way, a command on motor C is admitted.
        CompletableFuture<Void> after = platform.run(MotorCommand.of("after", List.of(MotorTarget.rotate("C", 1e9, 360))));
        Await.until("the command on C was admitted", Duration.ofSeconds(10), () -> platform.actionThread().actuatorsInUse().contains("C"));
        motors.release.countDown();

        ExecutionException ended = assertThrows(ExecutionException.class, () -> before.get(10, TimeUnit.SECONDS));
        assertTrue(ended.getCause().getMessage().contains("status 0xC0"), ended.getCause().getMessage());
        long cycles = platform.actionThread().cycles();
        Await.until("the cycle that ended it is over", Duration.ofSeconds(10), () -> platform.actionThread().cycles() > cycles);
        assertFalse(after.isDone(), "the command admitted after the refused poll was sent carries on");
        Await.until("motor C was started after the refusal", Duration.ofSeconds(10), () -> sentRunning("C"));
        assertFalse(after.isDone());
        after.cancel(false);
    }

    @Test
    void aStackOverflowInTheDriverIsCountedAndTheLinkThreadGoesOn() throws Exception {
        open();
        motors.throwOnce.set(new StackOverflowError("driver recursed"));
        motors.thrown.get(10, TimeUnit.SECONDS);
        CompletableFuture<Void> drive = platform.run(driveForever());
        Await.until("the motors were started", Duration.ofSeconds(10), () -> motors.sent.stream().anyMatch(b -> b.stream().anyMatch(s -> s.degreesPerSecond() != 0)));
        assertTrue(platform.linkThreadFailure().isEmpty());
        assertTrue(platform.driverErrors() >= 1);
        drive.cancel(false);
    }

    @Test
    void anErrorTheLinkThreadCannotSurviveStopsEveryCommandHandsTheStopToTheLinkAndFailsLaterCommands() throws Exception {
        open();
        CompletableFuture<Void> drive = platform.run(driveForever());
        Await.until("the motors were started", Duration.ofSeconds(10), () -> motors.sent.stream().anyMatch(b -> b.stream().anyMatch(s -> s.degreesPerSecond() != 0)));
        motors.throwOnce.set(new InternalError("the driver's native library crashed"));

        ExecutionException stopped = assertThrows(ExecutionException.class, () -> drive.get(10, TimeUnit.SECONDS));
        assertInstanceOf(RobotLinkException.class, stopped.getCause());
        Await.until("the link thread is marked failed", Duration.ofSeconds(10), () -> platform.linkThreadFailure().isPresent());
        // The dying thread hands the stop to the link after it marked the robot failed.
        Await.until("the last batch sent stops both motors: " + motors.sent, Duration.ofSeconds(10), () -> {
            List<MotorState> last = motors.sent.get(motors.sent.size() - 1);
            return last.size() == 2 && last.stream().allMatch(m -> m.degreesPerSecond() == 0);
        });

        ExecutionException later = assertThrows(ExecutionException.class, () -> platform.run(driveForever()).get(10, TimeUnit.SECONDS));
        assertTrue(later.getCause().getMessage().contains("robot 'failing' has failed") && later.getCause().getMessage().contains("InternalError"),
                later.getCause().getMessage());
    }
}
