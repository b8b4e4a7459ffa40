package io.robomw.cli;

import io.robomw.api.Pose;
import io.robomw.api.Robot;
import io.robomw.api.RobotException;
import io.robomw.config.description.DescriptionException;
import io.robomw.sim.SimRobot;
import io.robomw.sim.SimWorld;
import io.robomw.sim.Programs;
import io.robomw.sim.Simulation;
import io.robomw.sim.programs.SquareProgram;
import io.robomw.sim.programs.WanderController;
import io.robomw.sim.render.PngRenderer;
import io.robomw.sim.render.RealTimeControl;
import io.robomw.sim.render.RenderOptions;
import io.robomw.sim.render.SimViewer;
import picocli.CommandLine;
import picocli.CommandLine.ArgGroup;
import picocli.CommandLine.Command;
import picocli.CommandLine.Model.CommandSpec;
import picocli.CommandLine.Option;
import picocli.CommandLine.Parameters;
import picocli.CommandLine.Spec;

import java.awt.GraphicsEnvironment;
import java.io.IOException;
import java.io.PrintWriter;
import java.nio.file.Path;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.Locale;
import java.util.concurrent.Callable;
import java.util.concurrent.CountDownLatch;

/**
 * {@code mw sim WORLD.yaml}: runs a simulated world, optionally with a small built-in program on
 * every robot, shows it in a window or draws it into a PNG, and prints where each robot ended.
 *
 * <p>Three ways to run: as fast as possible (the default; repeatable bit for bit), in real time
 * ({@code --realtime}), or in the viewer window ({@code --view}, real time with pause and speed
 * controls, until the window closes). Exit codes: {@value #OK} ok, {@value #INVALID} an invalid
 * world or robot file (or a usage error, or no display for {@code --view}), {@value #FAILED} any
 * other failure (a program failed or ran over {@code --duration}, a file could not be written).
 */
@Command(name = "sim", sortOptions = false, mixinStandardHelpOptions = true,
        description = {"Run a simulated world: its robots (from their own YAML files) in an arena with rigid-body physics (dyn4j, or the swarm engine when the world file says physics: { engine: swarm }).",
                "Prints each robot's final pose and distance driven; --png draws the world and the robots' paths."})
final class SimCommand implements Callable<Integer> {

    static final int OK = 0;
    static final int FAILED = 1;
    static final int INVALID = 2;

    /** The square program's speed, m/s, unless a robot's max_speed is lower. */
    private static final double SQUARE_SPEED = 0.2;
    /** Share of a robot's max_speed the square program uses when 0.2 m/s is too fast for it. */
    private static final double SQUARE_SPEED_SHARE = 0.6;
    /** The wander controller's rate, ticks per simulated second. */
    private static final double WANDER_HZ = 10;
    /** Robots listed in the summary; the rest are counted. */
    private static final int SUMMARY_ROWS = 50;

    /** The built-in programs. */
    enum Program {
        /** A square on every robot, in parallel: {@link SquareProgram}. */
        SQUARE,
        /** Reactive wandering on every robot: {@link WanderController}. */
        WANDER,
        /** Nothing: the world runs, robots stand still. */
        NONE
    }

    /** {@code --realtime} or {@code --fast}; at most one. */
    static final class Pace {
        @Option(names = "--realtime", required = true, description = "run in real time (see --speed)")
        boolean realTime;

        @Option(names = "--fast", required = true, description = "run as fast as possible, repeatably (the default)")
        boolean fast;
    }

    @Parameters(index = "0", paramLabel = "WORLD.yaml", description = "the world file (docs/simulation.md)")
    private Path worldFile;

    @Option(names = "--program", paramLabel = "square|wander|none", defaultValue = "none", converter = ProgramConverter.class,
            description = "built-in program run on every robot (default: ${DEFAULT-VALUE})")
    private Program program;

    @Option(names = "--side", paramLabel = "METRES", defaultValue = "0.5", description = "side of the square program's square (default: ${DEFAULT-VALUE})")
    private double side;

    @Option(names = "--duration", paramLabel = "TIME", defaultValue = "20s",
            description = "simulated time to run: 20, 90s, 2m... (default: ${DEFAULT-VALUE}); --view runs until its window closes")
    private Duration durationOption;

    /** {@link #durationOption} in seconds. */
    private double duration;

    @ArgGroup(exclusive = true, multiplicity = "0..1")
    private Pace pace;

    @Option(names = "--speed", paramLabel = "FACTOR", defaultValue = "1",
            description = "simulated seconds per wall-clock second for --realtime and --view, 1/16 to 64 (default: ${DEFAULT-VALUE})")
    private double speed;

