package io.robomw.sim.emulator.mavlink;

import io.robomw.api.spi.FailurePolicy;
import io.robomw.config.description.VehicleDrive;
import io.robomw.platform.mavlink.wire.CoordinateFrame;
import io.robomw.platform.mavlink.wire.Frame;
import io.robomw.platform.mavlink.wire.FrameEncoder;
import io.robomw.platform.mavlink.wire.LandedState;
import io.robomw.platform.mavlink.wire.MavAutopilot;
import io.robomw.platform.mavlink.wire.MavCmd;
import io.robomw.platform.mavlink.wire.MavResult;
import io.robomw.platform.mavlink.wire.MavType;
import io.robomw.platform.mavlink.wire.Messages;
import io.robomw.platform.mavlink.wire.MissionResult;
import io.robomw.platform.mavlink.wire.ModeFlag;
import io.robomw.platform.mavlink.wire.Payload;
import io.robomw.platform.mavlink.wire.Signer;
import io.robomw.platform.mavlink.wire.SigningKey;
import io.robomw.platform.mavlink.wire.TypeMask;
import io.robomw.sim.Simulation;
import io.robomw.testkit.Await;
import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.parallel.Execution;
import org.junit.jupiter.api.parallel.ExecutionMode;

import java.io.IOException;
import java.net.InetAddress;
import java.net.InetSocketAddress;
import java.nio.file.Path;
import java.time.InstantSource;
import java.util.Optional;
import java.util.Set;

import static io.robomw.sim.emulator.mavlink.TestGroundStation.WAIT;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * The emulator against a small ground station made of the codec (the independent clients, MAVSDK
 * and pymavlink, fly it in src-it): the harbour world in real time, a real UDP socket on loopback.
 * The cases run side by side: each has its own world, emulator, port and ground station.
 */
@Execution(ExecutionMode.CONCURRENT)
class MavlinkEmulatorTest {

    private static final Path HARBOUR = Path.of("..", "examples", "worlds", "harbour.yaml");
    private static final InetSocketAddress LOOPBACK = new InetSocketAddress(InetAddress.getLoopbackAddress(), 0);

    private Simulation sim;
    private MavlinkEmulator emulator;
    private TestGroundStation gcs;

    private TestGroundStation start(String robot, Optional<VehicleDrive.Autopilot> dialect) throws IOException {
        sim = Simulation.load(HARBOUR, Set.of(robot));
        emulator = MavlinkEmulator.bind(sim, robot, dialect, FailurePolicy.logging());
        InetSocketAddress at = emulator.listen(LOOPBACK);
        sim.startRealTime(1);
        gcs = new TestGroundStation(at);
        gcs.send(Payload.of(Messages.Heartbeat.MESSAGE).set(Messages.Heartbeat.TYPE, MavType.GCS.code())
                .set(Messages.Heartbeat.AUTOPILOT, MavAutopilot.INVALID.code()));
        return gcs;
    }

    @AfterEach
    void stop() throws InterruptedException {
        if (gcs != null) {
            gcs.close();
        }
        if (emulator != null) {
            emulator.close();
        }
        if (sim != null) {
            sim.close();
        }
    }

    /** Waits until a value holds a condition, and returns it. */
    private static <T> T value(java.util.function.Supplier<T> what, java.util.function.Predicate<T> condition) {
        Object[] seen = new Object[1];
        Await.until("a value that holds", WAIT, () -> {
            T v = what.get();
            seen[0] = v;
            return condition.test(v);
        }, () -> String.valueOf(seen[0]));
        @SuppressWarnings("unchecked")
        T v = (T) seen[0];
        return v;
    }

    private double altitude() {
        return gcs.latest(Messages.GlobalPositionInt.MESSAGE).getLong(Messages.GlobalPositionInt.RELATIVE_ALT) / 1000.0;
    }

    private long customMode() {
        return gcs.latest(Messages.Heartbeat.MESSAGE).getLong(Messages.Heartbeat.CUSTOM_MODE);
    }

