package io.robomw.cli;

import io.robomw.api.spi.FailurePolicy;
import io.robomw.config.description.DescriptionException;
import io.robomw.config.description.VehicleDrive;
import io.robomw.platform.mavlink.link.MavlinkEndpoint;
import io.robomw.platform.mavlink.wire.SigningKey;
import io.robomw.sim.Simulation;
import io.robomw.sim.emulator.BrickEmulator;
import io.robomw.sim.emulator.Emulator;
import io.robomw.sim.emulator.LinkModel;
import io.robomw.sim.emulator.aibo.AiboEmulator;
import io.robomw.sim.emulator.ev3.Ev3Emulator;
import io.robomw.sim.emulator.ft.intelligent.IntelligentInterfaceEmulator;
import io.robomw.sim.emulator.ft.txt.TxtEmulator;
import io.robomw.sim.emulator.mavlink.MavlinkEmulator;
import io.robomw.sim.emulator.nxt.NxtEmulator;
import io.robomw.sim.emulator.rcx.RcxEmulator;
import picocli.CommandLine.Command;
import picocli.CommandLine.Model.CommandSpec;
import picocli.CommandLine.Option;
import picocli.CommandLine.Parameters;
import picocli.CommandLine.Spec;

import java.io.PrintWriter;
import java.net.InetSocketAddress;
import java.nio.file.Path;
import java.time.Duration;
import java.util.Locale;
import java.util.Map;
import java.util.Optional;
import java.util.Set;
import java.util.concurrent.Callable;
import java.util.concurrent.CountDownLatch;

/**
 * {@code mw emulate nxt --world W.yaml --robot R}: a virtual brick (or a virtual Aibo's URBI server)
 * for one robot of a simulated world. It prints the serial device (or TCP port) the real driver
 * connects to, runs the world in real time, and serves until interrupted (Ctrl-C).
 */
@Command(mixinStandardHelpOptions = true, name = "emulate", description = "Run a virtual brick (or Aibo, or MAVLink vehicle) bound to a robot in a simulated world; print its device path, port or address.")
final class EmulateCommand implements Callable<Integer> {

    @Parameters(index = "0", paramLabel = "BRICK", description = "the brick, by its robot files' platform name: nxt, ev3, rcx, ft-intelligent, ft-txt (TCP only), aibo (URBI, TCP only), mavlink (a drone, boat or rover over UDP)",
            converter = BrickConverter.class)
    private Brick brick;

    /** Accepts the bricks' platform names, exactly as robot files spell them. */
    static final class BrickConverter implements picocli.CommandLine.ITypeConverter<Brick> {
        @Override
        public Brick convert(String value) {
            for (Brick b : Brick.values()) {
                if (b.platform.equals(value)) {
                    return b;
                }
            }
            String near = value.replace('_', '-').toLowerCase(Locale.ROOT);
            String hint = java.util.Arrays.stream(Brick.values()).anyMatch(b -> b.platform.equals(near)) ? "did you mean '" + near + "'? " : "";
            throw new picocli.CommandLine.TypeConversionException("unknown brick '" + value + "'; " + hint + "emulated bricks: "
                    + String.join(", ", java.util.Arrays.stream(Brick.values()).map(b -> b.platform).toList()));
        }
    }

    @Option(names = "--world", required = true, paramLabel = "WORLD.yaml", description = "the world file")
    private Path world;

    @Option(names = "--robot", required = true, paramLabel = "NAME", description = "the robot in the world that the brick drives")
    private String robot;

    @Option(names = "--tcp", paramLabel = "PORT", description = "serve on TCP 127.0.0.1:PORT (0 = any) instead of a pseudo-terminal; "
            + "the TXT is TCP only (default 65000)")
    private Integer tcpPort;

    @Option(names = "--speed", defaultValue = "1", description = "simulated seconds per second (default ${DEFAULT-VALUE})")
    private double speed;

    @Option(names = "--write-robot", paramLabel = "FILE.yaml", description = "write a copy of the robot's file whose connection points at this emulator,"
            + " ready for Robots.open, mw host --robot or mw robot")
    private Path writeRobot;

