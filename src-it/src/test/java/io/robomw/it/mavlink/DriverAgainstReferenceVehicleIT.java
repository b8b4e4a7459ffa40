package io.robomw.it.mavlink;

import io.robomw.api.Clock;
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
import io.robomw.platform.mavlink.MavlinkPlatformProvider;
import org.junit.jupiter.api.Test;

import java.time.Duration;
import java.util.List;
import java.util.Map;
import java.util.Set;
import java.util.concurrent.TimeUnit;
import java.util.regex.Matcher;
import java.util.regex.Pattern;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * {@code platform: mavlink} against a vehicle it was not written with: reference_vehicle.py,
 * written with pymavlink alone, sends to the driver's port as ArduPilot SITL's --out does, and
 * prints every message it receives. The driver must behave as ArduPilot and PX4 expect a ground
 * station to: its own HEARTBEAT at 1 Hz as a GCS, GUIDED 4 on a copter and 15 on a boat, PX4's
 * take-off altitude as a parameter and OFFBOARD only after a second of setpoints, commands sent
 * again when not answered, IN_PROGRESS waited out, setpoints at 10 Hz or more while a command runs.
 */
class DriverAgainstReferenceVehicleIT {

    private static final Duration WAIT = Duration.ofSeconds(60);
    private static final Pattern SETPOINT_TIME = Pattern.compile("RX SET_POSITION_TARGET_LOCAL_NED .* t=([0-9.]+)");

    private static RobotPlatform open(String robot, int port) throws Exception {
        PlatformConfig config = new PlatformConfig(robot, "mavlink",
                new ConnectionSettings(Map.of("link", "udpin://127.0.0.1:" + port, "connect_timeout_ms", 30_000), "it " + robot + ".yaml"),
                List.of(), List.of(new SensorChannel("below", SensorType.LASER, "distance:down", Map.of())),
                Duration.ofMillis(20), Duration.ofMillis(500), Clock.system(), PlatformServices.none(), Cycling.OWN_THREADS,
                FailurePolicy.logging());
        return new MavlinkPlatformProvider().open(config);
    }

    private static HighLevelCommand command(String name, Map<String, Double> args, double seconds) {
        return new HighLevelCommand(name, name + args, args, Set.of("vehicle"), Duration.ofMillis(Math.round(seconds * 1000)), false,
                CommandPriority.NORMAL, Duration.ZERO, "");
    }

    private static void run(RobotPlatform p, HighLevelCommand c) throws Exception {
        ((HighLevelPlatform) p).execute(c).get(WAIT.toSeconds(), TimeUnit.SECONDS);
    }

    private static List<String> received(VehiclePython vehicle, String what) {
        return vehicle.transcript().stream().filter(l -> l.startsWith("RX " + what)).toList();
    }

    /** @return the most setpoint-to-setpoint gap, seconds, among the setpoints from the {@code from}th on */
    /** @return the gaps between the setpoints' arrivals at the vehicle, seconds, in order */
    private static List<Double> gaps(List<String> setpoints) {
        List<Double> gaps = new java.util.ArrayList<>();
        double last = Double.NaN;
        for (String l : setpoints) {
            Matcher m = SETPOINT_TIME.matcher(l);
            if (m.find()) {
                double t = Double.parseDouble(m.group(1));
                if (!Double.isNaN(last)) {
                    gaps.add(t - last);
                }
                last = t;
            }
        }
        return gaps;
    }

