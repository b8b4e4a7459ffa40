package io.robomw.examples;

import io.robomw.api.Pose;
import io.robomw.api.Robot;
import io.robomw.api.Robots;
import io.robomw.sim.Simulation;
import io.robomw.sim.emulator.Emulator;
import io.robomw.sim.emulator.aibo.AiboEmulator;
import io.robomw.sim.emulator.ev3.Ev3Emulator;
import io.robomw.sim.emulator.ft.intelligent.IntelligentInterfaceEmulator;
import io.robomw.sim.emulator.ft.txt.TxtEmulator;
import io.robomw.sim.emulator.nxt.NxtEmulator;
import io.robomw.api.spi.FailurePolicy;
import io.robomw.sim.emulator.mavlink.MavlinkEmulator;

import java.net.InetAddress;
import java.net.InetSocketAddress;
import java.util.Optional;
import org.junit.jupiter.api.io.TempDir;
import org.junit.jupiter.api.parallel.Execution;
import org.junit.jupiter.api.parallel.ExecutionMode;
import org.junit.jupiter.api.parallel.ResourceAccessMode;
import org.junit.jupiter.api.parallel.ResourceLock;
import org.junit.jupiter.params.ParameterizedTest;
import org.junit.jupiter.params.provider.ValueSource;

import java.nio.file.Files;
import java.nio.file.Path;
import java.util.Set;
import java.util.function.BiFunction;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * One application class, {@link SquareSurvey}, on every platform with a front range sensor, with
 * only the robot's YAML file changed: the real drivers over real pseudo-terminals (or TCP) to brick
 * emulators, the Sony Aibo (the example robot file) walking on four legs through its URBI emulator
 * and in the simulator, and the pure simulated robot. The range finders differ (ultrasonic on the
 * LEGO bricks and the TXT, infra-red on the Intelligent Interface and the Aibo, a laser reporting
 * millimetres and a generic {@code range} sensor in the simulator); the program reads each as
 * {@code RANGE}. Each robot starts 0.7 m from the east wall of its world, facing it, so its last
 * corner sample sees that wall.
 */
@Execution(ExecutionMode.CONCURRENT)
class SameProgramOnEveryPlatformTest {

    /** The same two-wheeled geometry everywhere; only platform, connection, ports and encoders differ. */
    private static final String GEOMETRY = """
              wheel_diameter: 0.056
              track_width: 0.112
              max_speed: 0.30
            """;

    @TempDir
    Path dir;

    private static String robotFile(String platform, String connection) {
        return switch (platform) {
            case "nxt" -> """
                    name: r
                    platform: nxt
                    connection: { %s }
                    drive:
                    %s  left: { port: B }
                      right: { port: C }
                    sensors:
                      - { name: sonar, type: sonar, position: front, port: S4, conversion: { scale: 0.01 } }
                    """.formatted(connection, GEOMETRY);
            case "ft-intelligent" -> """
                    name: r
                    platform: ft-intelligent
                    connection: { %s }
                    drive:
                    %s  encoder_ticks_per_revolution: 16
                      left: { port: M1, counter: E1 }
                      right: { port: M2, counter: E2 }
                    sensors:
                      - name: range
                        type: infrared
                        position: front
                        port: EX
                        conversion: { table: [[80, 0.80], [150, 0.40], [300, 0.20], [600, 0.10], [900, 0.06]] }
                    """.formatted(connection, GEOMETRY);
            case "ev3" -> """
                    name: r
                    platform: ev3
                    connection: { %s }
                    drive:
                    %s  left: { port: B }
                      right: { port: C }
                    sensors:
                      - { name: sonar, type: sonar, position: front, port: S4, conversion: { scale: 0.01 } }
                    """.formatted(connection, GEOMETRY);
            case "ft-txt" -> """
                    name: r
                    platform: ft-txt
                    connection: { %s }
                    drive:
                    %s  encoder_ticks_per_revolution: 63
                      left: { port: M1, counter: C1 }
                      right: { port: M2, counter: C2 }
                    sensors:
                      - { name: sonar, type: sonar, position: front, port: I2, conversion: { scale: 0.01 } }
                    """.formatted(connection, GEOMETRY);
            case "aibo", "aibo-sim" -> aibo(connection);
            case "sim" -> """
                    name: r
                    platform: sim
                    drive:
                    %s  left: { port: B }
                      right: { port: C }
                    sensors:
                      - { name: lidar, type: laser, position: front, port: L1, conversion: { scale: 0.001 }, options: { max_range: 4.0 } }
                    """.formatted(GEOMETRY);
            case "sim-range" -> """
                    name: r
                    platform: sim
                    drive:
                    %s  left: { port: B }
                      right: { port: C }
                    sensors:
                      - { name: tof, type: range, position: front, port: R1, options: { max_range: 2.0 } }
                    """.formatted(GEOMETRY);
            case "copter", "copter-px4", "copter-sim", "boat", "boat-sim" -> vehicle(platform, connection);
            default -> throw new IllegalArgumentException(platform);
        };
    }

