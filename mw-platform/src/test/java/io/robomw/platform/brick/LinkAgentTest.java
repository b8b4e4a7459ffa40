package io.robomw.platform.brick;

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
import io.robomw.platform.BrickPlatform;
import io.robomw.platform.link.Communicator;
import io.robomw.platform.link.LinkLostException;
import io.robomw.platform.motor.FeedbackSink;
import io.robomw.platform.motor.LinkTiming;
import io.robomw.platform.motor.MotorDriver;
import io.robomw.platform.motor.MotorPlatform;
import io.robomw.platform.motor.MotorState;
import io.robomw.platform.sensor.Sensor;
import io.robomw.platform.sensor.SensorPlatform;
import io.robomw.platform.testkit.ScriptedLink;
import io.robomw.testkit.Await;
import io.robomw.testkit.LogLines;
import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.Test;

import java.io.IOException;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.Map;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.CopyOnWriteArrayList;
import java.util.concurrent.ExecutionException;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicBoolean;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertInstanceOf;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * The link agent on its own thread and the wall clock, over a channel to a brick that can be
 * unplugged: one link state, changed by whichever thread's exchange finds the link lost, one log
 * line per change; while down, every command is stopped, new ones are refused and exchanges fail at
 * once naming the robot; the agent alone reopens the link, and then everything works again.
 */
class LinkAgentTest {

    /** Sends one byte per motor state (1 running, 0 stopped) and reads its echo; polls with one byte. */
    static final class EchoMotors implements MotorDriver {
        final List<List<MotorState>> sent = new CopyOnWriteArrayList<>();
        private final BrickChannel channel;

        EchoMotors(BrickChannel channel) {
            this.channel = channel;
        }

        @Override
        public LinkTiming timing() {
            return LinkTiming.NONE;
        }

        @Override
        public void send(List<MotorState> motors, FeedbackSink feedback) throws IOException {
            byte[] bytes = new byte[motors.size()];
            for (int i = 0; i < bytes.length; i++) {
                bytes[i] = (byte) (motors.get(i).running() ? 1 : 0);
            }
            ping(bytes);
            sent.add(List.copyOf(motors));
        }

        @Override
        public int poll(FeedbackSink feedback) throws IOException {
            ping(new byte[] {7});
            return 0;
        }

        void ping(byte[] bytes) throws IOException {
            channel.exchange((c, timeout) -> {
                c.send(bytes);
                return c.receiveExactly(bytes.length, timeout);
            });
        }
    }

    /** A brick that echoes what is written to it, and can be unplugged (a Bluetooth link out of range). */
    private final ScriptedLink brick = new ScriptedLink().named("pluggable brick").answering(written -> written);
    private BrickChannel channel;
    private EchoMotors motors;
    private BrickPlatform platform;

