package io.robomw.cli;

import io.robomw.agents.host.AgentHost;
import io.robomw.agents.host.ClusterKey;
import io.robomw.api.Agent;
import io.robomw.api.AgentRef;
import io.robomw.api.Pose;
import io.robomw.sim.SimRobot;
import io.robomw.sim.Simulation;
import io.robomw.config.description.RobotDescription;
import io.robomw.config.description.RobotDescriptionLoader;
import io.robomw.sim.emulator.Emulator;
import io.robomw.sim.emulator.aibo.AiboEmulator;
import io.robomw.sim.emulator.ev3.Ev3Emulator;
import io.robomw.sim.emulator.ft.intelligent.IntelligentInterfaceEmulator;
import io.robomw.sim.emulator.ft.txt.TxtEmulator;
import io.robomw.sim.emulator.nxt.NxtEmulator;
import io.robomw.sim.render.PngRenderer;
import io.robomw.sim.render.RenderOptions;
import io.robomw.sim.world.WorldDescription;
import io.robomw.sim.world.WorldLoader;
import picocli.CommandLine.Command;
import picocli.CommandLine.Model.CommandSpec;
import picocli.CommandLine.Option;
import picocli.CommandLine.Spec;

import java.io.BufferedReader;
import java.io.IOException;
import java.io.InputStreamReader;
import java.io.PrintWriter;
import java.io.Serializable;
import java.lang.reflect.RecordComponent;
import java.net.InetAddress;
import java.net.InetSocketAddress;
import java.net.ServerSocket;
import java.net.URL;
import java.net.URLClassLoader;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.security.SecureRandom;
import java.time.Duration;
import java.util.ArrayList;
import java.util.HexFormat;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Locale;
import java.util.Map;
import java.util.Set;
import java.util.concurrent.BlockingQueue;
import java.util.concurrent.Callable;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.LinkedBlockingQueue;
import java.util.concurrent.TimeUnit;

/**
 * {@code mw demo}: the paper's scenario (section IV, Fig. 7-8) in one command. One simulated world
 * with a LEGO NXT robot and a fischertechnik robot (and, with {@code --robots nxt,ft,aibo}, the
 * paper's third platform, a Sony Aibo; with {@code --robots nxt,copter,boat}, in the harbour world, a
 * drone flying its square at 2 m and a boat sailing it, each behind an emulated ArduPilot on UDP); a
 * virtual brick bound to each (a virtual NXT brick and a
 * virtual fischertechnik Intelligent Interface, each on its own pseudo-terminal; the Aibo's URBI
 * server on a TCP port); one agent host process per robot, each driving its robot through the real
 * driver over that link; and clones of one agent, shipped from the examples jar, dispatched to
 * every host. Each clone drives a square, samples its range sensor and brings the samples home;
 * the demo prints a table per robot, writes a picture of the trajectories, stops every process and
 * exits 0.
 */
@Command(name = "demo", mixinStandardHelpOptions = true,
        description = {"The paper's scenario: clones of one agent sent to a LEGO NXT and a fischertechnik robot (simulated, behind virtual bricks);",
                "--robots nxt,ft,aibo adds the Sony Aibo; --robots nxt,copter,boat goes to the harbour: on land, in the air at 2 m and on the water.",
                "Writes demo.png (the trajectories) and prints each robot's results."})
final class DemoCommand implements Callable<Integer> {

    private static final String AGENT = "io.robomw.examples.agents.SquareSurveyAgent";

    @Option(names = "--robots", split = ",", defaultValue = "nxt,ft", paramLabel = "NAME,...",
            description = "the robots of the world to send clones to (default ${DEFAULT-VALUE}, the paper's two; nxt,ft,aibo adds the Aibo)")
    List<String> robots;

    @Option(names = "--home", description = "the RoboMW checkout (default: the mw.home property the mw launcher sets, else .)")
    Path home;

    @Option(names = "--world", paramLabel = "WORLD.yaml", description = "the world (default: examples/worlds/arena.yaml, or harbour.yaml for robots only it has); its robots named by --robots are used")
    Path world;

    @Option(names = "--agent-jar", paramLabel = "JAR", description = "the jar with the agent (default: examples/target/examples-0.1.0-SNAPSHOT.jar)")
    Path agentJar;

