package io.robomw.cli;

import io.robomw.config.description.DescriptionException;
import io.robomw.sim.Simulation;
import io.robomw.sim.emulator.BrickEmulator;
import io.robomw.sim.emulator.ev3.Ev3Emulator;
import io.robomw.sim.emulator.ft.intelligent.IntelligentInterfaceEmulator;
import io.robomw.sim.emulator.ft.txt.TxtEmulator;
import io.robomw.sim.emulator.LinkModel;
import io.robomw.sim.emulator.nxt.NxtEmulator;
import io.robomw.sim.emulator.rcx.RcxEmulator;
import picocli.CommandLine.Command;
import picocli.CommandLine.Model.CommandSpec;
import picocli.CommandLine.Option;
import picocli.CommandLine.Parameters;
import picocli.CommandLine.Spec;

import java.io.PrintWriter;
import java.nio.file.Path;
import java.time.Duration;
import java.util.Set;
import java.util.concurrent.Callable;
import java.util.concurrent.CountDownLatch;

/**
 * {@code mw emulate nxt --world W.yaml --robot R}: a virtual brick for one robot of a simulated
 * world. It prints the serial device (or TCP port) the real driver connects to, runs the world in
 * real time, and serves until interrupted (Ctrl-C).
 */
@Command(name = "emulate", description = "Run a virtual brick bound to a robot in a simulated world; print its device path.")
final class EmulateCommand implements Callable<Integer> {

    @Parameters(index = "0", paramLabel = "BRICK", description = "the brick: nxt, ev3, rcx, ft-intelligent, ft-txt (TCP only)", converter = BrickConverter.class)
    private Brick brick;

    /** Accepts the bricks' platform names (with dashes). */
    static final class BrickConverter implements picocli.CommandLine.ITypeConverter<Brick> {
        @Override
        public Brick convert(String value) {
            try {
                return Brick.valueOf(value.replace('-', '_'));
            } catch (IllegalArgumentException e) {
                throw new picocli.CommandLine.TypeConversionException("unknown brick '" + value + "'; emulated bricks: nxt, ev3, rcx, ft-intelligent, ft-txt");
            }
        }
    }

    @Option(names = "--world", required = true, paramLabel = "WORLD.yaml", description = "the world file")
    private Path world;

    @Option(names = "--robot", required = true, paramLabel = "NAME", description = "the robot in the world that the brick drives")
    private String robot;

    @Option(names = "--tcp", paramLabel = "PORT", description = "serve on TCP 127.0.0.1:PORT (0 = any) instead of a pseudo-terminal; "
            + "the TXT is TCP only (default 65000) and also listens on PORT + 2, its I²C channel")
    private Integer tcpPort;

    @Option(names = "--speed", defaultValue = "1", description = "simulated seconds per second (default ${DEFAULT-VALUE})")
    private double speed;

    @Option(names = "--latency", paramLabel = "MS", description = "delay of every telegram on the link, each way, milliseconds "
            + "(default: the brick's usual link: 15 for the NXT and EV3 over Bluetooth, 0 for the serial bricks, 1 for the TXT)")
    private Integer latencyMillis;

    @Option(names = "--baud", paramLabel = "N", description = "the link's byte rate in baud, 0 for none (default: the brick's usual link: "
            + "115200 for Bluetooth, 9600 for the Intelligent Interface, 2400 for the RCX's IR tower)")
    private Integer baud;

    @Spec
    private CommandSpec spec;

    /** The bricks that can be emulated. */
    enum Brick {
        nxt,
        ev3,
        rcx,
        ft_intelligent,
        ft_txt
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
        CountDownLatch stopped = new CountDownLatch(1);
        try (sim; BrickEmulator emulator = bind(sim)) {
            if (brick == Brick.ft_txt && tcpPort == null) {
                tcpPort = 65000;
            }
            LinkModel link = emulator.linkModel();
            if (latencyMillis != null) {
                if (latencyMillis < 0) {
                    err.println("--latency must be 0 or more milliseconds, got " + latencyMillis);
                    return 2;
                }
                link = link.withLatency(Duration.ofMillis(latencyMillis));
            }
            if (baud != null) {
                if (baud < 0) {
                    err.println("--baud must be 0 (no byte-rate limit) or more, got " + baud);
                    return 2;
                }
                link = link.withBaud(baud);
            }
            emulator.linkModel(link);
            String where;
            if (tcpPort == null) {
                where = emulator.startOnPseudoTerminal();
            } else if (emulator instanceof TxtEmulator txt) {
                // A real TXT also accepts its I²C channel on the command port + 2 when a client goes online.
                where = "tcp://127.0.0.1:" + txt.startOnTcpPair("127.0.0.1", tcpPort);
            } else {
                where = "tcp://127.0.0.1:" + emulator.startOnTcp("127.0.0.1", tcpPort);
            }
            out.println(where);
            out.flush();
            err.printf("%s emulator for robot '%s' of %s, link: %s; connect the %s driver to %s; Ctrl-C stops it%n",
                    brick, robot, world, link, brick, where);
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

    private BrickEmulator bind(Simulation sim) {
        return switch (brick) {
            case nxt -> NxtEmulator.bind(sim, robot);
            case ev3 -> Ev3Emulator.bind(sim, robot);
            case rcx -> RcxEmulator.bind(sim, robot);
            case ft_intelligent -> IntelligentInterfaceEmulator.bind(sim, robot);
            case ft_txt -> TxtEmulator.bind(sim, robot);
        };
    }
}
