package io.robomw.platform;

import io.robomw.api.Clock;
import io.robomw.api.RobotLinkException;
import io.robomw.api.spi.ConnectionSettings;
import io.robomw.api.spi.Cycling;
import io.robomw.api.spi.FailurePolicy;
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
import io.robomw.testkit.Await;
import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.Test;

import java.io.IOException;
import java.time.Duration;
import java.util.List;
import java.util.Map;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.CopyOnWriteArrayList;
import java.util.concurrent.ExecutionException;
import java.util.concurrent.TimeUnit;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertInstanceOf;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * A brick platform on its own threads and the wall clock, with a driver that records what it
 * writes: {@code stopAll()} completes only once the brakes are written, so a command after it is
 * admitted; on a dead link it fails naming the robot; a cancelled command brakes its motors.
 */
class HonestVerbsTest {

    /** Records every batch it is handed; fails every write while {@link #unplugged}. */
    static final class RecordingMotors implements MotorDriver {
        final List<List<MotorState>> sent = new CopyOnWriteArrayList<>();
        volatile boolean unplugged;

        @Override
        public LinkTiming timing() {
            return LinkTiming.NONE;
        }

        @Override
        public void send(List<MotorState> motors, FeedbackSink feedback) throws IOException {
            if (unplugged) {
                throw new IOException("brick unplugged");
            }
            sent.add(List.copyOf(motors));
        }

        @Override
        public int poll(FeedbackSink feedback) throws IOException {
            if (unplugged) {
                throw new IOException("brick unplugged");
            }
            return 0;
        }

        boolean lastBrakes(String port) {
            for (int i = sent.size() - 1; i >= 0; i--) {
                for (MotorState s : sent.get(i)) {
                    if (s.port().equals(port)) {
                        return !s.running() && s.stopMode() == MotorState.StopMode.BRAKE;
                    }
                }
            }
            return false;
        }

        boolean sentRunning(String port) {
            return sent.stream().anyMatch(b -> b.stream().anyMatch(s -> s.port().equals(port) && s.running()));
        }
    }

    private final RecordingMotors motors = new RecordingMotors();
    private BrickPlatform platform;

    private void open() throws IOException {
        PlatformConfig config = new PlatformConfig("honest", "fake", new ConnectionSettings(Map.of(), "test"),
                List.of(MotorChannel.actuator("B"), MotorChannel.actuator("C")), List.of(), Duration.ofMillis(10), Duration.ZERO, Clock.system(),
                PlatformServices.none(), Cycling.OWN_THREADS, FailurePolicy.logging());
        MotorPlatform motorPlatform = new MotorPlatform(config, motors);
        SensorPlatform sensors = new SensorPlatform(motorPlatform) {
            @Override
            public Sensor createSensor(SensorChannel channel) {
                return () -> CompletableFuture.completedFuture(0.0);
            }
        };
        platform = new BrickPlatform(config, motorPlatform, sensors, null, null).start();
    }

    @AfterEach
    void close() {
        if (platform != null) {
            platform.close();
        }
    }

    private static MotorCommand rotate(String port, double degrees) {
        return MotorCommand.of("rotate " + port, List.of(MotorTarget.rotate(port, degrees, 360)));
    }

    @Test
    void stopCompletesOnceTheBrakesAreWrittenAndACommandAfterItIsAdmitted() throws Exception {
        open();
        CompletableFuture<Void> drive = platform.run(MotorCommand.of("drive", List.of(MotorTarget.rotate("B", 1e9, 360), MotorTarget.rotate("C", 1e9, 360))));
        Await.until("the motors were started", Duration.ofSeconds(10), () -> motors.sentRunning("B") && motors.sentRunning("C"));

        platform.stopAll().get(10, TimeUnit.SECONDS);
        assertTrue(motors.lastBrakes("B") && motors.lastBrakes("C"), "the brakes were written before stopAll completed: " + motors.sent);
        assertTrue(drive.isCompletedExceptionally());

        int before = motors.sent.size();
        CompletableFuture<Void> after = platform.run(rotate("B", 1e9));
        Await.until("the command after the stop started its motor", Duration.ofSeconds(10),
                () -> {
                    List<List<MotorState>> sent = List.copyOf(motors.sent); // a sub-list of the live list fails when the link side adds to it
                    return sent.subList(before, sent.size()).stream().anyMatch(b -> b.stream().anyMatch(MotorState::running));
                });
        assertFalse(after.isDone(), "admitted, not refused as held by 'stop'");
        after.cancel(true);
    }

    @Test
    void aCancelledCommandBrakesItsMotorsAtTheNextCycle() throws Exception {
        open();
        CompletableFuture<Void> rotating = platform.run(rotate("C", 1e9));
        Await.until("motor C was started", Duration.ofSeconds(10), () -> motors.sentRunning("C"));
        rotating.cancel(true);
        Await.until("motor C was braked", Duration.ofSeconds(10), () -> motors.lastBrakes("C"));
        Await.until("motor C is free", Duration.ofSeconds(10), () -> platform.actionThread().actuatorsInUse().isEmpty());
    }

    @Test
    void stopOnADeadLinkFailsNamingTheRobot() throws Exception {
        open();
        motors.unplugged = true;
        CompletableFuture<Void> rotating = platform.run(rotate("B", 1e9));
        assertInstanceOf(RobotLinkException.class, assertThrows(ExecutionException.class, () -> rotating.get(10, TimeUnit.SECONDS)).getCause());

        ExecutionException e = assertThrows(ExecutionException.class, () -> platform.stopAll().get(10, TimeUnit.SECONDS));
        assertInstanceOf(RobotLinkException.class, e.getCause());
        assertTrue(e.getCause().getMessage().contains("robot 'honest'"), e.getCause().getMessage());
        assertEquals(0, motors.sent.size(), "nothing reached the unplugged brick");
    }
}
