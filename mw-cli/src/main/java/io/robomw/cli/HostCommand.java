package io.robomw.cli;

import io.robomw.agents.host.AgentHost;
import io.robomw.agents.host.AgentHostBuilder;
import io.robomw.agents.host.ClusterKey;
import io.robomw.agents.messaging.MessagingNode;
import io.robomw.agents.messaging.MessagingSettings;
import io.robomw.agents.messaging.robot.RobotProtocol;
import io.robomw.agents.messaging.robot.RobotServer;
import io.robomw.api.Robot;
import io.robomw.api.RobotException;
import io.robomw.api.Robots;
import io.robomw.api.spi.PlatformServices;
import io.robomw.config.robot.ConnectionOverride;
import io.robomw.sim.Simulation;
import picocli.CommandLine.Command;
import picocli.CommandLine.Mixin;
import picocli.CommandLine.Model.CommandSpec;
import picocli.CommandLine.Option;
import picocli.CommandLine.Spec;

import java.io.PrintWriter;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Map;
import java.util.concurrent.Callable;
import java.util.concurrent.CountDownLatch;

/**
 * {@code mw host}: an agent host bound to a robot, until Ctrl-C (or SIGTERM). Prints
 * {@code agent host NAME ready at rmi://...} on standard output once it serves.
 */
@Command(name = "host", mixinStandardHelpOptions = true,
        description = {"Runs an agent host: receives mobile agents over RMI and runs them with a robot.",
                "Example: mw host --robot examples/robots/nxt-two-wheeled.yaml --connection port=/dev/pts/5 --port 1099 --name nxt --key-file cluster.key"})
final class HostCommand implements Callable<Integer> {

    @Option(names = "--name", required = true, description = "the host's name; agents address it as rmi://BIND:PORT/NAME")
    String name;

    @Option(names = "--port", defaultValue = "1099", description = "RMI registry port (default ${DEFAULT-VALUE}; 0 picks a free one)")
    int port;

    @Option(names = "--wire-port", paramLabel = "PORT", defaultValue = "0",
            description = "port of the host's agent wire, where agents hop to it (default ${DEFAULT-VALUE}: a free one; peers learn it when they authenticate, so only a firewall needs it)")
    int wirePort;

    @Option(names = "--no-wire", description = "no agent wire: agents hop to and from this host over RMI (protocol version 2 calls)")
    boolean noWire;

    @Option(names = "--bind", defaultValue = "127.0.0.1", description = "address to listen on and be known by (default ${DEFAULT-VALUE})")
    String bind;

    @Option(names = "--robot", paramLabel = "ROBOT.yaml", description = "the robot agents here drive, opened with its driver")
    Path robotFile;

    @Option(names = "--connection", paramLabel = "KEY=VALUE", description = "replace a connection value of the robot file, e.g. port=/dev/pts/5 as mw emulate prints it")
    Map<String, String> connection = new LinkedHashMap<>();

    @Option(names = "--world", paramLabel = "WORLD.yaml", description = "simulate this world here, in real time, and drive its robot --world-robot")
    Path world;

    @Option(names = "--world-robot", paramLabel = "NAME", description = "the robot of --world agents here drive")
    String worldRobot;

    @Option(names = "--speed", defaultValue = "1", description = "simulated seconds per second with --world (default ${DEFAULT-VALUE})")
    double speed;

    @Option(names = "--store", paramLabel = "DIR", description = "keep accepted agents durably here (they survive a kill); default: memory only")
    Path store;

    @Option(names = "--allow", split = ",", paramLabel = "CLASS", description = "classes agent state may hold besides the agent's own code and JDK value types")
    List<String> allow = new ArrayList<>();

    @Option(names = "--serve", paramLabel = "ADDRESS", description = "also serve the robot to Robots.remote at this messaging address, e.g. tcp://127.0.0.1:7000 (then Robots.remote(\"tcp://127.0.0.1:7000/ROBOT\"))"
            + " or a broker, mqtt://127.0.0.1:1883 (then Robots.remote(\"mqtt://127.0.0.1:1883/ROBOT\")); the host's messaging node receives there too")
    String serve;