    @Option(names = "--view", description = "show the world in a window, running in real time (needs a display)")
    private boolean view;

    @Option(names = "--png", paramLabel = "FILE", description = "draw the world and the robots' paths into this PNG at the end")
    private Path png;

    @Option(names = "--width", paramLabel = "PX", defaultValue = "1000", description = "width of the PNG (default: ${DEFAULT-VALUE})")
    private int width;

    @Option(names = "--rays", description = "draw range sensors' rays to their latest readings")
    private boolean rays;

    @Option(names = "--console", description = "show the world live in a web page (prints its address); runs in real time unless --fast, and keeps the page up after the run until Ctrl-C")
    private boolean console;

    @Option(names = "--console-port", paramLabel = "PORT", defaultValue = "8080", description = "the page's port (default: ${DEFAULT-VALUE}; 0 picks a free one)")
    private int consolePort;

    @Option(names = "--record", paramLabel = "FILE.mcap", description = "record the run (poses, sensors, the programs' commands) into an MCAP file that Foxglove opens")
    private Path record;

    @CommandLine.Mixin
    private FoxgloveOption foxglove;

    @CommandLine.Mixin
    private RosBridgeOption rosbridge;

    @Spec
    private CommandSpec spec;

    /** The page and recording of this run, if asked for. */
    private io.robomw.console.Console watching;
    /** Counted down by Ctrl-C (or SIGTERM), whose hook then finishes the page and the recording. */
    private final java.util.concurrent.CountDownLatch interrupted = new java.util.concurrent.CountDownLatch(1);

    /** Converts {@code square}, {@code wander}, {@code none} (any case) to a {@link Program}. */
    static final class ProgramConverter implements CommandLine.ITypeConverter<Program> {
        @Override
        public Program convert(String value) {
            try {
                return Program.valueOf(value.toUpperCase(Locale.ROOT));
            } catch (IllegalArgumentException e) {
                throw new CommandLine.TypeConversionException("'" + value + "' is not a program; choose square, wander or none");
            }
        }
    }

    @Override
    public Integer call() {
        PrintWriter out = spec.commandLine().getOut();
        PrintWriter err = spec.commandLine().getErr();
        try {
            return run(out, err);
        } finally {
            out.flush();
            err.flush();
        }
    }

    private int run(PrintWriter out, PrintWriter err) {
        checkOptions();
        if (view && GraphicsEnvironment.isHeadless()) {
            err.println("mw sim: --view needs a display and there is none (no DISPLAY, or java.awt.headless is set). "
                    + "Run it on a desktop or under Xvfb (xvfb-run -a ./mw sim " + worldFile + " --view), or draw a picture with --png FILE.");
            return INVALID;
        }
        RenderOptions options = RenderOptions.DEFAULT.withSize(width, RenderOptions.FIT_HEIGHT).withRays(rays);
        Simulation sim;
        try {
            sim = Simulation.load(worldFile);
        } catch (DescriptionException e) {
            err.println(e.getMessage());
            return INVALID;
        } catch (IllegalArgumentException e) {
            err.println(worldFile + ": " + e.getMessage());
            return INVALID;
        } catch (RobotException e) {
            // A robot file whose values the simulator refuses (sensor options); the message names the world, the robot's file and the sensor.
            err.println(e.getMessage());
            return INVALID;
        }
        try (sim) {
            if (console || record != null || foxglove.on()) {
                io.robomw.console.Console.Builder b = foxglove.apply(io.robomw.console.Console.builder("mw " + String.join(" ", spec.commandLine().getParseResult().originalArgs()))
                        .simulation(sim).record(record).about("world", worldFile.toString()));
                if (console) {
                    b.page("127.0.0.1", consolePort);
                } else {
                    b.noPage();
                }
                try {
                    watching = b.start();
                } catch (IOException e) {
                    err.println("mw sim: " + e.getMessage());
                    return FAILED;
                }
                io.robomw.console.Console w = watching;
                Runtime.getRuntime().addShutdownHook(new Thread(() -> {
                    interrupted.countDown();
                    w.close(); // a run stopped by Ctrl-C still gets its recording's summary and footer
                }, "mw-sim-shutdown"));
                watching.pageAddress().ifPresent(a -> out.println("console at " + a));
                watching.foxgloveAddress().ifPresent(a -> out.println("foxglove at " + a));
                watching.recording().ifPresent(f -> out.println("recording to " + f));
                out.flush();
            }
            io.robomw.console.rosbridge.RosBridge bridge = null;
            try {
                if (rosbridge.wanted()) {
                    bridge = startRosBridge(sim, out, err);
                    if (bridge == null) {
                        return FAILED;
                    }
                }
                return runAndReport(sim, out, err, options);
            } finally {
                if (bridge != null) {
                    bridge.close();
                }
                if (watching != null) {
                    watching.close();
                }
            }
        }
    }