    /** The longest link latency taken: a bare number is seconds, so a longer one is most likely milliseconds meant. */
    static final Duration MAX_LATENCY = Duration.ofSeconds(10);

    @Option(names = "--latency", paramLabel = "DURATION", description = "delay of every telegram on the link, each way, a duration as every time option"
            + " takes it (15ms; a bare number is seconds; at most 10s) (default: the brick's usual link: 15ms for the NXT and EV3 over Bluetooth,"
            + " 0 for the serial bricks, 1ms for the TXT)")
    private Duration latency;

    @Option(names = "--baud", paramLabel = "N", description = "the link's byte rate in baud, 0 for none (default: the brick's usual link: "
            + "115200 for Bluetooth, 9600 for the Intelligent Interface, 2400 for the RCX's IR tower)")
    private Integer baud;

    @Option(names = "--autopilot", paramLabel = "ardupilot|px4", description = "mavlink: the autopilot to behave as (default: the robot file's drive.autopilot)")
    private String autopilot;

    @Option(names = "--gcs", paramLabel = "udp://HOST:PORT", description = "mavlink: send to a ground station at this address, as ArduPilot SITL's --out (and hear its answers)")
    private String gcs;

    @Option(names = "--udp", paramLabel = "PORT", description = "mavlink: listen on UDP 127.0.0.1:PORT (0 = any) and answer whoever sends to it")
    private Integer udpPort;

    @Option(names = "--signing-key-file", paramLabel = "FILE", description = "mavlink: a file holding the signing passphrase (its SHA-256 is the key, as MAVProxy's"
            + " 'signing setup'; default: the " + Secrets.MAVLINK_SIGNING_ENV + " environment variable, else unsigned): everything is signed,"
            + " and unsigned commands are ignored")
    private Path signingKeyFile;

    /** A passphrase given as an option's value would show in {@code ps}: refused, naming the file option. */
    @Option(names = "--signing-key", hidden = true, converter = Secrets.RefusedSigningKey.class)
    private String refusedSigningKey;

    @Spec
    private CommandSpec spec;

    /** The bricks that can be emulated, by their platform names. */
    enum Brick {
        NXT("nxt"),
        EV3("ev3"),
        RCX("rcx"),
        FT_INTELLIGENT("ft-intelligent"),
        FT_TXT("ft-txt"),
        AIBO("aibo"),
        MAVLINK("mavlink");

        /** The {@code platform:} value of its robot files. */
        final String platform;

        Brick(String platform) {
            this.platform = platform;
        }

        @Override
        public String toString() {
            return platform;
        }
    }