    @Test
    void anArduCopterIsFlownAsArduPilotExpects() throws Exception {
        int port = VehiclePython.freeUdpPort();
        try (VehiclePython vehicle = VehiclePython.start("reference-copter", "reference_vehicle.py", "--out", "127.0.0.1:" + port,
                "--type", "copter", "--autopilot", "ardupilot", "--drop-first-arm", "--takeoff-in-progress");
             RobotPlatform p = open("ref-copter", port)) {
            run(p, command("takeoff", Map.of("altitude", 2.0), 4));
            vehicle.await("STATE armed=1", WAIT);
            run(p, command("move", Map.of("distance", 2.0, "speed", 1.0, "acceptance_radius", 0.3), 2));
            run(p, command("land", Map.of(), 6));
            List<String> commands = received(vehicle, "COMMAND_LONG");
            assertTrue(commands.stream().anyMatch(l -> l.contains("command=176 p1=1.0 p2=4.0")), "GUIDED is 4 on a copter: " + commands);
            assertEquals(2, commands.stream().filter(l -> l.contains("command=400 p1=1.0")).count(),
                    "the first arm went unanswered and was sent again: " + commands);
            assertTrue(commands.stream().anyMatch(l -> l.contains("command=22") && l.contains("p7=2.0")), "NAV_TAKEOFF to 2 m: " + commands);
            assertEquals(1, commands.stream().filter(l -> l.contains("command=22")).count(), "IN_PROGRESS held the take-off: not sent again");
            assertTrue(commands.stream().allMatch(l -> l.contains("target=1/1") && l.contains("from=255/190")), String.valueOf(commands));
            List<String> setpoints = received(vehicle, "SET_POSITION_TARGET_LOCAL_NED");
            assertTrue(setpoints.size() >= 10, "setpoints streamed while the move ran: " + setpoints.size());
            assertTrue(setpoints.stream().allMatch(l -> l.contains("frame=1 mask=2552")), "LOCAL_NED position and yaw: " + setpoints.get(0));
            // The stream's rate (the median gap: 10 Hz or more) and no pause a vehicle would take as the stream lost (PX4's
            // offboard loss is 0.5 s and more); not the largest gap against the rate, which a busy machine stretches.
            List<Double> gaps = gaps(setpoints).stream().sorted().toList();
            assertTrue(gaps.get(gaps.size() / 2) <= 0.1, "10 Hz or more: median gap " + gaps.get(gaps.size() / 2) + " s");
            assertTrue(gaps.get(gaps.size() - 1) < 0.5, "never paused long enough to look lost: largest gap " + gaps.get(gaps.size() - 1) + " s");
            List<String> heartbeats = received(vehicle, "HEARTBEAT");
            assertTrue(heartbeats.size() >= 3 && heartbeats.stream().allMatch(l -> l.contains("type=6 autopilot=8 from=255/190")),
                    "its own GCS HEARTBEAT: " + heartbeats);
            assertTrue(p.readRaw("below").get(5, TimeUnit.SECONDS) >= 0);
        }
    }

    @Test
    void aPx4CopterGetsItsTakeoffAltitudeAsAParameterAndOffboardAfterTheStream() throws Exception {
        int port = VehiclePython.freeUdpPort();
        try (VehiclePython vehicle = VehiclePython.start("reference-px4", "reference_vehicle.py", "--out", "127.0.0.1:" + port,
                "--type", "copter", "--autopilot", "px4");
             RobotPlatform p = open("ref-px4", port)) {
            run(p, command("takeoff", Map.of("altitude", 3.0), 4));
            assertTrue(received(vehicle, "PARAM_SET").stream().anyMatch(l -> l.contains("id=MIS_TAKEOFF_ALT value=3.0")),
                    String.valueOf(received(vehicle, "PARAM_SET")));
            assertTrue(received(vehicle, "COMMAND_LONG").stream().anyMatch(l -> l.contains("command=22 p1=nan")), "PX4 take-off params NaN");
            run(p, command("move", Map.of("distance", 2.0, "speed", 1.0, "acceptance_radius", 0.3), 2));
            List<String> modes = received(vehicle, "COMMAND_LONG").stream().filter(l -> l.contains("command=176")).toList();
            assertTrue(modes.stream().anyMatch(l -> l.contains("p2=6.0")), "OFFBOARD (main mode 6): " + modes);
            assertTrue(vehicle.transcript().stream().anyMatch(l -> l.startsWith("STATE armed=1 mode=393216")), "the vehicle went OFFBOARD");
        }
    }

    @Test
    void aBoatIsArmedAndGuidedIn15() throws Exception {
        int port = VehiclePython.freeUdpPort();
        try (VehiclePython vehicle = VehiclePython.start("reference-boat", "reference_vehicle.py", "--out", "127.0.0.1:" + port,
                "--type", "boat", "--autopilot", "ardupilot");
             RobotPlatform p = open("ref-boat", port)) {
            run(p, command("move", Map.of("distance", 3.0, "speed", 1.0, "acceptance_radius", 0.5), 3));
            List<String> commands = received(vehicle, "COMMAND_LONG");
            assertTrue(commands.stream().anyMatch(l -> l.contains("command=176 p1=1.0 p2=15.0")), "GUIDED is 15 on a boat: " + commands);
            assertTrue(commands.stream().anyMatch(l -> l.contains("command=400 p1=1.0")), "armed before it moves: " + commands);
        }
    }
}
