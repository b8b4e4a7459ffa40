package io.robomw.console;

import io.robomw.agents.net.OwnerThreads;
import io.robomw.api.spi.FailurePolicy;
import io.robomw.agents.host.ClusterKey;
import io.robomw.api.Robot;
import io.robomw.console.foxglove.FoxgloveServer;
import io.robomw.console.foxglove.Teleop;
import io.robomw.console.observe.Observation;
import io.robomw.console.observe.Observer;
import io.robomw.console.observe.WorldMap;
import io.robomw.console.record.McapRecorder;
import io.robomw.console.server.ConsoleServer;
import io.robomw.console.server.ConsoleView;
import io.robomw.console.server.Controls;
import io.robomw.console.source.HostWatcher;
import io.robomw.console.source.RecordingRobot;
import io.robomw.console.source.RobotWatcher;
import io.robomw.console.source.SimSource;
import io.robomw.sim.Simulation;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.io.IOException;
import java.nio.file.Path;
import java.time.Duration;
import java.util.ArrayList;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Map;
import java.util.Objects;
import java.util.Optional;
import java.util.UUID;

/**
 * Watching and recording, put together: sources (agent hosts, robots served over messaging, a
 * simulated world, robots whose commands are recorded) feed observations to the console's page
 * ({@link ConsoleServer}, optional) and to a recording ({@link McapRecorder}, optional). What
 * {@code mw console}, {@code mw record}, and {@code --console} / {@code --record} on
 * {@code mw sim}, {@code mw host} and {@code mw demo} start.
 *
 * <p>The page's retract and dispose buttons go to the host the agent was last seen at, over the
 * host's authenticated link (the cluster key this console was given; without one they are
 * disabled and say why); its stop buttons stop a watched remote robot or a simulated one.
 *
 * <p>With {@link Builder#foxglove} the same observations also go, live, to a Foxglove WebSocket
 * ({@link FoxgloveServer}), whose clients may drive the robots this console can stop.
 */
public final class Console implements AutoCloseable {

    private static final Logger LOG = LoggerFactory.getLogger(Console.class);

    private final ConsoleView view;
    private final McapRecorder recorder;
    private final FoxgloveServer foxglove;
    private final Observer observer;
    private final List<HostWatcher> hosts = new java.util.concurrent.CopyOnWriteArrayList<>();
    private final List<RobotWatcher> robots = new java.util.concurrent.CopyOnWriteArrayList<>();
    private final List<AutoCloseable> others = new ArrayList<>();
    private final Simulation sim;
    private final ClusterKey key;
    private final Duration period;
    private final FailurePolicy failures;
    private ConsoleServer server;
    private boolean closed;

    private Console(Builder b, McapRecorder recorder) {
        this.view = new ConsoleView(b.title);
        this.recorder = recorder;
        this.foxglove = b.foxglovePort < 0 ? null : FoxgloveServer.create(
                FoxgloveServer.Options.live(b.title, "127.0.0.1", b.foxglovePort).listening(b.foxgloveBind, b.foxgloveToken));
        List<Observer> to = new ArrayList<>(List.of(view));
        if (recorder != null) {
            to.add(recorder);
        }
        if (foxglove != null) {
            to.add(foxglove);
        }
        this.observer = to.size() == 1 ? view : Observer.all(to.toArray(Observer[]::new));
        this.sim = b.simulation;
        this.key = b.key;
        this.period = b.period;
        this.failures = b.failures;
    }

    /** @param title shown on the page: the command that runs the console @return a builder */
    public static Builder builder(String title) {
        return new Builder(title);
    }

    /** What to watch and where to show and record it. */
    public static final class Builder {
        private final String title;
        private String bind = "127.0.0.1";
        private int port = 8080;
        private boolean page = true;
        private final List<String> hostAddresses = new ArrayList<>();
        private final List<String> robotAddresses = new ArrayList<>();
        private ClusterKey key;
        private boolean tls;
        private WorldMap world;
        private Simulation simulation;
        private Path recording;
        private final Map<String, String> about = new LinkedHashMap<>();
        private Duration period = Duration.ofMillis(500);
        private boolean discover;
        private String foxgloveBind = "127.0.0.1";
        private int foxglovePort = -1;
        private String foxgloveToken;
        private FailurePolicy failures = FailurePolicy.logging();

