package io.robomw.console.record;

import com.fasterxml.jackson.core.JsonProcessingException;
import com.fasterxml.jackson.databind.JsonNode;
import com.fasterxml.jackson.databind.ObjectMapper;
import com.fasterxml.jackson.databind.node.ArrayNode;
import com.fasterxml.jackson.databind.node.ObjectNode;
import io.robomw.console.observe.HostView;
import io.robomw.console.observe.Observation;
import io.robomw.console.observe.WorldMap;

import java.io.IOException;
import java.util.ArrayList;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Map;

/**
 * How observations become MCAP messages (JSON, one channel per topic) and back. Topics, and the
 * schema each carries:
 *
 * <table>
 *   <caption>recording topics</caption>
 *   <tr><th>topic</th><th>schema</th><th>what</th></tr>
 *   <tr><td>/world</td><td>robomw.WorldMap</td><td>the arena, once</td></tr>
 *   <tr><td>/world/scene</td><td>foxglove.SceneUpdate</td><td>walls and obstacles for Foxglove's 3D panel, once</td></tr>
 *   <tr><td>/robots/R/pose</td><td>foxglove.PoseInFrame</td><td>the simulator's true pose, frame "world"</td></tr>
 *   <tr><td>/robots/R/odometry</td><td>foxglove.PoseInFrame</td><td>the robot's own estimate, frame "world"</td></tr>
 *   <tr><td>/tf</td><td>foxglove.FrameTransform</td><td>world to each robot's frame R, for the 3D panel</td></tr>
 *   <tr><td>/robots/R/sensors/S</td><td>robomw.SensorReading</td><td>one value (plot {@code .value})</td></tr>
 *   <tr><td>/robots/R/commands</td><td>robomw.RobotCommand</td><td>commands as they were given</td></tr>
 *   <tr><td>/robots/R/status</td><td>robomw.RobotStatus</td><td>whether a watched robot answered</td></tr>
 *   <tr><td>/hosts/H</td><td>robomw.HostView</td><td>an agent host, its agents and itineraries</td></tr>
 *   <tr><td>/agents/events</td><td>robomw.AgentEvent</td><td>arrivals, stops, reports, results...</td></tr>
 *   <tr><td>/agents/log</td><td>foxglove.Log</td><td>the same, as lines for the Log panel</td></tr>
 *   <tr><td>/topics/T</td><td>robomw.TopicMessage</td><td>messages seen on messaging topic T</td></tr>
 * </table>
 *
 * Times in messages are {@code {sec, nsec}} since the Unix epoch, as the MCAP log times.
 *
 * <p>The one definition of these topics, schemas and messages: a recording ({@link McapRecorder})
 * and the live Foxglove WebSocket ({@code io.robomw.console.foxglove}) both encode through
 * {@link #encode}, with the schemas {@link Schemas} holds, so a Foxglove layout made for one shows
 * the other. Stateless and thread-safe.
 */
public final class RecordingCodec {

    static final String WORLD = "/world";
    static final String SCENE = "/world/scene";
    static final String TF = "/tf";
    static final String AGENT_EVENTS = "/agents/events";
    static final String AGENT_LOG = "/agents/log";
    private static final ObjectMapper JSON = new ObjectMapper();

    /**
     * One message to write or send: its topic, its schema's name ({@link Schemas#json} has the
     * schema) and its JSON.
     *
     * @param topic  the channel's topic, {@code /robots/nxt/pose}
     * @param schema the schema's name, {@code foxglove.PoseInFrame}
     * @param json   the message, UTF-8 JSON
     */
    public record Out(String topic, String schema, byte[] json) {
    }

    private RecordingCodec() {
    }

