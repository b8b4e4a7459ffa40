package io.robomw.cli;

import io.robomw.agents.messaging.MessagingNode;
import io.robomw.api.Messaging;
import io.robomw.api.Robot;
import io.robomw.api.Robots;
import io.robomw.config.description.RobotDescriptionLoader;
import io.robomw.console.rosbridge.BridgedRobot;
import io.robomw.console.rosbridge.Rates;
import io.robomw.console.rosbridge.RosBridge;
import io.robomw.console.rosbridge.protocol.Limits;
import picocli.CommandLine.Command;
import picocli.CommandLine.Model.CommandSpec;
import picocli.CommandLine.Option;
import picocli.CommandLine.Parameters;
import picocli.CommandLine.Spec;

import java.io.PrintWriter;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.Callable;
import java.util.concurrent.CountDownLatch;

/**
 * {@code mw rosbridge ROBOT...}: a rosbridge v2 endpoint (docs/ros2.md) for robots served by
 * other processes ({@code tcp://127.0.0.1:7000/nxt}, as {@code mw host --serve} prints it) or
 * opened here from their files, until Ctrl-C. Prints {@code rosbridge at ws://...} once it serves.
 */
@Command(name = "rosbridge", mixinStandardHelpOptions = true, sortOptions = false,
        description = {"Serve robots to ROS 2 clients (roslibpy, roslibjs, a ROS 2 machine's rosbridge client) as a rosbridge v2 endpoint: "
                + "/ROBOT/odom, /ROBOT/cmd_vel, Range topics, /tf, services, rosapi. No ROS installation needed (docs/ros2.md).",
                "Example: mw rosbridge tcp://127.0.0.1:7000/nxt    then in Python: roslibpy.Ros('127.0.0.1', 9090)"})
final class RosbridgeCommand implements Callable<Integer> {

    @Parameters(arity = "1..*", paramLabel = "ROBOT", description = "a served robot's address (tcp://HOST:PORT/NAME, mqtt://BROKER/NAME...) or a robot file")
    List<String> targets;

    @Option(names = "--port", defaultValue = "" + RosBridge.DEFAULT_PORT, description = "the port (default ${DEFAULT-VALUE}, rosbridge's; 0 picks a free one)")
    int port;

    @Option(names = "--bind", paramLabel = "ADDRESS", defaultValue = "127.0.0.1",
            description = "where to listen (default ${DEFAULT-VALUE}: this machine only; another address needs --token-file or " + RosBridge.TOKEN_ENV + ")")
    String bind;

    @Option(names = "--token-file", paramLabel = "FILE",
            description = "file holding the access token clients must give (ws://HOST:PORT/?token=TOKEN); default: the " + RosBridge.TOKEN_ENV + " environment variable, else none")
    Path tokenFile;

    @Option(names = "--allow-origin", paramLabel = "ORIGIN", description = "a web origin whose pages may connect besides this machine's (https://dashboard.example.org; * for any)")
    List<String> origins = new ArrayList<>();

    @Option(names = "--odom-rate", paramLabel = "HZ", defaultValue = "20", description = "odometry and /tf messages per second (default ${DEFAULT-VALUE})")
    double odometryHz;

    @Option(names = "--sensor-rate", paramLabel = "HZ", defaultValue = "0",
            description = "range and joint readings per second (default: each sensor's rate_hz in its robot file, else 10)")
    double sensorHz;

    @Option(names = "--messaging", paramLabel = "ADDRESS",
            description = "bridge RoboMW topics (/robomw/T) through a node connected here (tcp://HOST:PORT, mqtt://BROKER); default: the first remote robot's node, connected to its host")
    String messaging;

    @Option(names = "--max-connections", paramLabel = "N", defaultValue = "64", description = "clients at once (default ${DEFAULT-VALUE})")
    int maxConnections;

    @Option(names = "--max-message-size", paramLabel = "BYTES", defaultValue = "10000000", description = "largest message a client may send (default ${DEFAULT-VALUE}, rosbridge's)")
    int maxMessageBytes;

    @Spec
    CommandSpec spec;

    @Override
    public Integer call() throws Exception {
        PrintWriter out = spec.commandLine().getOut();
        List<AutoCloseable> open = new ArrayList<>();
        String token = RosBridgeOption.token(tokenFile);
        io.robomw.console.rosbridge.server.RosBridgeServer.checkAccess(bind, token); // before any robot is opened
        try {
            List<BridgedRobot> robots = new ArrayList<>();
            Messaging node = null;
            for (String t : targets) {
                if (t.contains("://")) {
                    Robot r = Robots.remote(t);
                    open.add(0, r);
                    robots.add(BridgedRobot.remote(r));
                    if (node == null) {
                        node = r.messaging();
                    }
                } else {
                    Path file = Path.of(t);
                    if (!Files.isRegularFile(file)) {
                        throw new IllegalArgumentException("no robot file " + t + ", and it is no address (tcp://HOST:PORT/NAME)");
                    }
                    Robot r = Robots.open(file);
                    open.add(0, r);
                    robots.add(BridgedRobot.described(r, new RobotDescriptionLoader().load(file)));
                }
            }
            if (messaging != null) {
                MessagingNode m = MessagingNode.builder("rosbridge").connect(messaging).build();
                open.add(0, m);
                node = m;
            }
            RosBridge.Builder b = RosBridge.builder().listen(bind, port).token(token).rates(new Rates(odometryHz, sensorHz))
                    .limits(Limits.DEFAULTS.withMaxConnections(maxConnections).withMaxMessageBytes(maxMessageBytes)).messaging(node);
            origins.forEach(b::allowOrigin);
            robots.forEach(b::robot);
            RosBridge bridge = b.start();
            open.add(0, bridge);
            out.println("rosbridge at " + bridge.address() + " (" + RosBridgeOption.describe(bridge.namespaces()) + ")");
            out.flush();
            CountDownLatch stopped = new CountDownLatch(1);
            Runtime.getRuntime().addShutdownHook(new Thread(() -> {
                closeAll(open);
                stopped.countDown();
            }, "mw-rosbridge-shutdown"));
            stopped.await();
            return 0;
        } catch (RuntimeException | java.io.IOException e) {
            closeAll(open);
            throw e;
        }
    }

    private static void closeAll(List<AutoCloseable> open) {
        for (AutoCloseable c : open) {
            try {
                c.close();
            } catch (Exception e) {
                System.err.println("mw rosbridge: closing " + c + " failed: " + e);
            }
        }
        open.clear();
    }
}