    @Option(names = "--side", description = "side of each square, metres (default 0.4; 2 in a world wider than 10 m, the harbour)")
    Double side;

    @Option(names = "--png", defaultValue = "demo.png", description = "where to write the picture of both trajectories (default ${DEFAULT-VALUE})")
    Path png;

    @Option(names = "--logs", paramLabel = "DIR", description = "where the host processes' logs go (default: a temporary directory)")
    Path logs;

    @Option(names = "--timeout", defaultValue = "2m", description = "longest the agents may take: 90s, 2m, ISO-8601... (default ${DEFAULT-VALUE})")
    Duration timeout;

    @Option(names = "--console", description = "show the run live in a web page (prints its address); the page stays up after the demo until Ctrl-C")
    boolean console;

    @Option(names = "--console-port", defaultValue = "8080", description = "the page's port (default ${DEFAULT-VALUE}; 0 picks a free one)")
    int consolePort;

    @Option(names = "--record", paramLabel = "FILE.mcap", description = "record the run (both robots' poses and sensors, the agents' events) into an MCAP file that Foxglove opens")
    Path record;

    @picocli.CommandLine.Mixin
    FoxgloveOption foxglove;

    @picocli.CommandLine.Mixin
    RosBridgeOption rosbridge;

    @Spec
    CommandSpec spec;

    private PrintWriter out;
    /** Counted down once everything is closed: a Ctrl-C waits for it (the recording's footer) before the JVM ends. */
    private final java.util.concurrent.CountDownLatch closed = new java.util.concurrent.CountDownLatch(1);

    /** Waits for Ctrl-C (or SIGTERM), so the page stays up after the demo. */
    private void awaitCtrlC() throws InterruptedException {
        java.util.concurrent.CountDownLatch interrupted = new java.util.concurrent.CountDownLatch(1);
        Runtime.getRuntime().addShutdownHook(new Thread(() -> {
            interrupted.countDown();
            try {
                closed.await(30, TimeUnit.SECONDS);
            } catch (InterruptedException e) {
                Thread.currentThread().interrupt();
            }
        }, "mw-demo-shutdown"));
        interrupted.await();
    }

    @Override
    public Integer call() throws Exception {
        out = spec.commandLine().getOut();
        Path root = home != null ? home : Path.of(System.getProperty("mw.home", "."));
        Path worldFile = world != null ? world : defaultWorld(root);
        Path jar = agentJar != null ? agentJar : root.resolve("examples/target/examples-0.1.0-SNAPSHOT.jar");
        if (!Files.isRegularFile(jar)) {
            spec.commandLine().getErr().println("mw demo: no agent jar at " + jar + " (build it: mvn -q -DskipTests -pl examples -am package)");
            return 2;
        }
        Path logDir = logs != null ? Files.createDirectories(logs) : Files.createTempDirectory("mw-demo-");
        // The demo's table is for people: what the libraries in this JVM log (brokers, emulators, the home)
        // goes to demo.log beside the hosts' logs instead of interleaving with it on the terminal.
        java.io.PrintStream terminal = System.err;
        try (java.io.PrintStream log = new java.io.PrintStream(Files.newOutputStream(logDir.resolve("demo.log"), java.nio.file.StandardOpenOption.CREATE,
                java.nio.file.StandardOpenOption.APPEND), true, java.nio.charset.StandardCharsets.UTF_8)) {
            System.setErr(log);
            return run(root, worldFile, jar, logDir);
        } finally {
            System.setErr(terminal);
        }
    }