    @Override
    public Integer call() throws Exception {
        PrintWriter out = spec.commandLine().getOut();
        PrintWriter err = spec.commandLine().getErr();
        Simulation sim;
        try {
            sim = Simulation.load(world, Set.of(robot));
        } catch (DescriptionException e) {
            err.println(e.getMessage());
            return 2;
        } catch (IllegalArgumentException e) {
            err.println(e.getMessage());
            return 2;
        }
        // The robot file's own platform: inside the world every robot is simulated.
        Path robotFile = sim.world().description().robots().stream().filter(r -> r.name().equals(robot)).findFirst().orElseThrow().description();
        String platform = writeRobot == null ? brick.platform : new io.robomw.config.description.RobotDescriptionLoader().load(robotFile).platform();
        if (writeRobot != null && !platform.equals(brick.platform)) {
            sim.close();
            err.println("mw emulate: robot '" + robot + "' of " + world + " is a " + platform + " robot (its file says platform: " + platform
                    + "), so a " + brick + " emulator cannot write a robot file for it; emulate " + platform + ", or leave out --write-robot");
            return 2;
        }
        if (brick == Brick.MAVLINK) {
            return emulateVehicle(sim, out, err);
        }
        if (autopilot != null || gcs != null || udpPort != null || signingKeyFile != null) {
            sim.close();
            err.println("--autopilot, --gcs, --udp and --signing-key-file are for the mavlink emulator; the " + brick + " emulator does not take them");
            return 2;
        }
        CountDownLatch stopped = new CountDownLatch(1);
        Emulator emulator;
        try {
            emulator = bind(sim);
        } catch (IllegalArgumentException e) {
            sim.close();
            err.println(e.getMessage());
            return 2;
        }
        try (sim; emulator) {
            if (brick == Brick.FT_TXT && tcpPort == null) {
                tcpPort = 65000;
            }
            if (brick == Brick.AIBO && tcpPort == null) {
                tcpPort = 54000;
            }
            String linkText = "";
            if (emulator instanceof BrickEmulator b) {
                LinkModel link = b.linkModel();
                if (latency != null) {
                    if (latency.compareTo(MAX_LATENCY) > 0) {
                        // A bare number is seconds, as for every time option; --latency 40 once meant 40 ms.
                        err.println("--latency " + Durations.format(latency) + " is longer than any link's (at most " + Durations.format(MAX_LATENCY)
                                + "); give a unit: --latency " + latency.toSeconds() + "ms");
                        return 2;
                    }
                    link = link.withLatency(latency);
                }
                if (baud != null) {
                    if (baud < 0) {
                        err.println("--baud must be 0 (no byte-rate limit) or more, got " + baud);
                        return 2;
                    }
                    link = link.withBaud(baud);
                }
                b.linkModel(link);
                linkText = ", link: " + link;
            } else if (latency != null || baud != null) {
                err.println("--latency and --baud model a brick's link; the " + brick + " emulator serves on TCP as it is");
                return 2;
            }
            String where;
            if (tcpPort == null) {
                where = emulator.startOnPseudoTerminal();
            } else if (emulator instanceof TxtEmulator txt) {
                // A real TXT also accepts its I²C channel on the command port + 2 when a client goes online.
                tcpPort = txt.startOnTcpPair("127.0.0.1", tcpPort);
                where = "tcp://127.0.0.1:" + tcpPort;
            } else {
                tcpPort = emulator.startOnTcp("127.0.0.1", tcpPort);
                where = "tcp://127.0.0.1:" + tcpPort;
            }
            if (writeRobot != null) {
                // Written before the device is printed: whoever waits for that line finds the file.
                Path source = robotFile;
                Map<String, String> connection = new java.util.LinkedHashMap<>();
                if (tcpPort != null) {
                    connection.put("host", "127.0.0.1");
                }
                connection.put("port", tcpPort == null ? where : String.valueOf(tcpPort));
                ReadyRobotFile.write(source, writeRobot, connection, "mw emulate " + brick + " --robot " + robot + " --world " + world);
            }
            out.println(where);
            if (writeRobot != null) {
                out.println("wrote " + writeRobot + ": robot '" + robot + "' with its connection at this emulator");
            }
            out.flush();
            err.printf("%s emulator for robot '%s' of %s%s; connect the %s driver to %s; Ctrl-C stops it%n", brick, robot, world, linkText, brick, where);
            err.flush();
            sim.startRealTime(speed);
            Thread hook = new Thread(stopped::countDown, "mw-emulate-shutdown");
            Runtime.getRuntime().addShutdownHook(hook);
            try {
                stopped.await();
            } finally {
                removeHook(hook);
            }
        }
        return 0;
    }

    /** Removes the shutdown hook when the command ends otherwise (interrupted); not possible while the JVM shuts down. */
    private static void removeHook(Thread hook) {
        try {
            Runtime.getRuntime().removeShutdownHook(hook);
        } catch (IllegalStateException e) {
            // the JVM is shutting down: the hook is what ended the wait
        }
    }