    /** A multirotor or a boat of the same size, with a forward laser, as MAVLink drives it or the simulator flies it. */
    private static String vehicle(String platform, String connection) {
        boolean air = platform.startsWith("copter");
        return """
                name: r
                platform: %s
                connection: { %s }
                drive: { type: vehicle, medium: %s, autopilot: %s, max_speed: 1.0, %s max_turn_rate: 1.2, acceptance_radius: 0.03 }
                body: { length: 0.2, width: 0.2, mass: %s }
                sensors:
                  - { name: lidar, type: laser, position: front, port: "distance:forward", options: { max_range: 4.0 } }
                """.formatted(platform.endsWith("-sim") ? "sim" : "mavlink", connection.startsWith("link") ? connection : "link: \"udpout://127.0.0.1:9\"",
                air ? "air" : "water", platform.equals("copter-px4") ? "px4" : "ardupilot", air ? "max_climb_rate: 1.0," : "", air ? 1.2 : 3);
    }

    /** The example Aibo robot file with another connection block. */
    private static String aibo(String connection) {
        try {
            String file = Files.readString(Path.of("robots/aibo.yaml"));
            return file.substring(0, file.indexOf("connection:\n")) + "connection: { " + connection
                    + ", startup: \"motoron; robot.watchdogInterval = 0.5\" }\n" + file.substring(file.indexOf("cycle_hz:"));
        } catch (java.io.IOException e) {
            throw new java.io.UncheckedIOException(e);
        }
    }

    /** Held shared by the platforms that drive side by side, alone by those behind serial links (see below). */
    private static final String SIDE_BY_SIDE = "SameProgramOnEveryPlatformTest: platforms side by side";

    /**
     * The platforms run side by side (the class is concurrent: each has its own world, emulator, link and files), the
     * longest first: the vehicles' real-time flights. Their links are UDP and TCP.
     */
    @ParameterizedTest
    @ValueSource(strings = {"copter", "copter-px4", "boat", "ft-txt", "aibo", "aibo-sim", "sim", "sim-range",
            "copter-sim", "boat-sim"})
    @ResourceLock(value = SIDE_BY_SIDE, mode = ResourceAccessMode.READ)
    void shouldDriveTheSquareAndSeeTheWallOnEveryPlatform(String platform) throws Exception {
        driveTheSquareAndSeeTheWall(platform);
    }

    /**
     * The bricks behind serial links (pseudo-terminals) one at a time and with no other platform beside them: their
     * drivers give up on an answer after 0.5 s (the LEGO bricks) or 1 s (the Intelligent Interface), and side by side
     * with the others, beside two busy threads on a machine busy already, one of them lost its link in three runs of
     * four; one at a time, they held there.
     */
    @ParameterizedTest
    @ValueSource(strings = {"ft-intelligent", "nxt", "ev3"})
    @ResourceLock(value = SIDE_BY_SIDE, mode = ResourceAccessMode.READ_WRITE)
    @Execution(ExecutionMode.SAME_THREAD)
    void shouldDriveTheSquareAndSeeTheWallOverSerialLinks(String platform) throws Exception {
        driveTheSquareAndSeeTheWall(platform);
    }