    @Test
    void anArduCopterArmsTakesOffInGuidedFliesToAPositionAndLands() throws IOException {
        start("copter", Optional.empty());
        Payload hb = gcs.awaitLatest(Messages.Heartbeat.MESSAGE);
        assertEquals(MavType.QUADROTOR.code(), hb.getLong(Messages.Heartbeat.TYPE));
        assertEquals(MavAutopilot.ARDUPILOTMEGA.code(), hb.getLong(Messages.Heartbeat.AUTOPILOT));
        assertEquals(MavResult.FAILED, gcs.command(MavCmd.NAV_TAKEOFF, 0, 0, 0, 0, 0, 0, 2), "not armed, not GUIDED");
        assertEquals(MavResult.ACCEPTED, gcs.command(MavCmd.DO_SET_MODE, 1, 4));
        assertEquals(MavResult.ACCEPTED, gcs.command(MavCmd.COMPONENT_ARM_DISARM, 1));
        assertEquals(MavResult.ACCEPTED, gcs.command(MavCmd.NAV_TAKEOFF, 0, 0, 0, 0, 0, 0, 2));
        Await.until("at 2 m", WAIT, () -> gcs.latest(Messages.GlobalPositionInt.MESSAGE) != null && altitude() > 1.9);
        assertEquals(4, customMode());
        assertTrue(ModeFlag.SAFETY_ARMED.in(gcs.latest(Messages.Heartbeat.MESSAGE).getLong(Messages.Heartbeat.BASE_MODE)));
        // 3 m north, 2 m east of the origin, 2.5 m up, in LOCAL_NED
        gcs.send(Payload.of(Messages.SetPositionTargetLocalNed.MESSAGE)
                .set(Messages.SetPositionTargetLocalNed.TARGET_SYSTEM, 1).set(Messages.SetPositionTargetLocalNed.TARGET_COMPONENT, 1)
                .set(Messages.SetPositionTargetLocalNed.COORDINATE_FRAME, CoordinateFrame.LOCAL_NED.code())
                .set(Messages.SetPositionTargetLocalNed.TYPE_MASK, TypeMask.POSITION)
                .set(Messages.SetPositionTargetLocalNed.X, 3).set(Messages.SetPositionTargetLocalNed.Y, 2)
                .set(Messages.SetPositionTargetLocalNed.Z, -2.5));
        Await.until("at the target", WAIT, () -> {
            Payload l = gcs.latest(Messages.LocalPositionNed.MESSAGE);
            return Math.abs(l.getDouble(Messages.LocalPositionNed.X) - 3) < 0.2 && Math.abs(l.getDouble(Messages.LocalPositionNed.Y) - 2) < 0.2
                    && Math.abs(l.getDouble(Messages.LocalPositionNed.Z) + 2.5) < 0.2;
        }, () -> String.valueOf(gcs.latest(Messages.LocalPositionNed.MESSAGE)));
        assertEquals(MavResult.DENIED, gcs.command(MavCmd.COMPONENT_ARM_DISARM, 0), "no disarming in flight");
        assertEquals(MavResult.ACCEPTED, gcs.command(MavCmd.NAV_LAND));
        Await.until("landed and disarmed", WAIT, () -> gcs.latest(Messages.ExtendedSysState.MESSAGE).getLong(Messages.ExtendedSysState.LANDED_STATE)
                == LandedState.ON_GROUND.code() && !ModeFlag.SAFETY_ARMED.in(gcs.latest(Messages.Heartbeat.MESSAGE).getLong(Messages.Heartbeat.BASE_MODE)));
        assertEquals(9, customMode(), "LAND");
    }