        private Builder(String title) {
            this.title = Objects.requireNonNull(title);
            about.put("command", title);
        }

        /** @param address where the page listens (127.0.0.1: this machine only) @param port its port, 0 for a free one @return this */
        public Builder page(String address, int port) {
            this.bind = address;
            this.port = port;
            this.page = true;
            return this;
        }

        /** No page: record only ({@code mw record}). @return this */
        public Builder noPage() {
            this.page = false;
            return this;
        }

        /** @param addresses agent hosts to watch, {@code rmi://host:port/name} @return this */
        public Builder hosts(List<String> addresses) {
            hostAddresses.addAll(addresses);
            return this;
        }

        /** @param addresses robots to watch, as {@code Robots.remote} takes them @return this */
        public Builder robots(List<String> addresses) {
            robotAddresses.addAll(addresses);
            return this;
        }

        /** @param key the cluster key, for watching hosts and their buttons (null: buttons off) @param useTls whether hosts use TLS @return this */
        public Builder clusterKey(ClusterKey key, boolean useTls) {
            this.key = key;
            this.tls = useTls;
            return this;
        }

        /** @param map the world to draw robots on @return this */
        public Builder world(WorldMap map) {
            this.world = map;
            return this;
        }

        /** @param sim a simulation running in this process, watched from inside @return this */
        public Builder simulation(Simulation sim) {
            this.simulation = sim;
            return this;
        }

        /** @param file record into this .mcap file @return this */
        public Builder record(Path file) {
            this.recording = file;
            return this;
        }

        /**
         * Also serves what is watched, live, as a Foxglove WebSocket ({@link FoxgloveServer}: the
         * recordings' channels; clients may drive the robots this console can stop).
         *
         * @param address where it listens (127.0.0.1: this machine only)
         * @param port    its port ({@link FoxgloveServer#DEFAULT_PORT} is Foxglove's usual one), 0 for a free one
         * @return this
         */
        public Builder foxglove(String address, int port) {
            return foxglove(address, port, null);
        }

        /**
         * {@link #foxglove(String, int)} with an access token, which an address beyond this machine needs
         * ({@link FoxgloveServer.Options}).
         *
         * @param address where it listens
         * @param port    its port, 0 for a free one
         * @param token   the access token clients must give, or {@code null} (then {@code address} must be loopback)
         * @return this
         * @throws IllegalArgumentException if the address is beyond this machine and there is no token
         */
        public Builder foxglove(String address, int port, String token) {
            FoxgloveServer.Options.live("check", "127.0.0.1", port).listening(Objects.requireNonNull(address, "address"), token);
            this.foxgloveBind = address;
            this.foxglovePort = port;
            this.foxgloveToken = token;
            return this;
        }

        /** @param key a fact about the run, kept in the recording's metadata @param value its value @return this */
        public Builder about(String key, String value) {
            about.put(key, value);
            return this;
        }

        /**
         * Also watches the hosts the watched hosts know (their directory: each host's
         * {@code DESCRIBE} lists the hosts it has met), asking every {@value #DISCOVER_SECONDS} s.
         *
         * @return this
         */
        public Builder discover() {
            this.discover = true;
            return this;
        }

        /** Seconds between two looks at the watched hosts' directories. */
        public static final int DISCOVER_SECONDS = 5;

        /**
         * @param policy where whatever the console's threads catch goes (default
         *               {@link FailurePolicy#logging()}): its host and robot watchers, its discovery,
         *               its recorder, its page's pushes and requests
         * @return this
         */
        public Builder failures(FailurePolicy policy) {
            this.failures = Objects.requireNonNull(policy, "policy");
            return this;
        }

        /** @param period how often hosts and robots are asked @return this */
        public Builder period(Duration period) {
            this.period = period;
            return this;
        }