    /**
     * @param o an observation
     * @return the messages it becomes (one or more; none for an observation nothing records),
     *         stamped with its time
     */
    public static List<Out> encode(Observation o) {
        List<Out> out = new ArrayList<>();
        long t = o.timeNanos();
        if (o instanceof Observation.Batch b) {
            b.all().forEach(x -> out.addAll(encode(x)));
        } else if (o instanceof Observation.World w) {
            ObjectNode n = stamped(t);
            n.set("map", JSON.valueToTree(w.map()));
            out.add(new Out(WORLD, "robomw.WorldMap", bytes(n)));
            out.add(new Out(SCENE, "foxglove.SceneUpdate", bytes(scene(t, w.map()))));
        } else if (o instanceof Observation.RobotPose p) {
            ObjectNode n = stamped(t);
            n.put("frame_id", "world");
            n.set("pose", pose(p.x(), p.y(), p.z(), p.heading()));
            out.add(new Out("/robots/" + p.robot() + (p.truth() ? "/pose" : "/odometry"), "foxglove.PoseInFrame", bytes(n)));
            if (p.truth()) {
                ObjectNode tf = stamped(t);
                tf.put("parent_frame_id", "world");
                tf.put("child_frame_id", p.robot());
                tf.set("translation", vector(p.x(), p.y(), p.z()));
                tf.set("rotation", quaternion(p.heading()));
                out.add(new Out(TF, "foxglove.FrameTransform", bytes(tf)));
            }
        } else if (o instanceof Observation.SensorReading s) {
            ObjectNode n = stamped(t);
            n.put("robot", s.robot());
            n.put("sensor", s.sensor());
            n.put("value", s.value());
            n.put("unit", s.unit());
            out.add(new Out("/robots/" + s.robot() + "/sensors/" + s.sensor(), "robomw.SensorReading", bytes(n)));
        } else if (o instanceof Observation.RobotCommand c) {
            ObjectNode n = stamped(t);
            n.put("robot", c.robot());
            n.put("verb", c.verb());
            ObjectNode args = n.putObject("args");
            c.args().forEach(args::put);
            out.add(new Out("/robots/" + c.robot() + "/commands", "robomw.RobotCommand", bytes(n)));
        } else if (o instanceof Observation.RobotStatus s) {
            ObjectNode n = stamped(t);
            n.put("robot", s.robot());
            n.put("source", s.source());
            n.put("reachable", s.reachable());
            n.put("detail", s.detail());
            out.add(new Out("/robots/" + s.robot() + "/status", "robomw.RobotStatus", bytes(n)));
        } else if (o instanceof Observation.HostSeen h) {
            ObjectNode n = JSON.valueToTree(h.host());
            n.set("timestamp", time(t));
            out.add(new Out("/hosts/" + h.host().name(), "robomw.HostView", bytes(n)));
        } else if (o instanceof Observation.AgentEvent e) {
            ObjectNode n = stamped(t);
            n.put("agent", e.agent());
            n.put("agentClass", e.agentClass());
            n.put("kind", e.kind());
            n.put("host", e.host());
            n.put("detail", e.detail());
            out.add(new Out(AGENT_EVENTS, "robomw.AgentEvent", bytes(n)));
            ObjectNode log = stamped(t);
            boolean bad = e.kind().equals("failed") || e.kind().equals("stop-failed") || e.kind().equals("disposed");
            log.put("level", bad ? 3 : 2);
            String cls = e.agentClass().substring(e.agentClass().lastIndexOf('.') + 1);
            log.put("message", e.kind() + " " + cls + " " + shortId(e.agent()) + " at " + e.host() + (e.detail().isEmpty() ? "" : ": " + e.detail()));
            log.put("name", "agents");
            log.put("file", "");
            log.put("line", 0);
            out.add(new Out(AGENT_LOG, "foxglove.Log", bytes(log)));
        } else if (o instanceof Observation.TopicMessage m) {
            ObjectNode n = stamped(t);
            n.put("topic", m.topic());
            n.put("text", m.text());
            out.add(new Out("/topics/" + m.topic(), "robomw.TopicMessage", bytes(n)));
        }
        return out;
    }