    private int runAndReport(Simulation sim, PrintWriter out, PrintWriter err, RenderOptions options) {
        {
            long wallStart = System.nanoTime();
            int status = OK;
            try {
                if (view) {
                    runInViewer(sim, options);
                } else if (pace != null && pace.realTime || (console || foxglove.on() || rosbridge.wanted()) && pace == null) {
                    runInRealTime(sim);
                } else {
                    runFast(sim);
                }
            } catch (RobotException e) {
                err.println("mw sim: " + e.getMessage() + (program == Program.SQUARE ? " (a longer --duration or a smaller --side helps)" : ""));
                status = FAILED;
            } catch (InterruptedException e) {
                Thread.currentThread().interrupt();
                err.println("mw sim: interrupted");
                return FAILED;
            }
            double wallSeconds = (System.nanoTime() - wallStart) / 1e9;
            if (png != null) {
                try {
                    PngRenderer.write(sim.world(), png, options);
                    out.printf(Locale.ROOT, "wrote %s (%d × %d px)%n", png, options.widthPx(), PngRenderer.heightPx(sim.world().description(), options));
                } catch (IOException e) {
                    err.println("mw sim: cannot write " + png + ": " + e);
                    status = FAILED;
                }
            }
            printSummary(out, sim.world(), wallSeconds);
            if (console || foxglove.on()) {
                out.println((console ? "the console keeps" : "Foxglove keeps") + " showing the world until Ctrl-C");
                out.flush();
                awaitCtrlC();
            }
            return status;
        }
    }

    /**
     * Serves the world's robots to ROS 2 clients (--rosbridge) until the run ends or Ctrl-C.
     *
     * @return the endpoint, or {@code null} if it could not start (said on {@code err})
     */
    private io.robomw.console.rosbridge.RosBridge startRosBridge(Simulation sim, PrintWriter out, PrintWriter err) {
        List<io.robomw.console.rosbridge.BridgedRobot> robots = new ArrayList<>();
        for (Robot r : sim.robots()) {
            robots.add(io.robomw.console.rosbridge.BridgedRobot.simulated(r, sim.world().robot(r.name())));
        }
        try {
            io.robomw.console.rosbridge.RosBridge bridge = rosbridge.start(robots, null, out);
            Runtime.getRuntime().addShutdownHook(new Thread(bridge::close, "mw-sim-rosbridge-shutdown"));
            return bridge;
        } catch (IOException | IllegalArgumentException e) {
            err.println("mw sim: " + e.getMessage());
            return null;
        }
    }

    /** Waits for Ctrl-C (or SIGTERM), so a page stays up after the run. */
    private void awaitCtrlC() {
        try {
            interrupted.await();
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
        }
    }

    private void checkOptions() {
        CommandLine cl = spec.commandLine();
        if (durationOption.isZero()) {
            throw new CommandLine.ParameterException(cl, "--duration must be longer than 0");
        }
        duration = durationOption.toNanos() / 1e9;
        if (!(side > 0) || Double.isInfinite(side)) {
            throw new CommandLine.ParameterException(cl, "--side must be a number of metres > 0, got " + side);
        }
        if (!(speed >= RealTimeControl.MIN_SPEED && speed <= RealTimeControl.MAX_SPEED)) {
            throw new CommandLine.ParameterException(cl, "--speed must be between 1/16 and 64, got " + speed);
        }
        if (width < RenderOptions.MIN_SIZE_PX || width > RenderOptions.MAX_SIZE_PX) {
            throw new CommandLine.ParameterException(cl, "--width must be " + RenderOptions.MIN_SIZE_PX + " to " + RenderOptions.MAX_SIZE_PX + " px, got " + width);
        }
        if (rosbridge.wanted() && pace != null && pace.fast) {
            throw new CommandLine.ParameterException(cl, "--rosbridge runs the world in real time (ROS clients drive it as it runs), so it cannot be combined with --fast");
        }
        if (rosbridge.wanted() && !cl.getParseResult().hasMatchedOption("--duration")) {
            duration = Double.POSITIVE_INFINITY; // a world served to ROS clients runs until Ctrl-C
        }
        if (view && pace != null && pace.fast) {
            throw new CommandLine.ParameterException(cl, "--view runs the world in real time, so it cannot be combined with --fast; "
                    + "speed it up with --speed or the + key in the window");
        }
    }