    @Option(names = "--messaging", paramLabel = "ADDRESS", description = "where the host's messaging node, which its agents use, receives (default: tcp://BIND:0, a free port; mqtt://BROKER joins a broker)")
    String messaging;

    @Option(names = "--max-connections", paramLabel = "N", defaultValue = "128",
            description = "connections the host's messaging node (and --serve) accepts at once; one more is refused, told why (default ${DEFAULT-VALUE})")
    int maxConnections;

    @Option(names = "--no-messaging", description = "start the host without a messaging node (its agents then have no messaging)")
    boolean noMessaging;

    @Option(names = "--announce", paramLabel = "BROKER", description = "announce this host, its robot and its agents at an MQTT broker (mqtt://host:port[/prefix]) for mw agents --cluster BROKER;"
            + " a host whose node is at a broker (--messaging or --serve mqtt://...) announces there already")
    String announce;

    @Option(names = "--serve-password-file", paramLabel = "FILE", description = "file holding the password callers of --serve must give (default: the "
            + Secrets.SERVE_PASSWORD_ENV + " environment variable); --serve needs it, or mutual TLS (--tls-keystore), or --serve-insecure")
    Path servePasswordFile;

    @Option(names = "--serve-insecure", description = "serve the robot (--serve) without a password: anyone who reaches the address can drive it;"
            + " for a closed lab network only (logged as a warning)")
    boolean serveInsecure;

    /** Refused: a secret on the command line shows in ps. */
    @Option(names = "--serve-password", hidden = true, converter = Secrets.RefusedServePassword.class)
    String refusedServePassword;

    @Option(names = "--older-hosts", description = "talk to agent hosts of builds before agent protocol version 4, whose authentication does not bind the"
            + " address it was meant for (a relay between the hosts goes unnoticed): for a cluster being upgraded (hosts of version 4"
            + " need no such leave: those that do not read the compact form of agent state get the standard one)")
    boolean olderHosts;

    @Option(names = "--owed-expiry", paramLabel = "DURATION", defaultValue = "PT24H",
            description = "give up a report or result owed to a home that does not answer after this long (ISO-8601, default ${DEFAULT-VALUE}); mw agents lists what is owed")
    java.time.Duration owedExpiry;

    @Option(names = "--owed-max-backoff", paramLabel = "DURATION", defaultValue = "PT30S",
            description = "the longest pause between tries to deliver to a home that does not answer (default ${DEFAULT-VALUE})")
    java.time.Duration owedMaxBackoff;

    @Option(names = "--call-timeout", paramLabel = "DURATION", defaultValue = "30s",
            description = "how long a call to another host may take, its connection included (default ${DEFAULT-VALUE}): a hop to a host that does not answer"
                    + " fails after this long and the agent's itinerary decides what next (retry, skip, go home)")
    java.time.Duration callTimeout;

    @Option(names = "--record", paramLabel = "FILE.mcap", description = "record this host's agents (arrivals, stops, reports, results) and its robot (commands, pose, sensors) into an MCAP file")
    Path record;

    @Mixin
    ClusterOptions cluster;

    @Mixin
    BeaconOption beacon;

    @Mixin
    FoxgloveOption foxglove;

    @Mixin
    RosBridgeOption rosbridge;

    @Spec
    CommandSpec spec;

