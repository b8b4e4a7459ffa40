package io.robomw.sim.emulator.mavlink;

import io.robomw.api.Clock;
import io.robomw.api.RobotException;
import io.robomw.api.SensorType;
import io.robomw.api.spi.CommandPriority;
import io.robomw.api.spi.ConnectionSettings;
import io.robomw.api.spi.Cycling;
import io.robomw.api.spi.FailurePolicy;
import io.robomw.api.spi.HighLevelCommand;
import io.robomw.api.spi.HighLevelPlatform;
import io.robomw.api.spi.PlatformConfig;
import io.robomw.api.spi.PlatformServices;
import io.robomw.api.spi.RobotPlatform;
import io.robomw.api.spi.SensorChannel;
import io.robomw.config.description.VehicleDrive;
import io.robomw.platform.mavlink.MavlinkPlatformProvider;
import io.robomw.platform.mavlink.wire.SigningKey;
import io.robomw.sim.Simulation;
import io.robomw.sim.vehicle.SimVehicle;
import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.parallel.Execution;
import org.junit.jupiter.api.parallel.ExecutionMode;
import org.junit.jupiter.api.io.TempDir;

import java.io.IOException;
import java.net.InetAddress;
import java.net.InetSocketAddress;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.HashMap;
import java.util.List;
import java.util.Map;
import java.util.Optional;
import java.util.Set;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.ExecutionException;
import java.util.concurrent.TimeUnit;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertInstanceOf;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * {@code platform: mavlink} against the emulator, on loopback: the driver's high-level commands
 * (what the vehicle drive sends) fly the simulated copter in both dialects and sail the boat; its
 * sensors read the vehicle's telemetry. (Against an independent vehicle, pymavlink's: src-it.) The cases run
 * side by side: each has its own world, emulator, port and driver.
 */
@Execution(ExecutionMode.CONCURRENT)
class MavlinkDriverTest {

    private static final Path HARBOUR = Path.of("..", "examples", "worlds", "harbour.yaml");
    private static final Duration LONG = Duration.ofSeconds(60);

    private Simulation sim;
    private MavlinkEmulator emulator;
    private RobotPlatform platform;

    @TempDir
    Path dir;

    private HighLevelPlatform open(String robot, Optional<VehicleDrive.Autopilot> dialect) throws IOException {
        InetSocketAddress at = emulate(robot, dialect, Optional.empty());
        platform = new MavlinkPlatformProvider().open(config(robot, at, Map.of()));
        return (HighLevelPlatform) platform;
    }

    private InetSocketAddress emulate(String robot, Optional<VehicleDrive.Autopilot> dialect, Optional<SigningKey> key) throws IOException {
        sim = Simulation.load(HARBOUR, Set.of(robot));
        emulator = MavlinkEmulator.bind(sim, robot, dialect, FailurePolicy.logging());
        key.ifPresent(emulator::signing);
        InetSocketAddress at = emulator.listen(new InetSocketAddress(InetAddress.getLoopbackAddress(), 0));
        sim.startRealTime(1);
        return at;
    }

    private static PlatformConfig config(String robot, InetSocketAddress at, Map<String, Object> more) {
        Map<String, Object> connection = new HashMap<>(Map.of("link", "udpout://127.0.0.1:" + at.getPort(), "connect_timeout_ms", 10_000));
        connection.putAll(more);
        return new PlatformConfig(robot, "mavlink", new ConnectionSettings(connection, "test " + robot + ".yaml"),
                List.of(), List.of(new SensorChannel("below", SensorType.LASER, "distance:down", Map.of()),
                new SensorChannel("volts", SensorType.RANGE, "battery:volts", Map.of())),
                Duration.ofMillis(20), Duration.ofMillis(500), Clock.system(), PlatformServices.none(), Cycling.OWN_THREADS,
                FailurePolicy.logging());
    }

    @AfterEach
    void close() {
        if (platform != null) {
            platform.close();
        }
        if (emulator != null) {
            emulator.close();
        }
        if (sim != null) {
            sim.close();
        }
    }