        /**
         * Starts watching, serving and recording.
         *
         * @return the console
         * @throws IOException if the page's port or the recording's file cannot be used
         */
        public Console start() throws IOException {
            if (!hostAddresses.isEmpty() && key == null && !tls) {
                throw new IllegalArgumentException("watching agent hosts needs the cluster key (--key-file, MW_CLUSTER_KEY or ~/.robomw/cluster.key): "
                        + "hosts answer authenticated peers only");
            }
            McapRecorder recorder = recording == null ? null : McapRecorder.start(recording, about, failures);
            Console c = new Console(this, recorder);
            try {
                c.open(this);
            } catch (IOException | RuntimeException e) {
                c.close();
                throw e;
            }
            return c;
        }
    }

    private void open(Builder b) throws IOException {
        if (foxglove != null) {
            foxglove.start(new ConsoleTeleop());
        }
        if (b.world != null) {
            observer.observe(new Observation.World(now(), b.world));
        }
        if (b.simulation != null) {
            others.add(SimSource.watch(b.simulation, observer));
        }
        for (String h : b.hostAddresses) {
            hosts.add(HostWatcher.watch(h, b.key != null ? b.key : ClusterKey.tlsOnly(), b.tls, observer, b.period, failures));
        }
        for (String r : b.robotAddresses) {
            robots.add(RobotWatcher.watch(r, observer, b.period.dividedBy(2), failures));
        }
        if (b.discover) {
            java.util.concurrent.ScheduledExecutorService s = java.util.concurrent.Executors.newSingleThreadScheduledExecutor(
                    r -> OwnerThreads.thread("console-discover", r, failures));
            s.scheduleWithFixedDelay(OwnerThreads.rounds(failures, this::discoverHosts), 0, Builder.DISCOVER_SECONDS, java.util.concurrent.TimeUnit.SECONDS);
            others.add(s::shutdownNow);
        }
        if (b.page) {
            server = ConsoleServer.start(view, new ConsoleControls(), b.bind, b.port, failures);
        }
    }

    /**
     * Asks each watched host which hosts it knows, over its watcher's link (one session per host
     * for the console's life, not one per look), and watches the ones not watched yet.
     */
    private void discoverHosts() {
        for (HostWatcher w : List.copyOf(hosts)) {
            if (!w.last().up()) {
                continue;
            }
            io.robomw.agents.host.HostDescription d;
            try {
                d = w.describe();
            } catch (IOException | RuntimeException e) {
                LOG.debug("console: {} did not say which hosts it knows: {}", w.address(), e.toString());
                continue;
            }
            for (io.robomw.agents.host.HostDescription.Known k : d.known()) {
                synchronized (this) {
                    if (!closed && hosts.stream().noneMatch(h -> h.address().equals(k.address()))) {
                        LOG.info("console: {} knows host {} at {}: watching it too", w.address(), k.name(), k.address());
                        watchHost(k.address());
                    }
                }
            }
        }
    }

    /**
     * Watches one more agent host (one started after this console, such as {@code mw host}'s own).
     *
     * @param address the host
     */
    public void watchHost(String address) {
        hosts.add(HostWatcher.watch(address, key != null ? key : ClusterKey.tlsOnly(), key == null, observer, period, failures));
    }

    /**
     * Watches a robot of this process (its odometry and sensors), which stays the caller's.
     *
     * @param robot  the robot
     * @param source where it is (its robot file, its host), for the page
     */
    public void watchRobot(Robot robot, String source) {
        robots.add(RobotWatcher.watch(robot, source, observer, period.dividedBy(2), failures));
    }

    /** @return the addresses of the hosts watched, those found through the directory included */
    public List<String> watchedHosts() {
        return hosts.stream().map(HostWatcher::address).toList();
    }

    /** @return where observations go (add sources of your own: a robot's commands, a replay) */
    public Observer observer() {
        return observer;
    }

    /**
     * @param robot a robot driven in this process
     * @return the same robot, its commands recorded and shown
     */
    public Robot recordCommands(Robot robot) {
        return RecordingRobot.wrap(robot, observer);
    }

    /** @return the page's address with its access token, or empty without a page */
    public Optional<String> pageAddress() {
        return Optional.ofNullable(server).map(ConsoleServer::pageWithToken);
    }

    /** @return where Foxglove connects ({@code ws://127.0.0.1:8765}), or empty without {@link Builder#foxglove} */
    public Optional<java.net.URI> foxgloveAddress() {
        return Optional.ofNullable(foxglove).map(FoxgloveServer::address);
    }