    @Override
    public Integer call() throws Exception {
        PrintWriter out = spec.commandLine().getOut();
        PrintWriter err = spec.commandLine().getErr();
        List<AutoCloseable> open = new ArrayList<>();
        Robot robot = null;
        io.robomw.console.Console console = null;
        Simulation sim = null;
        try {
            if (world != null) {
                if (worldRobot == null) {
                    err.println("--world needs --world-robot NAME: which of its robots agents drive");
                    return 2;
                }
                sim = Simulation.load(world);
                open.add(0, sim);
                sim.startRealTime(speed);
                robot = sim.robot(worldRobot);
            } else if (robotFile != null) {
                AwaitedFile.await(robotFile, spec, "mw host");
                PlatformServices services = connection.isEmpty() ? PlatformServices.none()
                        : PlatformServices.none().with(ConnectionOverride.class, new ConnectionOverride(connection));
                robot = Robots.open(robotFile, services);
                open.add(0, robot);
            }
            if (serve != null && robot == null) {
                err.println("--serve needs a robot (--robot or --world)");
                return 2;
            }
            if (noWire && wirePort != 0) {
                err.println("--wire-port and --no-wire contradict each other; give one");
                return 2;
            }
            if (wirePort < 0 || wirePort > 65535) {
                err.println("--wire-port " + wirePort + " is not a TCP port (0-65535)");
                return 2;
            }
            if (noMessaging && messaging != null) {
                err.println("--messaging and --no-messaging contradict each other; give one");
                return 2;
            }
            if (record != null || foxglove.on()) {
                console = foxglove.apply(io.robomw.console.Console.builder("mw " + String.join(" ", spec.commandLine().getParseResult().originalArgs()))
                        .noPage().record(record).clusterKey(cluster.key(), cluster.tls() != null).simulation(sim)).start();
                if (robot != null) {
                    console.watchRobot(robot, robotFile != null ? robotFile.toString() : world + " (" + worldRobot + ")");
                    robot = console.recordCommands(robot);
                }
            }
            String servePassword = serve == null ? null : Secrets.read(servePasswordFile, "--serve-password-file", Secrets.SERVE_PASSWORD_ENV).orElse(null);
            boolean serveOverTls = serve != null && cluster.tls() != null && (serve.startsWith("tcp://") || serve.startsWith("rmi://"));
            if (serve != null && servePassword == null && !serveOverTls && !serveInsecure) {
                err.println("mw host: --serve " + serve + " would let anyone who reaches it drive robot " + robot.name() + ": give --serve-password-file"
                        + " FILE (or " + Secrets.SERVE_PASSWORD_ENV + "), serve over mutual TLS (--tls-keystore, a tcp:// or rmi:// address),"
                        + " or --serve-insecure for a lab network that wants it (docs/security.md)");
                closeAll(open);
                return 2;
            }
            if (serve != null && serveInsecure && servePassword != null) {
                err.println("mw host: --serve-insecure and a serve password contradict each other; give one");
                closeAll(open);
                return 2;
            }
            if (callTimeout.compareTo(java.time.Duration.ofMillis(100)) < 0) {
                err.println("--call-timeout " + Durations.format(callTimeout) + " is too short: a call to another host needs at least 100ms");
                closeAll(open);
                return 2;
            }
            rmiHostName(bind);
            MessagingSettings settings = serve == null ? MessagingSettings.defaults() : RobotProtocol.forServer(MessagingSettings.defaults());
            settings = settings.withLimits(settings.limits().withMaxConnections(maxConnections));
            if (serveOverTls && servePassword == null && !serveInsecure) {
                // the served robot's callers prove themselves with their certificates: the node takes only mutual TLS
                settings = settings.withTls(cluster.tls());
            }
            AgentHostBuilder builder = AgentHost.builder(name).bind(bind).port(port).robot(robot).clusterKey(cluster.key()).tls(cluster.tls())
                    .store(store).allow(allow).messagingSettings(settings).callTimeout(callTimeout)
                    .deliveryPolicy(io.robomw.agents.host.DeliveryPolicy.defaults().withExpiry(owedExpiry).withMaxBackoff(owedMaxBackoff));
            builder.wire(!noWire).wirePort(wirePort);
            if (olderHosts) {
                builder.olderHosts();
            }
            if (noMessaging) {
                builder.noMessaging();
            } else if (messaging != null) {
                builder.messaging(messaging);
            }
            AgentHost host = builder.start();
            open.add(0, host);
            if (console != null) {
                console.watchHost(host.address());
                open.add(0, console);
                console.recording().ifPresent(f -> out.printf("recording to %s%n", f));
                console.foxgloveAddress().ifPresent(a -> out.printf("foxglove at %s%n", a));
            }
            String served = null;
            MessagingNode servingNode = null;
            if (serve != null) {
                MessagingNode node = host.messagingNode().orElse(null);
                if (node == null) {
                    node = MessagingNode.builder(name + "-robot").settings(settings).build();
                    open.add(0, node);
                }
                servingNode = node;
                served = node.bind(serve) + "/" + robot.name();
                if (serveInsecure) {
                    err.println("mw host: WARNING: robot " + robot.name() + " is served at " + served + " WITHOUT A PASSWORD (--serve-insecure):"
                            + " anyone who can reach that address can drive it");
                    err.flush();
                    open.add(0, RobotServer.serveInsecure(node, robot));
                } else {
                    open.add(0, RobotServer.serve(node, robot, servePassword));
                }
            }
            MessagingNode presenceNode = host.messagingNode().orElse(servingNode);
            boolean atBroker = host.messagingAddresses().stream().anyMatch(m -> m.startsWith("mqtt"));
            if (announce != null || atBroker) {
                ClusterKey key = cluster.key();
                open.add(0, HostPresence.start(host, announce, presenceNode, key == null ? null : key.presenceSeal()));
            }
            if (presenceNode != null) {
                open.add(0, beacon.announce(presenceNode));
            }
            if (rosbridge.wanted()) {
                if (robot == null) {
                    err.println("--rosbridge needs a robot (--robot or --world)");
                    closeAll(open);
                    return 2;
                }
                io.robomw.console.rosbridge.BridgedRobot bridged = sim != null
                        ? io.robomw.console.rosbridge.BridgedRobot.simulated(robot, sim.world().robot(worldRobot))
                        : io.robomw.console.rosbridge.BridgedRobot.described(robot, new io.robomw.config.description.RobotDescriptionLoader().load(robotFile));
                open.add(0, rosbridge.start(java.util.List.of(bridged), host.messagingNode().orElse(servingNode), out));
            }
            out.printf("agent host %s ready at %s (robot: %s, store: %s)%n", name, host.address(), robot == null ? "none" : robot.name(),
                    store == null ? "memory" : store);
            out.printf("agent wire at %s%n", host.wirePort() == 0 ? "none (--no-wire; agents hop over RMI)" : bind + ":" + host.wirePort());
            out.printf("messaging at %s%n", host.messagingAddresses().isEmpty() ? "none (--no-messaging)" : String.join(" ", host.messagingAddresses()));
            if (served != null) {
                out.printf("robot %s served at %s%n", robot.name(), served);
            }
            out.flush();
            CountDownLatch stopped = new CountDownLatch(1);
            Thread closer = new Thread(() -> {
                closeAll(open);
                stopped.countDown();
            }, "mw-host-shutdown");
            Runtime.getRuntime().addShutdownHook(closer);
            stopped.await();
            return 0;
        } catch (RobotException | IllegalArgumentException | IllegalStateException | java.io.IOException e) {
            err.println("mw host: " + e.getMessage());
            err.flush();
            if (console != null && !open.contains(console)) {
                console.close();
            }
            closeAll(open);
            return 2;
        }
    }

    /**
     * RMI stubs carry the exporting machine's name (its first address, often 127.0.0.1 in a
     * container or namespace) unless {@code java.rmi.server.hostname} says otherwise; RMI names
     * that in its errors. One host per JVM here: its stubs carry its bind address, unless the
     * property was given ({@code MW_JAVA_OPTS}) or the host binds every interface.
     */
    private static void rmiHostName(String bind) {
        if (System.getProperty("java.rmi.server.hostname") == null && !bind.equals("0.0.0.0") && !bind.equals("::")) {
            System.setProperty("java.rmi.server.hostname", bind);
        }
    }

    private static void closeAll(List<AutoCloseable> open) {
        for (AutoCloseable c : open) {
            try {
                c.close();
            } catch (Exception e) {
                System.err.println("mw host: closing " + c + " failed: " + e);
            }
        }
        open.clear();
    }
}