    private Emulator bind(Simulation sim) {
        return switch (brick) {
            case NXT -> NxtEmulator.bind(sim, robot);
            case EV3 -> Ev3Emulator.bind(sim, robot);
            case RCX -> RcxEmulator.bind(sim, robot);
            case FT_INTELLIGENT -> IntelligentInterfaceEmulator.bind(sim, robot);
            case FT_TXT -> TxtEmulator.bind(sim, robot);
            case AIBO -> AiboEmulator.bind(sim, robot);
            case MAVLINK -> throw new IllegalStateException("the mavlink emulator is bound by emulateVehicle");
        };
    }

    /**
     * {@code mw emulate mavlink}: a MAVLink vehicle (ArduPilot or PX4) for a vehicle of the world, on
     * UDP: {@code --udp PORT} answers whoever sends there; {@code --gcs udp://HOST:PORT} sends to a
     * ground station (both may be given; without either it sends to udp://127.0.0.1:14550, where ground stations listen,
     * as ArduPilot's SITL does by default).
     * Prints {@code udp://ADDRESS} lines, the world runs in real time, Ctrl-C stops it.
     */
    private Integer emulateVehicle(Simulation sim, PrintWriter out, PrintWriter err) throws Exception {
        Optional<VehicleDrive.Autopilot> dialect = Optional.empty();
        if (autopilot != null) {
            try {
                dialect = Optional.of(VehicleDrive.Autopilot.valueOf(autopilot.toUpperCase(Locale.ROOT)));
            } catch (IllegalArgumentException e) {
                sim.close();
                err.println("--autopilot must be ardupilot or px4, got '" + autopilot + "'");
                return 2;
            }
        }
        if (latency != null || baud != null || tcpPort != null || writeRobot != null) {
            sim.close();
            err.println("--latency, --baud, --tcp and --write-robot are for bricks; the mavlink emulator serves UDP (--udp, --gcs)");
            return 2;
        }
        SigningKey key = null;
        try {
            key = Secrets.read(signingKeyFile, "--signing-key-file", Secrets.MAVLINK_SIGNING_ENV)
                    .map(SigningKey::fromPassphrase).orElse(null);
        } catch (IllegalStateException e) {
            sim.close();
            err.println(e.getMessage());
            return 2;
        }
        MavlinkEndpoint target = null;
        if (gcs == null && udpPort == null) {
            gcs = "udp://127.0.0.1:14550";
        }
        if (gcs != null) {
            try {
                target = MavlinkEndpoint.parse(gcs);
            } catch (IllegalArgumentException e) {
                sim.close();
                err.println("--gcs: " + e.getMessage());
                return 2;
            }
            if (target.kind() != MavlinkEndpoint.Kind.UDP_SEND) {
                sim.close();
                err.println("--gcs takes the ground station's address, udp://HOST:PORT, got '" + gcs + "'");
                return 2;
            }
        }
        MavlinkEmulator emulator;
        try {
            emulator = MavlinkEmulator.bind(sim, robot, dialect, FailurePolicy.logging());
        } catch (IllegalArgumentException e) {
            sim.close();
            err.println(e.getMessage());
            return 2;
        }
        CountDownLatch stopped = new CountDownLatch(1);
        try (sim; emulator) {
            if (key != null) {
                emulator.signing(key);
            }
            if (udpPort != null) {
                InetSocketAddress at = emulator.listen(new InetSocketAddress("127.0.0.1", udpPort));
                out.println("udp://127.0.0.1:" + at.getPort());
            }
            if (target != null) {
                InetSocketAddress from = emulator.sendTo(new InetSocketAddress(target.host(), target.port()));
                out.println("sending to udp://" + target.host() + ":" + target.port() + " from udp://" + from.getAddress().getHostAddress() + ":" + from.getPort());
            }
            out.flush();
            err.printf("mavlink emulator (%s) for robot '%s' of %s%s; Ctrl-C stops it%n", emulator.dialect(), robot, world,
                    key != null ? ", signing" : "");
            err.flush();
            sim.startRealTime(speed);
            Thread hook = new Thread(stopped::countDown, "mw-emulate-shutdown");
            Runtime.getRuntime().addShutdownHook(hook);
            try {
                stopped.await();
            } finally {
                removeHook(hook);
            }
        }
        return 0;
    }
}
