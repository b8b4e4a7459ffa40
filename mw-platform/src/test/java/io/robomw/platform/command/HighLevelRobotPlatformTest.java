package io.robomw.platform.command;

import io.robomw.api.ManualClock;
import io.robomw.api.RobotLinkException;
import io.robomw.api.spi.CommandPriority;
import io.robomw.api.spi.ConnectionSettings;
import io.robomw.api.spi.Cycling;
import io.robomw.api.spi.FailurePolicy;
import io.robomw.api.spi.HighLevelCommand;
import io.robomw.api.spi.PlatformConfig;
import io.robomw.api.spi.PlatformServices;
import io.robomw.api.spi.SensorChannel;
import io.robomw.platform.exec.Container;
import io.robomw.platform.sensor.Sensor;
import io.robomw.platform.sensor.SensorPlatform;
import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.Test;

import java.io.IOException;
import java.time.Duration;
import java.util.List;
import java.util.Map;
import java.util.Set;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.ExecutionException;
import java.util.concurrent.TimeUnit;

import static org.junit.jupiter.api.Assertions.assertInstanceOf;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * The platform of robots that move by their firmware's commands (the Aibo, MAVLink vehicles), on a
 * manual clock, cycled by the test: what a command handed over as the driver reports its link lost
 * becomes.
 */
class HighLevelRobotPlatformTest {

    private final ManualClock clock = new ManualClock();
    private final CountDownLatch building = new CountDownLatch(1);
    private final CountDownLatch reported = new CountDownLatch(1);
    private final HighLevelCommandPlatform driver = new HighLevelCommandPlatform("dog", clock) {
        @Override
        public Container container(HighLevelCommand command) {
            // the caller's thread is inside execute() when the driver's link thread reports the loss
            building.countDown();
            try {
                reported.await(10, TimeUnit.SECONDS);
            } catch (InterruptedException e) {
                Thread.currentThread().interrupt();
            }
            return super.container(command);
        }

        @Override
        protected void start(Run run) {
        }

        @Override
        protected void refresh(Run run) {
        }

        @Override
        protected void stop(Run run) {
        }
    };
    private final HighLevelRobotPlatform platform;

    HighLevelRobotPlatformTest() throws IOException {
        PlatformConfig config = new PlatformConfig("dog", "test", new ConnectionSettings(Map.of(), "dog.yaml"), List.of(), List.<SensorChannel>of(),
                Duration.ofMillis(10), Duration.ofMillis(500), clock, PlatformServices.none(), Cycling.BY_OWNER, FailurePolicy.logging());
        platform = new HighLevelRobotPlatform(config, driver, new SensorPlatform() {
            @Override
            public Sensor createSensor(SensorChannel channel) {
                throw new AssertionError("no sensors");
            }
        }, null);
    }

    @AfterEach
    void close() {
        platform.close();
    }

    @Test
    void aCommandHandedOverAsTheLinkIsReportedLostIsRefusedOrEndedNeverLeftForTheLinksReturn() throws Exception {
        CompletableFuture<CompletableFuture<Void>> walk = CompletableFuture.supplyAsync(() -> platform.execute(
                new HighLevelCommand("move", "robot.walk(2, 0.1)", Map.of(), Set.of("legs"), Duration.ofMinutes(1), false,
                        CommandPriority.NORMAL, Duration.ZERO, "robot.stop()")));
        assertTrue(building.await(10, TimeUnit.SECONDS), "the program's thread is handing the walk over");
        platform.linkFailed("urbi 127.0.0.1:54000", new IOException("connection reset"));
        reported.countDown();
        CompletableFuture<Void> done = walk.get(10, TimeUnit.SECONDS);
        platform.actionThread().cycle();
        platform.linkRestored();
        platform.actionThread().cycle();

        ExecutionException e = assertThrows(ExecutionException.class, () -> done.get(0, TimeUnit.SECONDS),
                "the walk neither refused nor ended: it waits for the link to come back, then moves the robot");
        assertInstanceOf(RobotLinkException.class, e.getCause());
        assertTrue(platform.actionThread().actuatorsInUse().isEmpty(), "nothing holds the legs");
    }
}
