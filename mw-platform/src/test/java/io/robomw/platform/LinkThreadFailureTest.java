package io.robomw.platform;

import io.robomw.api.Clock;
import io.robomw.api.RobotLinkException;
import io.robomw.api.spi.ConnectionSettings;
import io.robomw.api.spi.MotorChannel;
import io.robomw.api.spi.MotorCommand;
import io.robomw.api.spi.MotorTarget;
import io.robomw.api.spi.PlatformConfig;
import io.robomw.api.spi.PlatformServices;
import io.robomw.api.spi.SensorChannel;
import io.robomw.platform.motor.GenericMotorPlatform;
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
import java.util.concurrent.ExecutionException;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicReference;

import static org.junit.jupiter.api.Assertions.assertInstanceOf;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * A brick platform's link thread, on the wall clock, when its driver throws an error: one it can
 * cause is counted and the thread goes on; one it cannot survive ends the thread, never silently:
 * every command is stopped, the stop reaches the link before the thread exits, and later commands
 * fail saying the robot has failed.
 */
class LinkThreadFailureTest {

    /** A driver whose feedback poll throws what a test puts in {@link #throwOnce}; records what it sends. */
    static final class FailingMotors extends GenericMotorPlatform {
        final List<List<MotorState>> sent = new CopyOnWriteArrayList<>();
        final AtomicReference<Throwable> throwOnce = new AtomicReference<>();
        final CompletableFuture<Void> thrown = new CompletableFuture<>();

        FailingMotors() {
            super("failing", Clock.system(), List.of("B", "C"));
        }

        @Override
        protected void runImpl(List<MotorState> motors) {
            sent.add(List.copyOf(motors));
        }

        @Override
        protected void pollFeedback() {
            Throwable t = throwOnce.getAndSet(null);
            if (t != null) {
                thrown.complete(null);
                if (t instanceof Error e) {
                    throw e;
                }
                throw (RuntimeException) t;
            }
        }
    }

    private final FailingMotors motors = new FailingMotors();
    private BrickPlatform platform;

    private BrickPlatform open() throws Exception {
        PlatformConfig config = new PlatformConfig("failing", "fake", new ConnectionSettings(Map.of(), "test"),
                List.of(MotorChannel.actuator("B"), MotorChannel.actuator("C")), List.of(), Duration.ofMillis(5), Duration.ZERO, Clock.system(),
                PlatformServices.none());
        SensorPlatform sensors = new SensorPlatform(motors) {
            @Override
            public Sensor createSensor(SensorChannel channel) {
                return () -> CompletableFuture.completedFuture(0.0);
            }
        };
        platform = new BrickPlatform(config, motors, sensors, LinkThreading.OWN_THREAD, null).start();
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