    @Test
    void px4TakesOffWithNanParamsToMisTakeoffAltAndOffboardNeedsASetpointStream() throws IOException {
        start("copter-px4", Optional.empty());
        assertEquals(MavAutopilot.PX4.code(), gcs.awaitLatest(Messages.Heartbeat.MESSAGE).getLong(Messages.Heartbeat.AUTOPILOT));
        assertEquals(MavResult.ACCEPTED, gcs.command(MavCmd.COMPONENT_ARM_DISARM, 1, Double.NaN, Double.NaN, Double.NaN, Double.NaN, Double.NaN, Double.NaN));
        double nan = Double.NaN;
        assertEquals(MavResult.ACCEPTED, gcs.command(MavCmd.NAV_TAKEOFF, nan, nan, nan, nan, nan, nan, nan));
        Await.until("at MIS_TAKEOFF_ALT 2.5 m, holding", WAIT, () -> gcs.latest(Messages.GlobalPositionInt.MESSAGE) != null && altitude() > 2.4
                && customMode() == (4L << 16 | 3L << 24));
        assertEquals(MavResult.TEMPORARILY_REJECTED, gcs.command(MavCmd.DO_SET_MODE, 1, 6, 0), "OFFBOARD without a setpoint stream");
        Payload up = Payload.of(Messages.SetPositionTargetLocalNed.MESSAGE)
                .set(Messages.SetPositionTargetLocalNed.TARGET_SYSTEM, 1).set(Messages.SetPositionTargetLocalNed.TARGET_COMPONENT, 1)
                .set(Messages.SetPositionTargetLocalNed.COORDINATE_FRAME, CoordinateFrame.LOCAL_NED.code())
                .set(Messages.SetPositionTargetLocalNed.TYPE_MASK, TypeMask.VELOCITY)
                .set(Messages.SetPositionTargetLocalNed.VZ, -0.5);
        long start = System.nanoTime();
        while (System.nanoTime() - start < 1_500_000_000L) { // a 20 Hz stream for 1.5 s, as MAVSDK streams
            gcs.send(up);
            java.util.concurrent.locks.LockSupport.parkNanos(50_000_000);
        }
        gcs.send(up);
        assertEquals(MavResult.ACCEPTED, gcs.command(MavCmd.DO_SET_MODE, 1, 6, 0));
        assertEquals(6L << 16, (long) value(this::customMode, m -> m == 6L << 16));
        // the stream stops: PX4 leaves OFFBOARD for AUTO.LOITER after COM_OF_LOSS_T
        Await.until("offboard lost: holding", WAIT, () -> customMode() == (4L << 16 | 3L << 24));
        assertTrue(gcs.received.stream().anyMatch(f -> f.is(Messages.Statustext.MESSAGE)
                && f.payload().getText(Messages.Statustext.TEXT).contains("offboard")));
    }

    @Test
    void aBoatIsASurfaceBoatInGuided15AndCannotTakeOff() throws IOException {
        start("boat", Optional.empty());
        assertEquals(MavType.SURFACE_BOAT.code(), gcs.awaitLatest(Messages.Heartbeat.MESSAGE).getLong(Messages.Heartbeat.TYPE));
        assertEquals(MavResult.ACCEPTED, gcs.command(MavCmd.DO_SET_MODE, 1, 15));
        assertEquals(MavResult.ACCEPTED, gcs.command(MavCmd.COMPONENT_ARM_DISARM, 1));
        assertEquals(MavResult.UNSUPPORTED, gcs.command(MavCmd.NAV_TAKEOFF, 0, 0, 0, 0, 0, 0, 2));
        assertEquals(MavResult.UNSUPPORTED, gcs.command(MavCmd.NAV_LAND));
        assertEquals(MavResult.DENIED, gcs.command(MavCmd.DO_SET_MODE, 1, 9), "a boat has no LAND mode");
        assertEquals(15L, (long) value(this::customMode, m -> m == 15), "GUIDED on a boat is 15");
        // 1 m/s forward in the body frame: it goes east, and the velocity target expires after 3 s
        Payload ahead = Payload.of(Messages.SetPositionTargetLocalNed.MESSAGE)
                .set(Messages.SetPositionTargetLocalNed.TARGET_SYSTEM, 1).set(Messages.SetPositionTargetLocalNed.TARGET_COMPONENT, 1)
                .set(Messages.SetPositionTargetLocalNed.COORDINATE_FRAME, CoordinateFrame.BODY_NED.code())
                .set(Messages.SetPositionTargetLocalNed.TYPE_MASK, TypeMask.VELOCITY_YAW_RATE)
                .set(Messages.SetPositionTargetLocalNed.VX, 1);
        gcs.send(ahead);
        Await.until("moving east", WAIT, () -> gcs.latest(Messages.LocalPositionNed.MESSAGE).getDouble(Messages.LocalPositionNed.VY) > 0.5);
        Await.until("stopped after the guided timeout", WAIT, () -> gcs.received.stream().anyMatch(f -> f.is(Messages.Statustext.MESSAGE)
                && f.payload().getText(Messages.Statustext.TEXT).startsWith("target not received last 3.0 secs")));
    }

