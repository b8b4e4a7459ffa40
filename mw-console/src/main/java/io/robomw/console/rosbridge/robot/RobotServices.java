package io.robomw.console.rosbridge.robot;

import com.fasterxml.jackson.databind.JsonNode;
import com.fasterxml.jackson.databind.node.ArrayNode;
import com.fasterxml.jackson.databind.node.JsonNodeFactory;
import com.fasterxml.jackson.databind.node.ObjectNode;
import io.robomw.api.Capability;
import io.robomw.api.Futures;
import io.robomw.api.Position;
import io.robomw.api.Quantity;
import io.robomw.api.ReturnType;
import io.robomw.api.Robot;
import io.robomw.api.SensorInfo;
import io.robomw.api.SensorType;
import io.robomw.console.rosbridge.graph.Graph;
import io.robomw.console.rosbridge.graph.Service;
import io.robomw.console.rosbridge.graph.ServiceHandler;
import io.robomw.console.rosbridge.graph.Topic;
import io.robomw.console.rosbridge.msg.TypeName;

import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.Locale;
import java.util.concurrent.CancellationException;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.CompletionException;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.TimeoutException;
import java.util.function.Supplier;

/**
 * The rest of a robot's Instruction Layer as services of its node, with RoboMW's service types
 * ({@code robomw_msgs/srv/*}, defined in docs/ros2.md):
 *
 * <table>
 *   <caption>a robot's services</caption>
 *   <tr><th>service</th><th>type</th><th>does</th></tr>
 *   <tr><td>{@code /<ns>/move}</td><td>{@code robomw_msgs/srv/Move}</td><td>{@code robot.move(distance, speed)}</td></tr>
 *   <tr><td>{@code /<ns>/turn}</td><td>{@code robomw_msgs/srv/Turn}</td><td>{@code robot.turn(angle, speed)}</td></tr>
 *   <tr><td>{@code /<ns>/arc}</td><td>{@code robomw_msgs/srv/Arc}</td><td>{@code robot.arc(radius, angle, speed)}</td></tr>
 *   <tr><td>{@code /<ns>/stop}</td><td>{@code std_srvs/srv/Trigger}</td><td>{@code robot.stop()}</td></tr>
 *   <tr><td>{@code /<ns>/perform}</td><td>{@code robomw_msgs/srv/Perform}</td><td>{@code robot.perform(action, args...)}</td></tr>
 *   <tr><td>{@code /<ns>/read_sensor}</td><td>{@code robomw_msgs/srv/ReadSensor}</td><td>{@code robot.getValue(...)}, by name or by position and type</td></tr>
 *   <tr><td>{@code /<ns>/describe}</td><td>{@code robomw_msgs/srv/Describe}</td><td>the robot's capabilities, sensors, actions, topics and services</td></tr>
 *   <tr><td>{@code /<ns>/change_altitude}</td><td>{@code robomw_msgs/srv/ChangeAltitude}</td><td>{@code robot.changeAltitude(metres, speed)}, robots that fly only</td></tr>
 * </table>
 *
 * <p>A call is answered when the robot has done it (a move once the robot has covered the
 * distance), with {@code success: true}; a robot that refuses ({@code UnsupportedActionException}:
 * too fast, no such action), a newer command that interrupts it, a link that fails, or a motion
 * that runs past its deadline (three times its duration plus 10 s, as {@code Motion}'s blocking
 * forms wait) answer {@code success: false} with the reason in {@code message}. A motion whose
 * deadline passes is cancelled: its motors brake. Arguments that do not fit the request type
 * never reach the robot: the client gets {@code result: false} ({@link io.robomw.console.rosbridge.protocol.ClientSession}).
 */
public final class RobotServices {

    private static final JsonNodeFactory NODES = JsonNodeFactory.instance;

    private final RobotNode node;
    private final Robot robot;
    private final Graph graph;
    private final Threads threads;
    private final List<String> names = new ArrayList<>();

    private RobotServices(RobotNode node, Graph graph, Threads threads) {
        this.node = node;
        this.robot = node.robot().robot();
        this.graph = graph;
        this.threads = threads;
    }