    private void open() throws IOException {
        Communicator c = new Communicator(brick);
        c.open();
        channel = new BrickChannel("pluggable", c, Duration.ofMillis(300));
        motors = new EchoMotors(channel);
        PlatformConfig config = new PlatformConfig("pluggable", "fake", new ConnectionSettings(Map.of(), "test"),
                List.of(MotorChannel.actuator("B"), MotorChannel.actuator("C")), List.of(), Duration.ofMillis(10), Duration.ZERO, Clock.system(),
                PlatformServices.none(), Cycling.OWN_THREADS, FailurePolicy.logging());
        MotorPlatform motorPlatform = new MotorPlatform(config, motors);
        SensorPlatform sensors = new SensorPlatform(motorPlatform) {
            @Override
            public Sensor createSensor(SensorChannel s) {
                return () -> CompletableFuture.completedFuture(0.0);
            }
        };
        platform = new BrickPlatform(config, motorPlatform, sensors, channel, null).start();
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
    void aLinkLostOnAnyThreadIsDownOnceStopsEveryCommandAndIsReopenedByTheAgentAlone() throws Exception {
        try (LogLines log = new LogLines()) {
            open();
            CompletableFuture<Void> drive = platform.run(driveForever());
            Await.until("the motors were started", Duration.ofSeconds(10), () -> !motors.sent.isEmpty());

            brick.unplug();
            // A program's exchange (a sensor read) finds the link lost first, or the agent's poll does.
            assertThrows(IOException.class, () -> motors.ping(new byte[] {9}));
            Await.until("the link is down", Duration.ofSeconds(10), () -> platform.linkState() == LinkState.DOWN);
            RobotLinkException stopped = assertInstanceOf(RobotLinkException.class,
                    assertThrows(ExecutionException.class, () -> drive.get(10, TimeUnit.SECONDS)).getCause());
            assertTrue(stopped.getMessage().contains("robot 'pluggable'"), stopped.getMessage());

            LinkLostException refused = assertThrows(LinkLostException.class, () -> motors.ping(new byte[] {9}));
            assertTrue(refused.getMessage().contains("robot 'pluggable'") && refused.getMessage().contains("down"), refused.getMessage());
            ExecutionException later = assertThrows(ExecutionException.class, () -> platform.run(driveForever()).get(10, TimeUnit.SECONDS));
            assertTrue(later.getCause().getMessage().contains("is down"), later.getCause().getMessage());

            brick.plugIn();
            Await.until("the agent reopened the link", Duration.ofSeconds(10), () -> platform.linkState() == LinkState.UP);
            int before = motors.sent.size();
            CompletableFuture<Void> again = platform.run(driveForever());
            Await.until("the motors run again", Duration.ofSeconds(10), () -> motors.sent.size() > before);
            again.cancel(true);

            // The tests log warnings only: the return's line is at info level.
            assertEquals(1, log.containing("pluggable brick").size(), "one line for the loss, from one place: " + log.containing("pluggable brick"));
        }
    }

    /**
     * Commands submitted by other threads at the moment the link is lost either fail with the loss or are refused (or, detached,
     * are dropped): none is left admitted to wait on the gone link (it would run after the reconnect, long after its caller saw the link down).
     * Each round: one thread runs drives and another sends detached ones (a program's {@code drive} at its own rate) without
     * pause, the brick is unplugged and a read finds it, and once the link is down every future the first got must end and
     * no command may hold the motors, with the brick still unplugged.
     */
    @Test
    void noCommandSubmittedAsTheLinkIsLostIsLeftWaitingForItToComeBack() throws Exception {
        open();
        for (int round = 0; round < 12; round++) {
            Await.until("the link is up (round " + round + ")", Duration.ofSeconds(10), () -> platform.linkState() == LinkState.UP);
            List<CompletableFuture<Void>> submitted = new CopyOnWriteArrayList<>();
            AtomicBoolean submitting = new AtomicBoolean(true);
            List<Thread> submitters = new ArrayList<>();
            for (int t = 0; t < 2; t++) {
                boolean detached = t == 1;
                Thread s = new Thread(() -> {
                    while (submitting.get()) {
                        if (detached) {
                            // a program's drive(v, ω) at its own rate: nobody waits for it
                            platform.runDetached(MotorCommand.of("drive", List.of(MotorTarget.run("B", 180), MotorTarget.run("C", 180))));
                        } else {
                            submitted.add(platform.run(driveForever()));
                        }
                    }
                }, detached ? "detached-submitter" : "submitter");
                s.start();
                submitters.add(s);
            }
            int before = motors.sent.size();
            Await.until("drives reach the brick", Duration.ofSeconds(10), () -> motors.sent.size() > before);
            brick.unplug();
            assertThrows(IOException.class, () -> motors.ping(new byte[] {9}));
            Await.until("the link is down", Duration.ofSeconds(10), () -> platform.linkState() == LinkState.DOWN);
            submitting.set(false);
            for (Thread s : submitters) {
                s.join(10_000);
            }
            int r = round;
            Await.until("every drive submitted around the loss ended (round " + r + ", " + submitted.size() + " submitted)",
                    Duration.ofSeconds(10), () -> submitted.stream().allMatch(CompletableFuture::isDone));
            assertTrue(submitted.stream().allMatch(CompletableFuture::isCompletedExceptionally), "none of them finished: the motors run forever");
            Await.until("no command holds a motor while the link is down (round " + r + ")", Duration.ofSeconds(10),
                    () -> platform.actionThread().actuatorsInUse().isEmpty());
            brick.plugIn();
        }
    }
}