    /** @return the recording, or empty */
    public Optional<Path> recording() {
        return Optional.ofNullable(recorder).map(McapRecorder::file);
    }

    private static long now() {
        return System.currentTimeMillis() * 1_000_000L;
    }

    /** Stops watching, finishes the recording (summary and footer), stops serving. Once; later calls wait for the first. */
    @Override
    public synchronized void close() {
        if (closed) {
            return;
        }
        closed = true;
        hosts.forEach(HostWatcher::close);
        robots.forEach(RobotWatcher::close);
        for (AutoCloseable c : others) {
            try {
                c.close();
            } catch (Exception e) {
                LOG.warn("console: closing {} failed: {}", c, e.toString());
            }
        }
        if (recorder != null) {
            try {
                recorder.close();
            } catch (IOException e) {
                LOG.error("console: the recording {} could not be finished: {}", recorder.file(), e.toString());
            }
        }
        if (server != null) {
            server.close();
        }
        if (foxglove != null) {
            foxglove.close();
        }
    }

    /** @return the robots this console can stop and drive: watched ones, and a simulation's */
    private java.util.Set<String> robotsDriven() {
        java.util.Set<String> names = new java.util.TreeSet<>();
        robots.forEach(w -> names.add(w.name()));
        if (sim != null) {
            sim.robots().forEach(r -> names.add(r.name()));
        }
        return names;
    }

    /** What Foxglove clients may drive: the robots the page's stop buttons stop (watched ones, a simulation's). */
    private final class ConsoleTeleop implements Teleop {
        @Override
        public java.util.Set<String> robots() {
            return robotsDriven();
        }

        @Override
        public void drive(String robot, double linear, double angular) {
            RobotWatcher watched = robots.stream().filter(w -> w.name().equals(robot)).findFirst().orElse(null);
            if (watched != null) {
                watched.drive(linear, angular);
            } else if (sim != null) {
                sim.robot(robot).drive(linear, angular);
            } else {
                throw new IllegalArgumentException("this console drives no robot named '" + robot + "'");
            }
            Map<String, Double> args = new LinkedHashMap<>();
            args.put("linearSpeed", linear);
            args.put("angularSpeed", angular);
            observer.observe(new Observation.RobotCommand(now(), robot, "drive", args));
        }
    }

    /** The buttons: agents through the hosts' authenticated links, robots through their watchers or the simulation. */
    private final class ConsoleControls implements Controls {
        @Override
        public boolean agentsControllable() {
            return key != null && !hosts.isEmpty();
        }

        @Override
        public String agentsWhyNot() {
            if (hosts.isEmpty()) {
                return "this console watches no agent host";
            }
            return key == null ? "this console was started without a cluster key, so it cannot retract or dispose of agents" : "";
        }

        private HostWatcher hostOf(UUID agent) {
            String at = view.hostOf(agent.toString())
                    .orElseThrow(() -> new IllegalArgumentException("agent " + agent + " is not at any host this console watches"));
            return hosts.stream().filter(h -> h.address().equals(at)).findFirst()
                    .orElseThrow(() -> new IllegalArgumentException("agent " + agent + " is at " + at + ", which this console does not watch"));
        }

        @Override
        public String retract(UUID agent) throws Exception {
            requireKey();
            return hostOf(agent).retract(agent);
        }

        @Override
        public String dispose(UUID agent) throws Exception {
            requireKey();
            return hostOf(agent).dispose(agent);
        }

        private void requireKey() {
            if (key == null) {
                throw new IllegalStateException(agentsWhyNot());
            }
        }

        @Override
        public java.util.Set<String> stoppableRobots() {
            return robotsDriven();
        }

        @Override
        public String stop(String robot) {
            for (RobotWatcher w : robots) {
                if (w.name().equals(robot)) {
                    return w.stop();
                }
            }
            if (sim != null) {
                Robot r = sim.robot(robot);
                r.stop();
                observer.observe(new Observation.RobotCommand(now(), robot, "stop", Map.of()));
                return "robot " + robot + " stopped";
            }
            throw new IllegalArgumentException("this console does not drive a robot named '" + robot + "'");
        }
    }
}
