package io.robomw.cli;

import io.robomw.api.Messaging;
import io.robomw.console.rosbridge.BridgedRobot;
import io.robomw.console.rosbridge.RosBridge;
import picocli.CommandLine.Option;

import java.io.IOException;
import java.io.PrintWriter;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.List;
import java.util.Map;
import java.util.stream.Collectors;

/**
 * {@code --rosbridge [PORT]} on {@code mw sim}, {@code mw host} and {@code mw demo}: also serve the
 * command's robots to ROS 2 clients as a rosbridge v2 endpoint (docs/ros2.md), with the options
 * {@code mw rosbridge} has for where it listens and its token.
 */
final class RosBridgeOption {

    @Option(names = "--rosbridge", arity = "0..1", fallbackValue = "" + RosBridge.DEFAULT_PORT, paramLabel = "PORT",
            description = "also serve the robots to ROS 2 clients (roslibpy, roslibjs) as a rosbridge v2 endpoint on PORT (9090 if no port is given; 0: a free one); docs/ros2.md")
    Integer port;

    @Option(names = "--rosbridge-bind", paramLabel = "ADDRESS", defaultValue = "127.0.0.1",
            description = "where the rosbridge listens (default ${DEFAULT-VALUE}: this machine only; another address needs --rosbridge-token-file or " + RosBridge.TOKEN_ENV + ")")
    String bind;

    @Option(names = "--rosbridge-token-file", paramLabel = "FILE",
            description = "file holding the access token rosbridge clients must give (ws://HOST:PORT/?token=TOKEN); default: the " + RosBridge.TOKEN_ENV + " environment variable, else none")
    Path tokenFile;

    @Option(names = "--rosbridge-odom-rate", paramLabel = "HZ", defaultValue = "20", description = "odometry and /tf messages per second (default ${DEFAULT-VALUE})")
    double odometryHz;

    /** @return whether {@code --rosbridge} was given */
    boolean wanted() {
        return port != null;
    }

    /**
     * Starts the endpoint and prints its address.
     *
     * @param robots    the robots
     * @param messaging the node RoboMW topics are bridged through, or {@code null}
     * @param out       where the address is printed
     * @return the running endpoint
     * @throws IOException if the port cannot be used or the token file cannot be read
     */
    RosBridge start(List<BridgedRobot> robots, Messaging messaging, PrintWriter out) throws IOException {
        RosBridge.Builder b = RosBridge.builder().listen(bind, port).token(token(tokenFile))
                .rates(new io.robomw.console.rosbridge.Rates(odometryHz, 0)).messaging(messaging);
        robots.forEach(b::robot);
        RosBridge bridge = b.start();
        out.println("rosbridge at " + bridge.address() + " (" + describe(bridge.namespaces()) + ")");
        out.flush();
        return bridge;
    }

    /**
     * @param file a token file, or {@code null}
     * @return the token: the file's first line, else the environment's {@value RosBridge#TOKEN_ENV}, else {@code null}
     * @throws IOException if the file cannot be read
     */
    static String token(Path file) throws IOException {
        if (file != null) {
            String t = Files.readString(file, StandardCharsets.UTF_8).lines().findFirst().orElse("").strip();
            if (t.isEmpty()) {
                throw new IOException("rosbridge token file " + file + " is empty");
            }
            return t;
        }
        String env = System.getenv(RosBridge.TOKEN_ENV);
        return env == null || env.isBlank() ? null : env.strip();
    }

    /**
     * @param namespaces each robot's namespace by name
     * @return {@code robots: nxt-1 as /nxt_1, ft as /ft}
     */
    static String describe(Map<String, String> namespaces) {
        if (namespaces.isEmpty()) {
            return "no robots";
        }
        return "robots: " + namespaces.entrySet().stream().map(e -> e.getKey().equals(e.getValue()) ? "/" + e.getValue() : e.getKey() + " as /" + e.getValue())
                .collect(Collectors.joining(", "));
    }
}
