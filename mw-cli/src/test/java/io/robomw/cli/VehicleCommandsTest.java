package io.robomw.cli;

import io.robomw.api.spi.FailurePolicy;
import io.robomw.sim.Simulation;
import io.robomw.sim.emulator.mavlink.MavlinkEmulator;
import io.robomw.sim.vehicle.SimVehicle;
import io.robomw.testkit.Await;
import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.Test;

import java.io.IOException;
import java.net.InetAddress;
import java.net.InetSocketAddress;
import java.nio.file.Path;
import java.time.Duration;
import java.util.Optional;
import java.util.Set;
import java.util.regex.Matcher;
import java.util.regex.Pattern;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * {@code mw robot FILE takeoff|climb|land} and {@code mw describe} on the example vehicles: the
 * example robot file, its link pointed ({@code --connection link=...}) at an emulated ArduPilot on
 * loopback, each command a robot opened, flown and closed, as a user types them one after another.
 */
class VehicleCommandsTest {

    private static final Path HARBOUR = Path.of("../examples/worlds/harbour.yaml");
    private static final Path COPTER = Path.of("../examples/robots/copter-ardupilot.yaml");
    private static final Path BOAT = Path.of("../examples/robots/boat.yaml");
    private static final Pattern ALTITUDE = Pattern.compile("altitude ([0-9.]+) m");

    private Simulation sim;
    private MavlinkEmulator emulator;

    private String emulate(String robot) throws IOException {
        sim = Simulation.load(HARBOUR, Set.of(robot));
        emulator = MavlinkEmulator.bind(sim, robot, Optional.empty(), FailurePolicy.logging());
        InetSocketAddress at = emulator.listen(new InetSocketAddress(InetAddress.getLoopbackAddress(), 0));
        sim.startRealTime(1);
        return "link=udpout://127.0.0.1:" + at.getPort();
    }

    @AfterEach
    void close() {
        if (emulator != null) {
            emulator.close();
        }
        if (sim != null) {
            sim.close();
        }
    }

    private static double altitude(CliRun run) {
        Matcher m = ALTITUDE.matcher(run.out());
        assertTrue(m.find(), "the pose printed has an altitude: " + run.out());
        return Double.parseDouble(m.group(1));
    }

    /**
     * Waits until the simulated copter holds altitude {@code z}: within 0.1 m of it and still (under
     * 0.05 m/s up or down), not passing through it on an overshoot, so that the next command, a
     * new process that climbs from where the copter is, starts from {@code z}. Says where it was last.
     */
    private void settlesAt(double z, String when) {
        SimVehicle.Snapshot[] last = {null};
        Await.until("the simulated copter holding " + z + " m " + when, Duration.ofSeconds(20), () -> {
            last[0] = sim.world().robot("copter").vehicle().snapshot();
            return Math.abs(last[0].z() - z) < 0.1 && Math.abs(last[0].vz()) < 0.05;
        }, () -> String.format(java.util.Locale.ROOT, "last at %.2f m, %.2f m/s", last[0].z(), last[0].vz()));
    }

    @Test
    void aCopterTakesOffClimbsAndLandsOneCommandAtATime() throws Exception {
        String link = emulate("copter");
        CliRun takeoff = CliRun.mw("robot", COPTER.toString(), "--connection", link, "takeoff", "2");
        assertEquals(0, takeoff.status(), takeoff.err());
        assertEquals(2.0, altitude(takeoff), 0.3, takeoff.out());
        settlesAt(2.0, "after mw robot takeoff 2 (it printed: " + takeoff.out().strip() + ")");

        CliRun climb = CliRun.mw("robot", COPTER.toString(), "--connection", link, "climb", "1", "0.5");
        assertEquals(0, climb.status(), climb.err());
        assertEquals(3.0, altitude(climb), 0.3, climb.out());
        settlesAt(3.0, "after mw robot climb 1 (it printed: " + climb.out().strip() + ")");

        CliRun land = CliRun.mw("robot", COPTER.toString(), "--connection", link, "land");
        assertEquals(0, land.status(), land.err());
        assertTrue(land.out().startsWith("landed"), land.out());
        assertTrue(sim.world().robot("copter").vehicle().snapshot().landed(), "on the ground after mw robot land");
    }

    @Test
    void aBoatThatIsToldToTakeOffIsAUsageErrorOnOneLine() throws Exception {
        String link = emulate("boat");
        CliRun takeoff = CliRun.mw("robot", BOAT.toString(), "--connection", link, "takeoff", "2");
        assertEquals(2, takeoff.status(), takeoff.toString());
        assertEquals(1, takeoff.errLines().size(), takeoff.err());
        assertTrue(takeoff.err().startsWith("mw robot takeoff: ") && takeoff.err().contains("boat"), takeoff.err());
        assertEquals(0.0, sim.world().robot("boat").vehicle().snapshot().z(), 1e-9);
    }

    @Test
    void describeShowsTheVehicleDriveAndWhatItsVerbsSend() {
        CliRun copter = CliRun.mw("describe", COPTER.toString());
        assertEquals(0, copter.status(), copter.err());
        assertTrue(copter.out().contains("drive: vehicle in the air, autopilot ardupilot"), copter.out());
        assertTrue(copter.out().contains("GUIDED"), copter.out());
        CliRun px4 = CliRun.mw("describe", "../examples/robots/copter-px4.yaml");
        assertEquals(0, px4.status(), px4.err());
        assertTrue(px4.out().contains("OFFBOARD"), px4.out());
    }
}