    /**
     * Offers a robot's services in the graph.
     *
     * @param node    the robot's node
     * @param graph   the graph
     * @param threads where blocking calls (stop) run
     */
    public static void offer(RobotNode node, Graph graph, Threads threads) {
        RobotServices s = new RobotServices(node, graph, threads);
        s.add("move", "robomw_msgs", "Move", req -> {
            double d = req.get("distance").doubleValue();
            double v = req.get("speed").doubleValue();
            return s.motion(String.format(Locale.ROOT, "move(%.3f m, %.3f m/s)", d, v), () -> s.robot.moveAsync(d, v), Math.abs(d) / v);
        });
        s.add("turn", "robomw_msgs", "Turn", req -> {
            double a = req.get("angle").doubleValue();
            double v = req.get("speed").doubleValue();
            return s.motion(String.format(Locale.ROOT, "turn(%.3f rad, %.3f rad/s)", a, v), () -> s.robot.turnAsync(a, v), Math.abs(a) / v);
        });
        s.add("arc", "robomw_msgs", "Arc", req -> {
            double r = req.get("radius").doubleValue();
            double a = req.get("angle").doubleValue();
            double v = req.get("speed").doubleValue();
            return s.motion(String.format(Locale.ROOT, "arc(%.3f m, %.3f rad, %.3f m/s)", r, a, v), () -> s.robot.arcAsync(r, a, v),
                    Math.abs(r * a) / v);
        });
        if (s.robot.can(Capability.AIR)) {
            s.add("change_altitude", "robomw_msgs", "ChangeAltitude", req -> {
                double m = req.get("metres").doubleValue();
                double v = req.get("speed").doubleValue();
                return s.motion(String.format(Locale.ROOT, "changeAltitude(%.3f m, %.3f m/s)", m, v), () -> s.robot.changeAltitudeAsync(m, v),
                        Math.abs(m) / v);
            });
        }
        s.add("stop", "std_srvs", "Trigger", req -> CompletableFuture.supplyAsync(() -> {
            try {
                s.robot.stop();
                return result(true, "stopped");
            } catch (RuntimeException e) {
                return result(false, "stop failed: " + e.getMessage());
            }
        }, threads.blocking()));
        s.add("perform", "robomw_msgs", "Perform", req -> {
            String action = req.get("action").asText();
            double[] args = doubles(req.get("args"));
            return s.motion("perform(\"" + action + "\")", () -> s.robot.performAsync(action, args), Double.NaN);
        });
        s.add("read_sensor", "robomw_msgs", "ReadSensor", s::readSensor);
        s.add("describe", "robomw_msgs", "Describe", req -> CompletableFuture.completedFuture(s.describe()));
    }

    private void add(String name, String pkg, String type, ServiceHandler handler) {
        String full = node.node() + "/" + name;
        graph.addService(new Service(full, graph.interfaces().service(new TypeName(pkg, TypeName.Kind.SRV, type))
                .orElseThrow(() -> new IllegalStateException("the bridge's interfaces lack " + pkg + "/srv/" + type)), node.node(), handler));
        names.add(full);
    }

    /** A motion: answered when it completes, or fails, or runs past its deadline (then cancelled: its motors brake). */
    private CompletableFuture<ObjectNode> motion(String what, Supplier<CompletableFuture<Void>> start, double seconds) {
        CompletableFuture<Void> running;
        try {
            running = start.get();
        } catch (RuntimeException e) {
            return CompletableFuture.completedFuture(result(false, what + " refused: " + e.getMessage()));
        }
        Duration deadline = Double.isNaN(seconds) ? Futures.DEFAULT_TIMEOUT : Futures.motionTimeout(seconds);
        return running.copy().orTimeout(deadline.toMillis(), TimeUnit.MILLISECONDS).handle((v, e) -> {
            if (e == null) {
                return result(true, what + " done");
            }
            Throwable cause = e instanceof CompletionException && e.getCause() != null ? e.getCause() : e;
            if (cause instanceof TimeoutException) {
                running.cancel(true);
                return result(false, what + " did not finish within " + deadline.toSeconds() + " s; cancelled (its motors brake)");
            }
            if (cause instanceof CancellationException) {
                return result(false, what + " was cancelled");
            }
            return result(false, what + " failed: " + cause.getMessage());
        });
    }