    /** As fast as possible, in lockstep: the same world and options give the same result, bit for bit. */
    private void runFast(Simulation sim) {
        Duration limit = simDuration();
        switch (program) {
            case SQUARE -> {
                sim.run(limit, squarePrograms(sim).toArray(Runnable[]::new));
                double left = duration - sim.world().time();
                if (left > sim.world().stepSeconds() / 2) {
                    sim.runFor(Duration.ofNanos(Math.round(left * 1e9)));
                }
            }
            case WANDER -> {
                WanderController.install(sim, WANDER_HZ, sim.world().description().seed());
                sim.runFor(limit);
            }
            case NONE -> sim.runFor(limit);
        }
    }

    /** In real time on the simulation's thread, until {@code --duration} of simulated time has passed. */
    private void runInRealTime(Simulation sim) throws InterruptedException {
        Programs programs = startPrograms(sim);
        CountDownLatch reached = new CountDownLatch(1);
        double end = duration - sim.world().stepSeconds() / 2;
        Runnable endCheck = () -> {
            if (sim.world().time() >= end) {
                reached.countDown();
            }
        };
        sim.addStepListener(endCheck);
        sim.startRealTime(speed);
        try {
            reached.await();
        } finally {
            sim.stopRealTime();
            sim.removeStepListener(endCheck);
        }
        programs.requireFinished(duration);
    }

    /** In the viewer window until it is closed; programs still running then are left as they are. */
    private void runInViewer(Simulation sim, RenderOptions options) throws InterruptedException {
        Programs programs = startPrograms(sim);
        SimViewer viewer = SimViewer.open(sim, options, speed);
        viewer.awaitClosed();
        programs.rethrowFailures();
    }

    private Duration simDuration() {
        return Duration.ofNanos(Math.round(duration * 1e9));
    }

    /** One {@link SquareProgram} per robot that drives or walks; robots without a drive stand still. */
    private List<Runnable> squarePrograms(Simulation sim) {
        List<Runnable> programs = new ArrayList<>();
        for (Robot robot : sim.robots()) {
            Robot driven = watching != null ? watching.recordCommands(robot) : robot;
            var d = sim.world().robot(robot.name()).description();
            // Wheels keep a share of their top speed in reserve for steering; a gait's top speed is a walking speed.
            d.drive().map(w -> w.maxSpeed() * SQUARE_SPEED_SHARE).or(() -> d.leggedDrive().map(l -> l.maxSpeed())).ifPresent(max ->
                    programs.add(new SquareProgram(driven, side, Math.min(SQUARE_SPEED, max))));
        }
        return programs;
    }

    /**
     * Starts the program for a real-time run: wander as a step listener, square on one thread per
     * robot.
     */
    private Programs startPrograms(Simulation sim) {
        if (program == Program.WANDER) {
            WanderController.install(sim, WANDER_HZ, sim.world().description().seed());
        }
        return sim.startPrograms(program == Program.SQUARE ? squarePrograms(sim).toArray(Runnable[]::new) : new Runnable[0]);
    }

    private void printSummary(PrintWriter out, SimWorld world, double wallSeconds) {
        double simSeconds = world.time();
        out.printf(Locale.ROOT, "world '%s': %d robots, program %s, %.1f s simulated in %.2f s (%.1f× real time)%n",
                world.description().name(), world.robots().size(), program.name().toLowerCase(Locale.ROOT), simSeconds, wallSeconds,
                wallSeconds > 0 ? simSeconds / wallSeconds : 0.0);
        out.printf(Locale.ROOT, "%-16s %8s %8s %12s %11s%n", "robot", "x (m)", "y (m)", "heading (°)", "driven (m)");
        List<SimRobot> robots = world.robots();
        double total = 0;
        for (int i = 0; i < robots.size(); i++) {
            SimRobot r = robots.get(i);
            Pose p = r.pose();
            double driven = driven(r);
            total += driven;
            if (i < SUMMARY_ROWS) {
                out.printf(Locale.ROOT, "%-16s %8.3f %8.3f %12.1f %11.3f%n", r.name(), p.x(), p.y(), Math.toDegrees(p.heading()), driven);
            }
        }
        if (robots.size() > SUMMARY_ROWS) {
            out.printf(Locale.ROOT, "... and %d more robots; %.3f m driven on average%n", robots.size() - SUMMARY_ROWS, total / robots.size());
        }
    }

    /** @return the length of the robot's sampled path, up to its pose now, metres */
    static double driven(SimRobot robot) {
        Pose now = robot.pose();
        return robot.trajectory().lengthTo(now.x(), now.y());
    }
}