    private Integer run(Path root, Path worldFile, Path jar, Path logDir) throws Exception {
        Path keyFile = logDir.resolve("cluster.key");
        byte[] secret = new byte[24];
        new SecureRandom().nextBytes(secret);
        Files.writeString(keyFile, HexFormat.of().formatHex(secret));
        WorldDescription description = new WorldLoader().load(worldFile);
        double squareSide = side != null ? side : description.width() > 10 ? VEHICLE_SIDE : DEFAULT_SIDE;
        List<String> names = List.copyOf(new java.util.LinkedHashSet<>(robots));
        Map<String, Path> robotFiles = new LinkedHashMap<>();
        Map<String, String> platforms = new LinkedHashMap<>();
        for (String r : names) {
            Path file = description.robots().stream().filter(p -> p.name().equals(r)).findFirst()
                    .orElseThrow(() -> new IllegalArgumentException(worldFile + " has no robot '" + r + "'; its robots are "
                            + description.robots().stream().map(WorldDescription.RobotPlacement::name).toList())).description();
            robotFiles.put(r, file);
            RobotDescription d = new RobotDescriptionLoader().load(file);
            if (!EMULATORS.containsKey(d.platform())) {
                spec.commandLine().getErr().println("mw demo: robot '" + r + "' is on platform '" + d.platform() + "', which has no emulator; emulated: "
                        + EMULATORS.keySet());
                return 2;
            }
            platforms.put(r, d.platform());
        }
        long started = System.nanoTime();
        List<Process> hosts = new ArrayList<>();
        List<AutoCloseable> closeLater = new java.util.concurrent.CopyOnWriteArrayList<>();
        Thread reaper = new Thread(() -> {
            hosts.forEach(Process::destroyForcibly);
            for (AutoCloseable c : closeLater) {
                try {
                    c.close(); // a demo stopped by Ctrl-C still gets its recording's summary and footer
                } catch (Exception e) {
                    System.err.println("mw demo: closing " + c + " failed: " + e);
                }
            }
        }, "mw-demo-reaper");
        Runtime.getRuntime().addShutdownHook(reaper);
        try (Simulation sim = Simulation.load(worldFile, Set.copyOf(names))) {
            step("world %s: robots %s", description.name(), names);
            Map<String, Map<String, String>> links = new LinkedHashMap<>();
            for (String r : names) {
                EmulatorKind kind = EMULATORS.get(platforms.get(r));
                Emulator e = kind.bind().apply(sim, r);
                closeLater.add(e);
                if (e instanceof io.robomw.sim.emulator.mavlink.MavlinkEmulator vehicle) {
                    int port = vehicle.listen(new InetSocketAddress(InetAddress.getLoopbackAddress(), 0)).getPort();
                    links.put(r, Map.of("link", "udpout://127.0.0.1:" + port));
                } else if (kind.tcp()) {
                    int port = e.startOnTcp("127.0.0.1", 0);
                    links.put(r, Map.of("host", "127.0.0.1", "port", String.valueOf(port)));
                } else {
                    links.put(r, Map.of("port", e.startOnPseudoTerminal()));
                }
                step("virtual %s for %s on %s", kind.title(), r, describeLink(links.get(r)));
            }
            io.robomw.console.Console watching = null;
            if (console || record != null || foxglove.on()) {
                io.robomw.console.Console.Builder b = foxglove.apply(io.robomw.console.Console.builder("mw demo").simulation(sim).record(record)
                        .clusterKey(ClusterKey.read(keyFile), false).about("world", worldFile.toString()));
                watching = (console ? b.page("127.0.0.1", consolePort) : b.noPage()).start();
                closeLater.add(watching);
                watching.pageAddress().ifPresent(a -> step("console at %s", a));
                watching.foxgloveAddress().ifPresent(a -> step("foxglove at %s", a));
                watching.recording().ifPresent(f -> step("recording to %s", f));
            }
            sim.startRealTime(1.0);
            Map<String, String> addresses = new LinkedHashMap<>();
            for (String r : names) {
                int port = freePort();
                hosts.add(startHost(r, port, robotFiles.get(r), links.get(r), keyFile, logDir, rosbridge.wanted()));
                addresses.put(r, "rmi://127.0.0.1:" + port + "/" + r);
            }
            List<io.robomw.console.rosbridge.BridgedRobot> served = new ArrayList<>();
            for (int i = 0; i < names.size(); i++) {
                String r = names.get(i);
                String ready = awaitReady(r, hosts.get(i), logDir, rosbridge.wanted() ? " served at " : " ready at ");
                if (rosbridge.wanted()) {
                    io.robomw.api.Robot remote = io.robomw.api.Robots.remote(ready.substring(ready.indexOf(" served at ") + " served at ".length()).trim());
                    closeLater.add(0, remote);
                    served.add(io.robomw.console.rosbridge.BridgedRobot.remote(remote));
                }
                step("agent host %s ready at %s (driver: %s over %s)", r, addresses.get(r), EMULATORS.get(platforms.get(r)).title(),
                        describeLink(links.get(r)));
                if (watching != null) {
                    watching.watchHost(addresses.get(r));
                }
            }
            if (rosbridge.wanted()) {
                closeLater.add(0, rosbridge.start(served, null, out)); // the robots through their hosts' drivers, as the agents drive them
            }
            Map<String, Pose> startPoses = new LinkedHashMap<>();
            for (String r : names) {
                startPoses.put(r, sim.world().robot(r).pose());
            }
            Map<String, Serializable> results;
            try (URLClassLoader code = new URLClassLoader(new URL[] {jar.toUri().toURL()}, Agent.class.getClassLoader());
                 AgentHost home = AgentHost.builder("demo").clusterKey(ClusterKey.read(keyFile)).start()) {
                Agent agent = (Agent) code.loadClass(AGENT).getConstructor(double.class).newInstance(squareSide);
                if (watching != null) {
                    watching.watchHost(home.address());
                }
                List<AgentRef> refs = home.agency().dispatchClones(agent, addresses.values().toArray(String[]::new));
                step("dispatched clones of %s (its code from %s) to %s", AGENT, jar.getFileName(), hostsWord(names.size()));
                results = new LinkedHashMap<>();
                List<CompletableFuture<Serializable>> pending = new ArrayList<>();
                for (int i = 0; i < refs.size(); i++) {
                    String r = names.get(i);
                    refs.get(i).addReportListener(v -> step("[%s] %s", r, v));
                    pending.add(refs.get(i).result());
                }
                List<CompletableFuture<Serializable>> settled = pending.stream().map(f -> f.exceptionally(failure -> null)).toList();
                CompletableFuture.allOf(settled.toArray(CompletableFuture[]::new)).get(timeout.toMillis(), TimeUnit.MILLISECONDS);
                for (int i = 0; i < refs.size(); i++) {
                    int index = i;
                    pending.get(i).exceptionally(failure -> {
                        step("[%s] FAILED: %s", names.get(index), failure.getCause() != null ? failure.getCause().getMessage() : failure.getMessage());
                        return null;
                    });
                    results.put(names.get(i), settled.get(i).get());
                }
            }
            step("%s home after %.1f s", names.size() == 2 ? "both clones are" : "all " + names.size() + " clones are", (System.nanoTime() - started) / 1e9);
            if (!rosbridge.wanted()) {
                stopHosts(hosts);
            }
            boolean complete = true;
            for (String r : names) {
                if (results.get(r) == null) {
                    step("[%s] no result came home (see %s)", r, logDir.resolve(r + "-host.log"));
                    complete = false;
                } else {
                    printTable(r, robotFiles.get(r), results.get(r), startPoses.get(r), sim.world().robot(r));
                }
            }
            if (!complete) {
                return 1;
            }
            sim.pauseRealTime();
            Path picture = png.toAbsolutePath();
            if (picture.getParent() != null) {
                Files.createDirectories(picture.getParent());
            }
            PngRenderer.write(sim.world(), picture, RenderOptions.DEFAULT);
            step("wrote %s (the trajectories)", picture);
            if (rosbridge.wanted()) {
                sim.resumeRealTime(); // ROS clients go on driving the robots through their hosts
                step("the rosbridge keeps serving the robots%s until Ctrl-C", console || foxglove.on() ? " (and the watchers showing them)" : "");
                awaitCtrlC();
            } else if (console || foxglove.on()) {
                stopHosts(hosts);
                step((console ? "the console keeps" : "Foxglove keeps") + " showing the run until Ctrl-C");
                awaitCtrlC();
            }
        } finally {
            stopHosts(hosts);
            for (AutoCloseable c : closeLater) {
                c.close();
            }
            closed.countDown();
            try {
                Runtime.getRuntime().removeShutdownHook(reaper);
            } catch (IllegalStateException e) {
                // the JVM is shutting down (Ctrl-C after the demo): the hook is running
            }
        }
        step("stopped %s, the virtual robots and the world; done in %.1f s (logs in %s: the hosts' and demo.log)", hostsWord(names.size()),
                (System.nanoTime() - started) / 1e9, logDir);
        return 0;
    }