    private CompletableFuture<ObjectNode> readSensor(ObjectNode req) {
        String sensor = req.get("sensor").asText();
        String unitText = req.get("unit").asText();
        CompletableFuture<Double> reading;
        String what;
        ReturnType unit;
        try {
            if (!sensor.isEmpty()) {
                SensorInfo info = robot.sensors().stream().filter(s -> s.name().equals(sensor)).findFirst()
                        .orElseThrow(() -> new IllegalArgumentException("robot '" + robot.name() + "' has no sensor '" + sensor + "'; it has "
                                + robot.sensors().stream().map(SensorInfo::name).toList()));
                unit = unitText.isEmpty() ? siUnit(info.type().quantity()) : constant(ReturnType.class, "unit", unitText);
                what = "getValue(\"" + sensor + "\", " + unit + ")";
                reading = robot.getValueAsync(sensor, unit);
            } else {
                Position position = constant(Position.class, "position", req.get("position").asText());
                SensorType type = constant(SensorType.class, "type", req.get("type").asText());
                unit = unitText.isEmpty() ? siUnit(type.quantity()) : constant(ReturnType.class, "unit", unitText);
                what = "getValue(" + position + ", " + type + ", " + unit + ")";
                reading = robot.getValueAsync(position, type, unit);
            }
        } catch (RuntimeException e) {
            ObjectNode r = result(false, "read_sensor refused: " + e.getMessage());
            r.put("value", 0.0);
            return CompletableFuture.completedFuture(r);
        }
        return reading.copy().orTimeout(Futures.DEFAULT_TIMEOUT.toMillis(), TimeUnit.MILLISECONDS).handle((v, e) -> {
            ObjectNode r;
            if (e == null) {
                r = result(true, what + " read in " + unit);
                r.put("value", v);
            } else {
                Throwable cause = e instanceof CompletionException && e.getCause() != null ? e.getCause() : e;
                r = result(false, what + " failed: " + (cause instanceof TimeoutException ? "no reading within " + Futures.DEFAULT_TIMEOUT.toSeconds() + " s"
                        : cause.getMessage()));
                r.put("value", 0.0);
            }
            return r;
        });
    }

    private ObjectNode describe() {
        ObjectNode r = NODES.objectNode();
        r.put("name", robot.name());
        ArrayNode caps = r.putArray("capabilities");
        robot.capabilities().stream().map(Enum::name).sorted().forEach(caps::add);
        ArrayNode sensorNames = r.putArray("sensor_names");
        ArrayNode sensorTypes = r.putArray("sensor_types");
        ArrayNode sensorPositions = r.putArray("sensor_positions");
        for (SensorInfo s : robot.sensors()) {
            sensorNames.add(s.name());
            sensorTypes.add(s.type().name());
            sensorPositions.add(s.position().name());
        }
        ArrayNode actions = r.putArray("actions");
        robot.actions().forEach(actions::add);
        ArrayNode topics = r.putArray("topics");
        graph.topics().stream().map(Topic::name).filter(t -> t.startsWith(node.node() + "/")).forEach(topics::add);
        ArrayNode services = r.putArray("services");
        names.forEach(services::add);
        return r;
    }

    private static ReturnType siUnit(Quantity q) {
        return switch (q) {
            case DISTANCE -> ReturnType.METERS;
            case ANGLE -> ReturnType.RADIANS;
            case ANGULAR_RATE -> ReturnType.RADIANS_PER_SECOND;
            case ACCELERATION -> ReturnType.METERS_PER_SECOND_SQUARED;
            case RATIO -> ReturnType.PERCENT;
            case PRESENCE -> ReturnType.BOOLEAN;
            case SOUND_LEVEL -> ReturnType.DECIBELS;
            case COLOR_ID -> ReturnType.COLOR_ID;
        };
    }

    private static <E extends Enum<E>> E constant(Class<E> type, String field, String text) {
        try {
            return Enum.valueOf(type, text.trim().toUpperCase(Locale.ROOT));
        } catch (IllegalArgumentException e) {
            List<String> names = java.util.Arrays.stream(type.getEnumConstants()).map(Enum::name).toList();
            throw new IllegalArgumentException(field + " '" + text + "' is not one of " + names);
        }
    }

    private static double[] doubles(JsonNode sequence) {
        if (sequence instanceof com.fasterxml.jackson.databind.node.POJONode p && p.getPojo() instanceof io.robomw.console.rosbridge.msg.NumberSequence n) {
            return n.floats().clone();
        }
        return new double[0];
    }

    private static ObjectNode result(boolean success, String message) {
        ObjectNode r = NODES.objectNode();
        r.put("success", success);
        r.put("message", message);
        return r;
    }
}
