package io.robomw.platform.motor;

import io.robomw.api.ManualClock;
import io.robomw.api.spi.CommandPriority;
import io.robomw.api.spi.ConnectionSettings;
import io.robomw.api.spi.Cycling;
import io.robomw.api.spi.FailurePolicy;
import io.robomw.api.spi.MotorChannel;
import io.robomw.api.spi.MotorCommand;
import io.robomw.api.spi.MotorTarget;
import io.robomw.api.spi.PlatformConfig;
import io.robomw.api.spi.PlatformServices;
import io.robomw.api.spi.SensorChannel;
import io.robomw.platform.BrickPlatform;
import io.robomw.platform.sensor.Sensor;
import io.robomw.platform.sensor.SensorPlatform;
import io.robomw.testkit.Allocations;
import org.junit.jupiter.api.Test;

import java.time.Duration;
import java.util.List;
import java.util.Map;
import java.util.Set;
import java.util.concurrent.CompletableFuture;

import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * A simulation cycles thousands of robots' platforms on one thread (the link agent inline, after
 * each cycle): a cycle of a robot whose drive runs on, with nothing new to send, allocates nothing,
 * so ten thousand robots leave the garbage collector nothing to do between commands.
 */
class SteadyCycleAllocationTest {

    /** A driver without I/O, like the simulator's: it reads two encoders and keeps nothing. */
    static final class QuietMotors implements MotorDriver {
        double degrees;

        @Override
        public void send(List<MotorState> states, FeedbackSink feedback) {
        }

        @Override
        public int poll(FeedbackSink feedback) {
            degrees += 1;
            feedback.degrees(0, degrees);
            feedback.degrees(1, -degrees);
            return 0;
        }

        @Override
        public LinkTiming timing() {
            return LinkTiming.NONE;
        }
    }

    @Test
    void aCycleOfARunningDriveWithNothingNewAllocatesNothing() throws Exception {
        ManualClock clock = new ManualClock();
        PlatformConfig config = new PlatformConfig("quiet", "fake", new ConnectionSettings(Map.of(), "test"),
                List.of(MotorChannel.actuator("B"), MotorChannel.actuator("C")), List.of(), Duration.ofMillis(10), Duration.ZERO, clock,
                PlatformServices.none(), Cycling.BY_OWNER, FailurePolicy.logging());
        MotorPlatform motors = new MotorPlatform(config, new QuietMotors());
        SensorPlatform sensors = new SensorPlatform(motors) {
            @Override
            public Sensor createSensor(SensorChannel channel) {
                return () -> CompletableFuture.completedFuture(0.0);
            }
        };
        try (BrickPlatform platform = new BrickPlatform(config, motors, sensors, null, null).start()) {
            platform.runDetached(new MotorCommand("drive", List.of(MotorTarget.run("B", 100), MotorTarget.run("C", 100)),
                    CommandPriority.NORMAL, Duration.ZERO));
            for (int i = 0; i < 20_000; i++) { // warm up: the JIT compiles the cycle, escape analysis included
                platform.actionThread().cycle();
                clock.advanceNanos(10_000_000L);
            }
            long perCycle = Allocations.perCall(10_000, () -> {
                platform.actionThread().cycle();
                clock.advanceNanos(10_000_000L);
            });
            assertTrue(perCycle < 8, "a steady cycle allocated " + perCycle + " bytes");
        }
    }

    @Test
    void aDriveRefreshedAtEveryCycleWithTheSameSpeedsAllocatesNothing() throws Exception {
        ManualClock clock = new ManualClock();
        PlatformConfig config = new PlatformConfig("refreshed", "fake", new ConnectionSettings(Map.of(), "test"),
                List.of(MotorChannel.actuator("B"), MotorChannel.actuator("C")), List.of(), Duration.ofMillis(100), Duration.ofMillis(500), clock,
                PlatformServices.none(), Cycling.BY_OWNER, FailurePolicy.logging());
        MotorPlatform motors = new MotorPlatform(config, new QuietMotors());
        SensorPlatform sensors = new SensorPlatform(motors) {
            @Override
            public Sensor createSensor(SensorChannel channel) {
                return () -> CompletableFuture.completedFuture(0.0);
            }
        };
        // A controller's drive at every tick: the Configuration Layer hands the same command again
        // while the speeds stay the same (DifferentialDriveControl keeps its last one).
        MotorCommand drive = new MotorCommand("drive", List.of(MotorTarget.run("B", 120), MotorTarget.run("C", 80)),
                CommandPriority.NORMAL, Duration.ofMillis(500));
        try (BrickPlatform platform = new BrickPlatform(config, motors, sensors, null, null).start()) {
            for (int i = 0; i < 20_000; i++) { // warm up: the JIT compiles refresh and cycle
                platform.runDetached(drive);
                platform.actionThread().cycle();
                clock.advanceNanos(100_000_000L);
            }
            long perCycle = Allocations.perCall(10_000, () -> {
                platform.runDetached(drive);
                platform.actionThread().cycle();
                clock.advanceNanos(100_000_000L);
            });
            assertTrue(perCycle < 8, "a refresh and its cycle allocated " + perCycle + " bytes");
            assertTrue(platform.actionThread().actuatorsInUse().containsAll(Set.of("B", "C")),
                    "the refreshed drive still runs (its watchdog restarted by every refresh): " + platform.actionThread().actuatorsInUse());
        }
    }
}