    private void driveTheSquareAndSeeTheWall(String platform) throws Exception {
        Files.writeString(dir.resolve("body.yaml"), robotFile(platform, "port: /dev/unused"));
        Files.writeString(dir.resolve("world.yaml"), """
                name: square
                arena: { width: 3, height: 3 }
                water: [ { x: 0, y: 0, width: 3, height: 3 } ]
                robots:
                  - { robot: body.yaml, name: r, x: 2.2, y: 1.0, heading: 0 }
                """);
        boolean flies = platform.startsWith("copter");
        boolean emulated = !platform.startsWith("sim") && !platform.endsWith("-sim");
        try (Simulation sim = Simulation.load(dir.resolve("world.yaml"), emulated ? Set.of("r") : Set.of())) {
            Pose start = sim.world().robot("r").pose();
            SquareSurvey.Report report;
            if (emulated) {
                BiFunction<Simulation, String, Emulator> bind = switch (platform) {
                    case "copter", "copter-px4", "boat" -> (world, name) -> MavlinkEmulator.bind(world, name, Optional.empty(), FailurePolicy.logging());
                    case "nxt" -> NxtEmulator::bind;
                    case "ev3" -> Ev3Emulator::bind;
                    case "ft-intelligent" -> IntelligentInterfaceEmulator::bind;
                    case "aibo" -> AiboEmulator::bind;
                    default -> TxtEmulator::bind;
                };
                try (Emulator emulator = bind.apply(sim, "r")) {
                    String connection = emulator instanceof MavlinkEmulator vehicle
                            ? "link: \"udpout://127.0.0.1:" + vehicle.listen(new InetSocketAddress(InetAddress.getLoopbackAddress(), 0)).getPort() + "\""
                            : platform.equals("ft-txt") || platform.equals("aibo")
                            ? "host: 127.0.0.1, port: " + emulator.startOnTcp("127.0.0.1", 0)
                            : "port: " + emulator.startOnPseudoTerminal();
                    // The Intelligent Interface stops nothing by itself: its precision depends on its
                    // link's latency in wall-clock time, so its world runs in real time.
                    sim.startRealTime(platform.equals("ft-intelligent") ? 1 : 4);
                    Files.writeString(dir.resolve("driver.yaml"), robotFile(platform, connection));
                    try (Robot robot = Robots.open(dir.resolve("driver.yaml"))) {
                        if (flies) {
                            robot.takeOff(2.0);
                        }
                        report = new SquareSurvey(0.3, 0.15).run(robot);
                        if (flies) {
                            robot.land();
                        }
                    }
                }
            } else {
                Robot robot = sim.robot("r");
                SquareSurvey.Report[] out = new SquareSurvey.Report[1];
                sim.run(java.time.Duration.ofMinutes(2), () -> {
                    if (flies) {
                        robot.takeOff(2.0);
                    }
                    out[0] = new SquareSurvey(0.3, 0.15).run(robot);
                    if (flies) {
                        robot.land();
                    }
                });
                report = out[0];
            }
            // The Intelligent Interface counts 16 impulse-wheel transitions per motor turn: 11 mm of
            // travel per tick, and a quarter turn is right only to about a tick per wheel (11° of
            // heading), which four legs add up. Its own precision (move ±2 cm, turn ±5°) is asserted
            // in IntelligentInterfaceEmulatorTest; here it must show the same program runs.
            //
            // The Aibo walks on a gait that loses 2 % of every motion and varies 3 % step by step
            // (aibo.yaml): each quarter turn comes 1.8° short and each side 6 mm, which leaves it
            // 27 mm from its start; the jitter adds about 19 mm (σ: 4 mm along each side, 1.35° per
            // turn carried across the sides after it). Three σ over the systematic error: 0.09 m.
            // A vehicle reaches each corner within its acceptance radius (0.03 m) and its autopilot's
            // turn within a degree or two: four corners and turns add up to a few centimetres.
            boolean aibo = platform.startsWith("aibo");
            boolean vehicle = platform.startsWith("copter") || platform.startsWith("boat");
            double tolerance = platform.equals("ft-intelligent") ? 0.10 : aibo ? 0.09 : vehicle ? 0.10 : 0.03;
            assertTrue(sim.world().robot("r").pose().distanceTo(start) < tolerance,
                    platform + ": back at the start within " + tolerance + " m, but " + sim.world().robot("r").pose().distanceTo(start));
            assertEquals(4, report.ranges().size());
            double rangeTolerance = platform.equals("ft-intelligent") ? 0.10 : 0.05;
            // The bricks' range sensors sit 0.10 m ahead of the centre; the Aibo's head sensor 0.15 m.
            double sensorAhead = aibo ? 0.15 : 0.10;
            assertEquals(3.0 - (2.2 + sensorAhead), report.ranges().get(3), rangeTolerance, platform + ": the last corner faces the east wall again");
        }
    }
}