    /**
     * Reads a message back into an observation.
     *
     * @param topic    its channel's topic
     * @param schema   its schema's name
     * @param json     its bytes
     * @param logTime  its log time
     * @return the observation, or {@code null} for a message replays do not need (scene, transforms, log lines, foreign schemas)
     * @throws IOException if the message is not what its schema says
     */
    static Observation decode(String topic, String schema, byte[] json, long logTime) throws IOException {
        JsonNode n;
        try {
            n = JSON.readTree(json);
        } catch (JsonProcessingException e) {
            throw new IOException("message on " + topic + " is not JSON: " + e.getOriginalMessage());
        }
        if (n == null || !n.isObject()) {
            throw new IOException("message on " + topic + " is not a JSON object");
        }
        try {
            return switch (schema) {
                case "robomw.WorldMap" -> new Observation.World(logTime, JSON.treeToValue(require(n, "map", topic), WorldMap.class));
                case "foxglove.PoseInFrame" -> {
                    String robot = robotOf(topic);
                    if (robot == null) {
                        yield null;
                    }
                    JsonNode pose = require(n, "pose", topic);
                    JsonNode p = require(pose, "position", topic);
                    JsonNode q = require(pose, "orientation", topic);
                    double heading = 2 * Math.atan2(number(q, "z", topic), number(q, "w", topic));
                    // z: the altitude (recordings before vehicles wrote 0 there too)
                    yield new Observation.RobotPose(logTime, robot, number(p, "x", topic), number(p, "y", topic), number(p, "z", topic), heading,
                            topic.endsWith("/pose"));
                }
                case "robomw.SensorReading" -> new Observation.SensorReading(logTime, text(n, "robot", topic), text(n, "sensor", topic),
                        number(n, "value", topic), text(n, "unit", topic));
                case "robomw.RobotCommand" -> {
                    Map<String, Double> args = new LinkedHashMap<>();
                    JsonNode a = require(n, "args", topic);
                    a.fieldNames().forEachRemaining(k -> args.put(k, a.get(k).asDouble()));
                    yield new Observation.RobotCommand(logTime, text(n, "robot", topic), text(n, "verb", topic), args);
                }
                case "robomw.RobotStatus" -> new Observation.RobotStatus(logTime, text(n, "robot", topic), n.path("source").asText(""),
                        require(n, "reachable", topic).asBoolean(), n.path("detail").asText(""));
                case "robomw.HostView" -> {
                    ((ObjectNode) n).remove("timestamp");
                    yield new Observation.HostSeen(logTime, JSON.treeToValue(n, HostView.class));
                }
                case "robomw.AgentEvent" -> new Observation.AgentEvent(logTime, text(n, "agent", topic), n.path("agentClass").asText(""),
                        text(n, "kind", topic), text(n, "host", topic), n.path("detail").asText(""));
                case "robomw.TopicMessage" -> new Observation.TopicMessage(logTime, text(n, "topic", topic), text(n, "text", topic));
                default -> null;
            };
        } catch (JsonProcessingException e) {
            throw new IOException("message on " + topic + " does not fit " + schema + ": " + e.getOriginalMessage());
        }
    }

    private static String robotOf(String topic) {
        String[] parts = topic.split("/");
        return parts.length == 4 && parts[1].equals("robots") ? parts[2] : null;
    }

    private static JsonNode require(JsonNode n, String field, String topic) throws IOException {
        JsonNode v = n.get(field);
        if (v == null || v.isNull()) {
            throw new IOException("message on " + topic + " has no field '" + field + "'");
        }
        return v;
    }

    private static double number(JsonNode n, String field, String topic) throws IOException {
        JsonNode v = require(n, field, topic);
        if (!v.isNumber()) {
            throw new IOException("message on " + topic + ": field '" + field + "' must be a number, got " + v);
        }
        return v.asDouble();
    }

    private static String text(JsonNode n, String field, String topic) throws IOException {
        JsonNode v = require(n, field, topic);
        if (!v.isTextual()) {
            throw new IOException("message on " + topic + ": field '" + field + "' must be a string, got " + v);
        }
        return v.asText();
    }

    private static String shortId(String id) {
        return id.length() > 8 ? id.substring(0, 8) : id;
    }

    private static ObjectNode stamped(long t) {
        ObjectNode n = JSON.createObjectNode();
        n.set("timestamp", time(t));
        return n;
    }

    static ObjectNode time(long t) {
        ObjectNode n = JSON.createObjectNode();
        n.put("sec", Math.floorDiv(t, 1_000_000_000L));
        n.put("nsec", Math.floorMod(t, 1_000_000_000L));
        return n;
    }

    private static ObjectNode vector(double x, double y, double z) {
        ObjectNode n = JSON.createObjectNode();
        n.put("x", x);
        n.put("y", y);
        n.put("z", z);
        return n;
    }

    private static ObjectNode quaternion(double heading) {
        ObjectNode n = JSON.createObjectNode();
        n.put("x", 0.0);
        n.put("y", 0.0);
        n.put("z", Math.sin(heading / 2));
        n.put("w", Math.cos(heading / 2));
        return n;
    }

    private static ObjectNode pose(double x, double y, double heading) {
        return pose(x, y, 0, heading);
    }

    private static ObjectNode pose(double x, double y, double z, double heading) {
        ObjectNode n = JSON.createObjectNode();
        n.set("position", vector(x, y, z));
        n.set("orientation", quaternion(heading));
        return n;
    }