    /** How a robot of a platform is emulated. */
    private record EmulatorKind(String title, boolean tcp, java.util.function.BiFunction<Simulation, String, Emulator> bind) {
    }

    /** The emulators, by the platform of the robot files. */
    private static final Map<String, EmulatorKind> EMULATORS = Map.of(
            "nxt", new EmulatorKind("LEGO NXT brick", false, NxtEmulator::bind),
            "ev3", new EmulatorKind("LEGO EV3 brick", false, Ev3Emulator::bind),
            "ft-intelligent", new EmulatorKind("fischertechnik Intelligent Interface", false, IntelligentInterfaceEmulator::bind),
            "ft-txt", new EmulatorKind("fischertechnik TXT", true, TxtEmulator::bind),
            "aibo", new EmulatorKind("Sony Aibo (URBI server)", true, AiboEmulator::bind),
            "mavlink", new EmulatorKind("MAVLink vehicle (an emulated ArduPilot or PX4, over UDP)", false,
                    (sim, name) -> io.robomw.sim.emulator.mavlink.MavlinkEmulator.bind(sim, name, java.util.Optional.empty(),
                            io.robomw.api.spi.FailurePolicy.logging())));

    /** The side of the squares in the paper's arena, metres. */
    static final double DEFAULT_SIDE = 0.4;
    /** The side in a world wider than 10 m (the harbour, where drones and boats are), metres. */
    static final double VEHICLE_SIDE = 2.0;