    private static HighLevelCommand command(String name, Map<String, Double> args, double seconds) {
        return new HighLevelCommand(name, name + args, args, Set.of(VehicleDrive.VEHICLE), Duration.ofMillis(Math.round(seconds * 1000)), false,
                CommandPriority.NORMAL, Duration.ZERO, "");
    }

    private static void run(HighLevelPlatform p, HighLevelCommand c) {
        try {
            p.execute(c).get(LONG.toSeconds(), TimeUnit.SECONDS);
        } catch (Exception e) {
            throw new AssertionError(c.name() + " failed: " + e, e);
        }
    }

    private SimVehicle.Snapshot vehicle(String robot) {
        return sim.world().robot(robot).vehicle().snapshot();
    }

    private void fliesASquareCorner(String robot, Optional<VehicleDrive.Autopilot> dialect) throws Exception {
        HighLevelPlatform p = open(robot, dialect);
        run(p, command("takeoff", Map.of("altitude", 2.0), 4));
        assertEquals(2.0, vehicle(robot).z(), 0.2);
        double x0 = vehicle(robot).x();
        run(p, command("move", Map.of("distance", 2.0, "speed", 1.0, "acceptance_radius", 0.3), 2));
        assertEquals(x0 + 2, vehicle(robot).x(), 0.35, "2 m ahead, east (its heading)");
        assertEquals(2.0, vehicle(robot).z(), 0.25, "keeps its altitude while it moves");
        run(p, command("turn", Map.of("angle", Math.PI / 2, "speed", 0.8), 2));
        assertEquals(Math.PI / 2, vehicle(robot).heading(), 0.08, "a quarter turn left: north");
        assertEquals(2.0, vehicle(robot).z(), 0.25, "keeps its altitude while it turns");
        run(p, command("climb", Map.of("height", 1.0, "speed", 0.5), 2));
        assertEquals(3.0, vehicle(robot).z(), 0.2);
        double below = platform.readRaw("below").get(5, TimeUnit.SECONDS);
        assertEquals(3.0, below, 0.3, "the downward range finder sees the ground 3 m below (its last report, at most 0.1 s old)");
        assertTrue(platform.readRaw("volts").get(5, TimeUnit.SECONDS) > 13);
        run(p, command("land", Map.of(), 6));
        assertTrue(vehicle(robot).landed());
    }

    @Test
    void theDriverFliesAnArduCopter() throws Exception {
        fliesASquareCorner("copter", Optional.empty());
    }

    @Test
    void theDriverFliesAPx4CopterThroughOffboard() throws Exception {
        fliesASquareCorner("copter-px4", Optional.empty());
    }

    /**
     * PX4 answers OFFBOARD with TEMPORARILY_REJECTED when it has not seen the setpoint stream long
     * enough (a busy machine stalled the ground station's sender): "retrying later should work", so
     * the driver streams on and asks again instead of failing the move.
     */
    @Test
    void aPx4ThatRejectsOffboardForAWhileIsAskedAgainAndTheMoveGoesOn() throws Exception {
        InetSocketAddress at = emulate("copter-px4", Optional.empty(), Optional.empty());
        try (SetpointGapRelay relay = new SetpointGapRelay(at)) {
            HighLevelPlatform p = (HighLevelPlatform) (platform = new MavlinkPlatformProvider().open(config("copter-px4", relay.address(), Map.of())));
            run(p, command("takeoff", Map.of("altitude", 2.0), 4));
            double x0 = vehicle("copter-px4").x();
            run(p, command("move", Map.of("distance", 2.0, "speed", 1.0, "acceptance_radius", 0.3), 2));
            assertEquals(x0 + 2, vehicle("copter-px4").x(), 0.35, "2 m ahead");
            assertTrue(relay.held() > 0, "setpoints were held back before the first OFFBOARD request");
            assertTrue(relay.setModes() >= 2, "OFFBOARD was asked for again after PX4's TEMPORARILY_REJECTED: " + relay.setModes());
        }
    }

