package io.robomw.cli;

import io.robomw.api.Robot;
import io.robomw.api.Robots;
import io.robomw.api.spi.FailurePolicy;
import io.robomw.api.spi.PlatformServices;
import io.robomw.config.robot.ConnectionOverride;
import io.robomw.sim.Simulation;
import io.robomw.sim.emulator.mavlink.MavlinkEmulator;
import io.robomw.testkit.Await;
import org.junit.jupiter.api.Test;
import picocli.CommandLine;

import java.io.PipedInputStream;
import java.io.PipedOutputStream;
import java.io.PrintWriter;
import java.io.StringWriter;
import java.net.InetAddress;
import java.net.InetSocketAddress;
import java.nio.charset.StandardCharsets;
import java.nio.file.Path;
import java.time.Duration;
import java.util.Map;
import java.util.Optional;
import java.util.Set;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.TimeUnit;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * {@code mw robot COPTER teleop}'s keys fly: r (and PageUp) climb a step, f (and PageDown) descend
 * one, through the example copter's driver and an emulated ArduCopter on loopback; x quits, and
 * the copter hovers where the keys left it.
 */
class TeleopFliesTest {

    private static final Path HARBOUR = Path.of("../examples/worlds/harbour.yaml");
    private static final Path COPTER = Path.of("../examples/robots/copter-ardupilot.yaml");
    private static final Duration WAIT = Duration.ofSeconds(30);

    @Test
    void upAndDownKeysClimbAndDescendAStepAndXQuits() throws Exception {
        try (Simulation sim = Simulation.load(HARBOUR, Set.of("copter"));
             MavlinkEmulator emulator = MavlinkEmulator.bind(sim, "copter", Optional.empty(), FailurePolicy.logging())) {
            InetSocketAddress at = emulator.listen(new InetSocketAddress(InetAddress.getLoopbackAddress(), 0));
            sim.startRealTime(1);
            PlatformServices services = PlatformServices.none().with(ConnectionOverride.class,
                    new ConnectionOverride(Map.of("link", "udpout://127.0.0.1:" + at.getPort())));
            try (Robot copter = Robots.open(COPTER, services)) {
                copter.takeOff(2);
                CommandLine mw = Mw.commandLine(); // its options and their defaults, as the launcher parses them
                mw.parseArgs("robot", COPTER.toString(), "teleop", "--climb-step", "0.5");
                TeleopCommand teleop = mw.getSubcommands().get("robot").getSubcommands().get("teleop").getCommand();
                PipedOutputStream keys = new PipedOutputStream();
                PipedInputStream typed = new PipedInputStream(keys);
                StringWriter printed = new StringWriter();
                CompletableFuture<Integer> ended = CompletableFuture.supplyAsync(() -> {
                    try {
                        return teleop.drive(copter, typed, new PrintWriter(printed, true));
                    } catch (Exception e) {
                        throw new IllegalStateException(e);
                    }
                });
                keys.write("rr".getBytes(StandardCharsets.US_ASCII));
                keys.flush();
                Await.until("two r keys: 3 m, both steps", WAIT, () -> Math.abs(altitude(sim) - 3.0) < 0.15, () -> "at " + altitude(sim) + " m; " + printed);
                keys.write("\u001b[6~".getBytes(StandardCharsets.US_ASCII)); // PageDown
                keys.flush();
                Await.until("PageDown: 2.5 m", WAIT, () -> Math.abs(altitude(sim) - 2.5) < 0.15, () -> "at " + altitude(sim) + " m; " + printed);
                keys.write('x');
                keys.flush();
                assertEquals(0, ended.get(WAIT.toSeconds(), TimeUnit.SECONDS), printed.toString());
                assertTrue(printed.toString().contains("r/f up/down"), printed.toString());
                // the two r keys were typed at once: flown as one climb of 1 m, or as two of 0.5 m if the first had begun
                assertTrue(printed.toString().contains("climbed ") && printed.toString().contains("descended 0.50 m"), printed.toString());
                assertEquals(2.5, altitude(sim), 0.2, "hovering where the keys left it");
                copter.land();
            }
        }
    }

    private static double altitude(Simulation sim) {
        return sim.world().robot("copter").vehicle().snapshot().z();
    }
}