    /**
     * @return the paper's arena, or the harbour when the robots asked for are there and not in the
     *         arena ({@code --robots nxt,copter,boat})
     */
    private Path defaultWorld(Path root) {
        Path arena = root.resolve("examples/worlds/arena.yaml");
        Path harbour = root.resolve("examples/worlds/harbour.yaml");
        try {
            java.util.Set<String> inArena = new WorldLoader().load(arena).robots().stream().map(WorldDescription.RobotPlacement::name)
                    .collect(java.util.stream.Collectors.toSet());
            if (!inArena.containsAll(robots) && Files.isRegularFile(harbour)) {
                java.util.Set<String> inHarbour = new WorldLoader().load(harbour).robots().stream().map(WorldDescription.RobotPlacement::name)
                        .collect(java.util.stream.Collectors.toSet());
                if (inHarbour.containsAll(robots)) {
                    return harbour;
                }
            }
        } catch (RuntimeException e) {
            return arena;
        }
        return arena;
    }

    /** @return whether the robot walks on legs: its pose is then dead reckoning, not encoder odometry */
    private static boolean legged(Path robotFile) {
        try {
            return new RobotDescriptionLoader().load(robotFile).leggedDrive().isPresent();
        } catch (RuntimeException e) {
            return false;
        }
    }

    /** @return whether the robot is a vehicle: its pose is what its autopilot reports */
    private static boolean vehicle(Path robotFile) {
        try {
            return new RobotDescriptionLoader().load(robotFile).vehicleDrive().isPresent();
        } catch (RuntimeException e) {
            return false;
        }
    }

    private static String describeLink(Map<String, String> link) {
        return link.containsKey("host") ? "tcp " + link.get("host") + ":" + link.get("port") : link.get("port");
    }

    private static String hostsWord(int n) {
        return n == 2 ? "both hosts" : n == 1 ? "the host" : "all " + n + " hosts";
    }

    /** Stops the host processes (before the bricks, so their drivers do not see the links vanish). */
    private static void stopHosts(List<Process> hosts) throws InterruptedException {
        for (Process p : hosts) {
            p.destroy();
        }
        for (Process p : hosts) {
            if (!p.waitFor(15, TimeUnit.SECONDS)) {
                p.destroyForcibly();
                p.waitFor(10, TimeUnit.SECONDS);
            }
        }
    }

    private void step(String format, Object... args) {
        synchronized (this) {
            out.printf(Locale.ROOT, "demo: " + format + "%n", args);
            out.flush();
        }
    }