    @Test
    void aLostLinkFailsTheRunningCommandAndTheVehiclesOwnFailsafeActs() throws Exception {
        HighLevelPlatform p = open("boat", Optional.empty());
        CompletableFuture<Void> going = p.execute(command("move", Map.of("distance", 15.0, "speed", 1.0, "acceptance_radius", 0.5), 15));
        io.robomw.testkit.Await.until("the boat under way", Duration.ofSeconds(20), () -> vehicle("boat").surge() > 0.5);
        emulator.close(); // the vehicle goes silent: no HEARTBEAT for 3 s is a lost link
        ExecutionException e = assertThrows(ExecutionException.class, () -> going.get(20, TimeUnit.SECONDS));
        io.robomw.api.RobotLinkException lost = assertInstanceOf(io.robomw.api.RobotLinkException.class, e.getCause());
        assertTrue(lost.getMessage().contains("no HEARTBEAT from vehicle 1 for 3000 ms"), lost.getMessage());
        ExecutionException refused = assertThrows(ExecutionException.class,
                () -> p.execute(command("turn", Map.of("angle", 1.0, "speed", 0.5), 2)).get(10, TimeUnit.SECONDS));
        assertInstanceOf(io.robomw.api.RobotLinkException.class, refused.getCause(), "new commands are refused while the link is down");
        io.robomw.testkit.Await.until("the boat stopped (the emulator's last act: hold)", Duration.ofSeconds(20),
                () -> Math.abs(vehicle("boat").surge()) < 0.1);
    }

    @Test
    void theDriverSailsABoatAndItCannotTakeOff() throws Exception {
        HighLevelPlatform p = open("boat", Optional.empty());
        double x0 = vehicle("boat").x();
        run(p, command("move", Map.of("distance", 3.0, "speed", 1.0, "acceptance_radius", 0.5), 3));
        assertEquals(x0 + 3, vehicle("boat").x(), 0.7);
        run(p, command("turn", Map.of("angle", Math.PI / 2, "speed", 0.6), 3));
        // from the course it sailed (east; in the tide its heading crabbed), a quarter turn left: north
        assertEquals(Math.PI / 2, vehicle("boat").heading(), 0.12, "a quarter turn left of its course");
        CompletableFuture<Void> takeoff = p.execute(command("takeoff", Map.of("altitude", 2.0), 4));
        ExecutionException e = assertThrows(ExecutionException.class, () -> takeoff.get(10, TimeUnit.SECONDS));
        RobotException refused = assertInstanceOf(RobotException.class, e.getCause());
        assertTrue(refused.getMessage().contains("cannot take off"), refused.getMessage());
    }

    @Test
    void aSignedVehicleIsDrivenWithThePassphraseFromAFileAndNeverWithAnotherOrInline() throws Exception {
        InetSocketAddress at = emulate("copter", Optional.empty(), Optional.of(SigningKey.fromPassphrase("harbour pilots")));
        Files.writeString(dir.resolve("wrong.key"), "not the pilots' passphrase\n");
        MavlinkPlatformProvider provider = new MavlinkPlatformProvider();
        IOException wrong = assertThrows(IOException.class, () -> provider.open(
                config("copter", at, Map.of("signing_key_file", dir.resolve("wrong.key").toString(), "connect_timeout_ms", 3_000))).close());
        assertTrue(wrong.getMessage().contains("copter") && wrong.getMessage().contains("WRONG_SIGNATURE"), "the failure names the robot and the signature: " + wrong.getMessage());

        List<String> inline = provider.check(config("copter", at, Map.of("signing_key", "harbour pilots")));
        assertTrue(inline.stream().anyMatch(p -> p.contains("signing_key is not taken") && p.contains("signing_key_file")
                && !p.contains("harbour pilots")), "an inline passphrase is refused without being repeated: " + inline);

        Files.writeString(dir.resolve("pilots.key"), "harbour pilots\n");
        platform = provider.open(config("copter", at, Map.of("signing_key_file", dir.resolve("pilots.key").toString())));
        HighLevelPlatform p = (HighLevelPlatform) platform;
        run(p, command("takeoff", Map.of("altitude", 1.5), 6));
        assertEquals(1.5, vehicle("copter").z(), 0.3, "signed commands fly the signed vehicle");
        run(p, command("land", Map.of(), 8));
    }
}
