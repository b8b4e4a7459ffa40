package io.robomw.cli;

import io.robomw.config.description.DescriptionException;
import io.robomw.sim.Simulation;
import io.robomw.sim.emulator.Emulator;
import io.robomw.sim.emulator.aibo.AiboEmulator;
import io.robomw.sim.emulator.ev3.Ev3Emulator;
import io.robomw.sim.emulator.ft.intelligent.IntelligentInterfaceEmulator;
import io.robomw.sim.emulator.ft.txt.TxtEmulator;
import io.robomw.sim.emulator.nxt.NxtEmulator;
import picocli.CommandLine.Command;
import picocli.CommandLine.Model.CommandSpec;
import picocli.CommandLine.Option;
import picocli.CommandLine.Parameters;
import picocli.CommandLine.Spec;

import java.io.PrintWriter;
import java.nio.file.Path;
import java.util.Set;
import java.util.concurrent.Callable;
import java.util.concurrent.CountDownLatch;

/**
 * {@code mw emulate nxt --world W.yaml --robot R}: a virtual brick (or a virtual Aibo's URBI server)
 * for one robot of a simulated world. It prints the serial device (or TCP port) the real driver
 * connects to, runs the world in real time, and serves until interrupted (Ctrl-C).
 */
@Command(name = "emulate", description = "Run a virtual brick (or Aibo) bound to a robot in a simulated world; print its device path or port.")
final class EmulateCommand implements Callable<Integer> {

    @Parameters(index = "0", paramLabel = "BRICK", description = "the brick: nxt, ev3, ft-intelligent, ft-txt (TCP only), aibo (URBI, TCP only)", converter = BrickConverter.class)
    private Brick brick;

    /** Accepts the bricks' platform names (with dashes). */
    static final class BrickConverter implements picocli.CommandLine.ITypeConverter<Brick> {
        @Override
        public Brick convert(String value) {
            try {
                return Brick.valueOf(value.replace('-', '_'));
            } catch (IllegalArgumentException e) {
                throw new picocli.CommandLine.TypeConversionException("unknown brick '" + value + "'; emulated bricks: nxt, ev3, ft-intelligent, ft-txt, aibo");
            }
        }
    }

    @Option(names = "--world", required = true, paramLabel = "WORLD.yaml", description = "the world file")
    private Path world;

    @Option(names = "--robot", required = true, paramLabel = "NAME", description = "the robot in the world that the brick drives")
    private String robot;

    @Option(names = "--tcp", paramLabel = "PORT", description = "serve on TCP 127.0.0.1:PORT (0 = any) instead of a pseudo-terminal; "
            + "the TXT and the Aibo are TCP only (default 65000 and 54000)")
    private Integer tcpPort;

    @Option(names = "--speed", defaultValue = "1", description = "simulated seconds per second (default ${DEFAULT-VALUE})")
    private double speed;

    @Spec
    private CommandSpec spec;

    /** The bricks that can be emulated. */
    enum Brick {
        nxt,
        ev3,
        ft_intelligent,
        ft_txt,
        aibo
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
        Emulator emulator;
        try {
            emulator = bind(sim);
        } catch (IllegalArgumentException e) {
            sim.close();
            err.println(e.getMessage());
            return 2;
        }
        try (sim; emulator) {
            if (brick == Brick.ft_txt && tcpPort == null) {
                tcpPort = 65000;
            }
            if (brick == Brick.aibo && tcpPort == null) {
                tcpPort = 54000;
            }
            String where = tcpPort == null ? emulator.startOnPseudoTerminal() : "tcp://127.0.0.1:" + emulator.startOnTcp("127.0.0.1", tcpPort);
            out.println(where);
            out.flush();
            err.printf("%s emulator for robot '%s' of %s; connect the %s driver to %s; Ctrl-C stops it%n", brick, robot, world, brick, where);
            err.flush();
            sim.startRealTime(speed);
            Runtime.getRuntime().addShutdownHook(new Thread(stopped::countDown, "mw-emulate-shutdown"));
            stopped.await();
        }
        return 0;
    }

    private Emulator bind(Simulation sim) {
        return switch (brick) {
            case nxt -> NxtEmulator.bind(sim, robot);
            case ev3 -> Ev3Emulator.bind(sim, robot);
            case ft_intelligent -> IntelligentInterfaceEmulator.bind(sim, robot);
            case ft_txt -> TxtEmulator.bind(sim, robot);
            case aibo -> AiboEmulator.bind(sim, robot);
        };
    }
}