    @Test
    void unusedParamsAsNanAndUnknownCommandsAreAnswered() throws IOException {
        start("rover", Optional.empty());
        gcs.awaitLatest(Messages.Heartbeat.MESSAGE);
        assertEquals(MavResult.UNSUPPORTED, gcs.command(MavCmd.REQUEST_PROTOCOL_VERSION, Double.NaN));
        assertEquals(MavResult.ACCEPTED, gcs.command(MavCmd.REQUEST_MESSAGE, 148, Double.NaN, Double.NaN));
        Payload v = gcs.awaitLatest(Messages.AutopilotVersion.MESSAGE);
        assertTrue((v.getLong(Messages.AutopilotVersion.CAPABILITIES) & 8192) != 0, "MAVLink 2");
        assertEquals(MavResult.ACCEPTED, gcs.command(MavCmd.SET_MESSAGE_INTERVAL, Messages.ExtendedSysState.MESSAGE.id(), 1e6));
        assertEquals(10, gcs.latest(Messages.Heartbeat.MESSAGE).getLong(Messages.Heartbeat.TYPE), "rover");
    }

    @Test
    void aMissionIsUploadedDownloadedAndFlownWithItsProgress() throws IOException {
        start("rover", Optional.empty());
        gcs.awaitLatest(Messages.Heartbeat.MESSAGE);
        LocalFrame lf = new LocalFrame(sim.world().description().surroundings().home(), 8, 16);
        double[][] points = {{8, 16}, {8, 19}, {11, 19}};   // home (ArduPilot's item 0), then two waypoints
        gcs.send(Payload.of(Messages.MissionCount.MESSAGE).set(Messages.MissionCount.TARGET_SYSTEM, 1)
                .set(Messages.MissionCount.TARGET_COMPONENT, 1).set(Messages.MissionCount.COUNT, points.length));
        for (int i = 0; i < points.length; i++) {
            int seq = i;
            Await.until("MISSION_REQUEST_INT " + seq, WAIT, () -> gcs.received.stream().anyMatch(f -> f.is(Messages.MissionRequestInt.MESSAGE)
                    && f.payload().getLong(Messages.MissionRequestInt.SEQ) == seq
                    && f.payload().getLong(Messages.MissionRequestInt.TARGET_SYSTEM) == 245));
            gcs.send(Payload.of(Messages.MissionItemInt.MESSAGE).set(Messages.MissionItemInt.TARGET_SYSTEM, 1)
                    .set(Messages.MissionItemInt.TARGET_COMPONENT, 1).set(Messages.MissionItemInt.SEQ, seq)
                    .set(Messages.MissionItemInt.FRAME, CoordinateFrame.GLOBAL_RELATIVE_ALT_INT.code())
                    .set(Messages.MissionItemInt.COMMAND, MavCmd.NAV_WAYPOINT.code()).set(Messages.MissionItemInt.AUTOCONTINUE, 1)
                    .set(Messages.MissionItemInt.X, Math.round(lf.latitude(points[i][1]) * 1e7))
                    .set(Messages.MissionItemInt.Y, Math.round(lf.longitude(points[i][0]) * 1e7)));
        }
        Payload ack = value(() -> gcs.latest(Messages.MissionAck.MESSAGE), a -> a != null);
        assertEquals(MissionResult.ACCEPTED.code(), ack.getLong(Messages.MissionAck.TYPE));
        gcs.send(Payload.of(Messages.MissionRequestList.MESSAGE).set(Messages.MissionRequestList.TARGET_SYSTEM, 1)
                .set(Messages.MissionRequestList.TARGET_COMPONENT, 1));
        Await.until("MISSION_COUNT 3", WAIT, () -> gcs.latest(Messages.MissionCount.MESSAGE) != null
                && gcs.latest(Messages.MissionCount.MESSAGE).getLong(Messages.MissionCount.COUNT) == 3);
        assertEquals(MavResult.ACCEPTED, gcs.command(MavCmd.COMPONENT_ARM_DISARM, 1));
        assertEquals(MavResult.ACCEPTED, gcs.command(MavCmd.MISSION_START));
        assertEquals(10L, (long) value(this::customMode, m -> m == 10), "AUTO");
        Await.until("both waypoints reached", Duration60.WAIT, () -> gcs.received.stream().filter(f -> f.is(Messages.MissionItemReached.MESSAGE))
                .map(f -> f.payload().getLong(Messages.MissionItemReached.SEQ)).toList().containsAll(java.util.List.of(1L, 2L)));
        Await.until("holding at the end", WAIT, () -> customMode() == 4);
    }