    private void printTable(String robot, Path robotFile, Serializable result, Pose start, SimRobot simRobot) {
        Pose end = simRobot.pose();
        double closure = end.distanceTo(start);
        double headingError = Math.toDegrees(Math.abs(Math.IEEEremainder(end.heading() - start.heading(), 2 * Math.PI)));
        List<?> samples = (List<?>) component(result, "samples");
        synchronized (this) {
            out.println();
            out.printf(Locale.ROOT, "== %s (%s, host %s) ==%n", robot, robotFile.getFileName(), component(result, "host"));
            out.printf(Locale.ROOT, "  distance driven    %8.3f m%n", (Double) component(result, "distanceDriven"));
            out.printf(Locale.ROOT, "  final pose error   %8.3f m, %5.1f deg   (true pose in the world vs. where it started)%n", closure, headingError);
            out.printf(Locale.ROOT, "  odometry closure   %8.3f m            (%s)%n", (Double) component(result, "odometryClosure"),
                    legged(robotFile) ? "the robot's own dead reckoning from its commanded gait"
                            : vehicle(robotFile) ? "where the vehicle's autopilot says it is" : "what the robot's own encoders say");
            out.printf(Locale.ROOT, "  samples            %8d%n", samples.size());
            out.printf(Locale.ROOT, "  %8s %8s %9s%n", "x (m)", "y (m)", "range (m)");
            for (Object s : samples) {
                out.printf(Locale.ROOT, "  %8.3f %8.3f %9.3f%n", (Double) component(s, "x"), (Double) component(s, "y"), (Double) component(s, "range"));
            }
            out.println();
            out.flush();
        }
    }

    private static Object component(Object record, String name) {
        for (RecordComponent c : record.getClass().getRecordComponents()) {
            if (c.getName().equals(name)) {
                try {
                    c.getAccessor().setAccessible(true);
                    return c.getAccessor().invoke(record);
                } catch (ReflectiveOperationException e) {
                    throw new IllegalStateException("cannot read " + name + " of " + record.getClass().getName(), e);
                }
            }
        }
        throw new IllegalStateException(record.getClass().getName() + " has no component " + name);
    }

    private static Process startHost(String name, int port, Path robotFile, Map<String, String> link, Path keyFile, Path logDir, boolean serve)
            throws IOException {
        String java = ProcessHandle.current().info().command().orElse(Path.of(System.getProperty("java.home"), "bin", "java").toString());
        List<String> command = new ArrayList<>(List.of(java, "-XX:+UseSerialGC", "-XX:TieredStopAtLevel=1", "-cp", System.getProperty("java.class.path"),
                Mw.class.getName(), "host", "--name", name, "--port", String.valueOf(port), "--robot", robotFile.toString(),
                "--key-file", keyFile.toString()));
        for (Map.Entry<String, String> e : link.entrySet()) {
            command.add("--connection");
            command.add(e.getKey() + "=" + e.getValue());
        }
        if (serve) {
            command.addAll(List.of("--serve", "tcp://127.0.0.1:0")); // --rosbridge reaches the robot through its host
        }
        return new ProcessBuilder(command).redirectError(logDir.resolve(name + "-host.log").toFile()).start();
    }

    /** @return the first line of the host's output that holds {@code until} (it is ready once it printed " ready at ") */
    private static String awaitReady(String name, Process p, Path logDir, String until) throws IOException, InterruptedException {
        BlockingQueue<String> lines = new LinkedBlockingQueue<>();
        Thread reader = new Thread(() -> {
            try (BufferedReader r = new BufferedReader(new InputStreamReader(p.getInputStream(), StandardCharsets.UTF_8))) {
                String line;
                while ((line = r.readLine()) != null) {
                    lines.add(line);
                }
            } catch (IOException ignored) {
                // the host ended
            }
            lines.add("EOF");
        }, "mw-demo-host-" + name);
        reader.setDaemon(true);
        reader.start();
        long deadline = System.nanoTime() + TimeUnit.SECONDS.toNanos(60);
        while (true) {
            String line = lines.poll(Math.max(0, deadline - System.nanoTime()), TimeUnit.NANOSECONDS);
            if (line == null || line.equals("EOF")) {
                throw new IOException("agent host " + name + " did not start (see " + logDir.resolve(name + "-host.log") + ")");
            }
            if (line.contains(until)) {
                return line;
            }
        }
    }

    private static int freePort() throws IOException {
        try (ServerSocket s = new ServerSocket()) {
            s.bind(new InetSocketAddress(InetAddress.getLoopbackAddress(), 0));
            return s.getLocalPort();
        }
    }
}