    private static ObjectNode color(double r, double g, double b, double a) {
        ObjectNode n = JSON.createObjectNode();
        n.put("r", r);
        n.put("g", g);
        n.put("b", b);
        n.put("a", a);
        return n;
    }

    /** The arena as cubes (floor, walls, boxes) and cylinders (discs); polygons as line strips, water areas as blue ones. */
    private static ObjectNode scene(long t, WorldMap w) {
        ObjectNode update = JSON.createObjectNode();
        update.putArray("deletions");
        ArrayNode entities = update.putArray("entities");
        ObjectNode e = entities.addObject();
        e.set("timestamp", time(t));
        e.put("frame_id", "world");
        e.put("id", "arena");
        e.set("lifetime", time(0));
        e.put("frame_locked", false);
        e.putArray("metadata");
        e.putArray("arrows");
        ArrayNode cubes = e.putArray("cubes");
        e.putArray("spheres");
        ArrayNode cylinders = e.putArray("cylinders");
        ArrayNode lines = e.putArray("lines");
        e.putArray("triangles");
        e.putArray("texts");
        e.putArray("models");
        cubes.add(cube(w.width() / 2, w.height() / 2, -0.005, 0, w.width(), w.height(), 0.01, color(w.floorBrightness(), w.floorBrightness(), w.floorBrightness(), 1)));
        if (w.walls()) {
            double th = w.wallThickness();
            ObjectNode wall = color(0.35, 0.38, 0.42, 1);
            cubes.add(cube(w.width() / 2, -th / 2, 0.05, 0, w.width() + 2 * th, th, 0.1, wall));
            cubes.add(cube(w.width() / 2, w.height() + th / 2, 0.05, 0, w.width() + 2 * th, th, 0.1, wall));
            cubes.add(cube(-th / 2, w.height() / 2, 0.05, 0, th, w.height(), 0.1, wall));
            cubes.add(cube(w.width() + th / 2, w.height() / 2, 0.05, 0, th, w.height(), 0.1, wall));
        }
        for (List<double[]> area : w.water()) {
            lines.add(loop(area, 0.006, 0.05, color(0.35, 0.58, 0.77, 1)));
        }
        ObjectNode grey = color(0.55, 0.59, 0.64, 1);
        for (WorldMap.Shape s : w.obstacles()) {
            switch (s.kind()) {
                case "box" -> cubes.add(cube(s.x(), s.y(), 0.1, s.angle(), s.width(), s.height(), 0.2, grey));
                case "circle" -> {
                    ObjectNode c = cylinders.addObject();
                    c.set("pose", pose(s.x(), s.y(), 0));
                    ((ObjectNode) c.get("pose").get("position")).put("z", 0.1);
                    c.set("size", vector(s.width(), s.width(), 0.2));
                    c.put("bottom_scale", 1.0);
                    c.put("top_scale", 1.0);
                    c.set("color", grey);
                }
                default -> lines.add(loop(s.points(), 0.1, 0.02, grey));
            }
        }
        return update;
    }

    /** A closed outline (foxglove.LineType LINE_LOOP, 1) through points at a height. */
    private static ObjectNode loop(List<double[]> points, double z, double thickness, ObjectNode color) {
        ObjectNode l = JSON.createObjectNode();
        l.put("type", 1);
        l.set("pose", pose(0, 0, 0));
        l.put("thickness", thickness);
        l.put("scale_invariant", false);
        ArrayNode at = l.putArray("points");
        for (double[] p : points) {
            at.add(vector(p[0], p[1], z));
        }
        l.set("color", color);
        l.putArray("colors");
        l.putArray("indices");
        return l;
    }

    private static ObjectNode cube(double x, double y, double z, double angle, double sx, double sy, double sz, ObjectNode color) {
        ObjectNode c = JSON.createObjectNode();
        ObjectNode p = pose(x, y, angle);
        ((ObjectNode) p.get("position")).put("z", z);
        c.set("pose", p);
        c.set("size", vector(sx, sy, sz));
        c.set("color", color);
        return c;
    }

    private static byte[] bytes(JsonNode n) {
        try {
            return JSON.writeValueAsBytes(n);
        } catch (JsonProcessingException e) {
            throw new IllegalStateException("cannot write a recording message as JSON: " + e.getMessage(), e);
        }
    }
}