    /** A longer wait, for a whole mission in real time. */
    static final class Duration60 {
        static final java.time.Duration WAIT = java.time.Duration.ofSeconds(60);
    }

    @Test
    void withAKeyUnsignedAndWronglySignedCommandsAreIgnored() throws IOException, InterruptedException {
        SigningKey key = SigningKey.fromPassphrase("harbour master");
        sim = Simulation.load(HARBOUR, Set.of("boat"));
        emulator = MavlinkEmulator.bind(sim, "boat", Optional.empty(), FailurePolicy.logging()).signing(key);
        InetSocketAddress at = emulator.listen(LOOPBACK);
        sim.startRealTime(1);
        try (TestGroundStation unsigned = new TestGroundStation(at);
             TestGroundStation wrong = new TestGroundStation(at, new FrameEncoder(245, 190).signWith(
                     new Signer(SigningKey.fromPassphrase("pirate"), 0, InstantSource.system())))) {
            gcs = new TestGroundStation(at, new FrameEncoder(245, 190).signWith(new Signer(key, 0, InstantSource.system())));
            gcs.send(Payload.of(Messages.Heartbeat.MESSAGE));
            Frame hb = value(() -> gcs.received.stream().filter(f -> f.is(Messages.Heartbeat.MESSAGE)).findFirst().orElse(null),
                    f -> f != null);
            assertTrue(hb.signed(), "the vehicle signs what it sends");
            Payload arm = Payload.of(Messages.CommandLong.MESSAGE).set(Messages.CommandLong.TARGET_SYSTEM, 1)
                    .set(Messages.CommandLong.TARGET_COMPONENT, 1).set(Messages.CommandLong.COMMAND, MavCmd.COMPONENT_ARM_DISARM.code())
                    .set(Messages.CommandLong.PARAM1, 1);
            unsigned.send(arm);
            wrong.send(arm);
            Await.until("two refused", WAIT, () -> emulator.refused() >= 2);
            assertTrue(unsigned.received.stream().noneMatch(f -> f.is(Messages.CommandAck.MESSAGE)));
            assertTrue(!ModeFlag.SAFETY_ARMED.in(gcs.awaitLatest(Messages.Heartbeat.MESSAGE).getLong(Messages.Heartbeat.BASE_MODE)));
            assertEquals(MavResult.ACCEPTED, gcs.command(MavCmd.COMPONENT_ARM_DISARM, 1));
        }
    }
}
