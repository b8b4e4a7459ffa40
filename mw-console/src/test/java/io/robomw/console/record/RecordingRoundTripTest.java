package io.robomw.console.record;

import com.fasterxml.jackson.databind.JsonNode;
import com.fasterxml.jackson.databind.ObjectMapper;
import io.robomw.console.mcap.McapReader;
import io.robomw.console.mcap.McapRecord;
import io.robomw.console.observe.HostView;
import io.robomw.console.observe.Observation;
import io.robomw.console.observe.WorldMap;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

import java.io.IOException;
import java.io.InputStream;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.HashMap;
import java.util.List;
import java.util.Map;
import java.util.Set;
import java.util.TreeSet;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertInstanceOf;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/** A recording holds what was observed, under the topics and schemas Foxglove knows, and a replay gives it back. */
class RecordingRoundTripTest {

    private static final long T0 = 1_700_000_000_000_000_000L;

    private static List<Observation> run() {
        WorldMap world = new WorldMap("arena", 4, 3, true, 0.1, 0.8,
                List.of(new WorldMap.Shape("box", 2, 1.5, 0.4, 0.2, 0.3, List.of()), new WorldMap.Shape("circle", 3, 2, 0.4, 0.4, 0, List.of())),
                List.of(new WorldMap.Patch(0, 0, 1, 1, 0.1)), List.of(new WorldMap.RobotMark("nxt", 0.2, 0.15, 0.5, 0.5, 0)));
        HostView.AgentView agent = new HostView.AgentView("6f1c0e8e-8f7e-4a8b-a5a3-5c1d2f0e9b11", "x.SurveyAgent", "ACTIVE", 1, "rmi://127.0.0.1:1/home",
                List.of(new HostView.StopView("rmi://127.0.0.1:2/a", "DONE", "", 0), new HostView.StopView("rmi://127.0.0.1:3/b", "", "", 0)), 1);
        return List.of(
                new Observation.World(T0, world),
                new Observation.RobotPose(T0 + 1_000_000, "nxt", 0.5, 0.5, 0.25, true),
                new Observation.RobotPose(T0 + 2_000_000, "nxt", 0.49, 0.51, 0.26, false),
                new Observation.RobotPose(T0 + 2_500_000, "copter", 1.5, 0.75, 2.0, -0.5, true), // a flyer at 2 m
                new Observation.SensorReading(T0 + 3_000_000, "nxt", "sonar", 0.73, "m"),
                new Observation.RobotCommand(T0 + 4_000_000, "nxt", "move", Map.of("distance", 0.4, "speed", 0.2)),
                new Observation.RobotStatus(T0 + 5_000_000, "nxt", "tcp://127.0.0.1:7000/nxt", false, "no answer"),
                new Observation.HostSeen(T0 + 6_000_000, new HostView("rmi://127.0.0.1:2/a", "a", true, "nxt", List.of(agent), null, "", T0)),
                new Observation.AgentEvent(T0 + 7_000_000, agent.id(), agent.className(), "report", "rmi://127.0.0.1:2/a", "x=0.50 range=0.73"),
                new Observation.TopicMessage(T0 + 8_000_000, "alerts", "battery low"));
    }

    @Test
    void aReplayGivesBackWhatWasRecordedInOrder(@TempDir Path dir) throws Exception {
        Path file = dir.resolve("run.mcap");
        try (McapRecorder r = McapRecorder.start(file, Map.of("command", "test"))) {
            run().forEach(r::observe);
        }
        List<Observation> replayed = new ArrayList<>();
        McapReplay.Played played = McapReplay.play(file, replayed::add, 0, () -> false);
        assertFalse(played.truncated());
        assertEquals(run().size(), replayed.size());
        for (int i = 0; i < run().size(); i++) {
            assertEquals(withoutTime(run().get(i)), withoutTime(replayed.get(i)), "observation " + i);
        }
        assertEquals(0.008, played.recordedSeconds(), 1e-9);
    }

    @Test
    void aFlyersAltitudeAndTheWorldsWaterAreRecordedWhereFoxgloveReadsThem(@TempDir Path dir) throws Exception {
        WorldMap harbour = new WorldMap("harbour", 10, 8, false, 0.1, 0.8, List.of(), List.of(), List.of(),
                List.of(List.of(new double[] {0, 0}, new double[] {10, 0}, new double[] {10, 3}, new double[] {0, 3})));
        Path file = dir.resolve("flight.mcap");
        try (McapRecorder r = McapRecorder.start(file, Map.of("command", "test"))) {
            r.observe(new Observation.World(T0, harbour));
            r.observe(new Observation.RobotPose(T0 + 1_000_000, "copter", 4, 5, 2.25, 0, true));
        }
        List<Observation> replayed = new ArrayList<>();
        McapReplay.play(file, replayed::add, 0, () -> false);
        Observation.RobotPose pose = replayed.stream().filter(o -> o instanceof Observation.RobotPose).map(o -> (Observation.RobotPose) o)
                .findFirst().orElseThrow();
        assertEquals(2.25, pose.z(), 1e-9, "the altitude comes back from the recording");
        WorldMap map = replayed.stream().filter(o -> o instanceof Observation.World).map(o -> ((Observation.World) o).map()).findFirst().orElseThrow();
        assertEquals(1, map.water().size());
        assertEquals(10.0, map.water().get(0).get(2)[0], "the water area's corner comes back");
        assertTrue(map.description().surroundings().onWater(5, 1.5), "a replayed picture knows the water too");
        RecordingCodec.Out scene = RecordingCodec.encode(new Observation.World(T0, harbour)).stream()
                .filter(o -> o.schema().equals("foxglove.SceneUpdate")).findFirst().orElseThrow();
        JsonNode lines = new ObjectMapper().readTree(scene.json()).at("/entities/0/lines");
        assertEquals(1, lines.size(), "the water's outline in Foxglove's 3D panel");
        assertEquals(4, lines.get(0).get("points").size());
        for (RecordingCodec.Out out : RecordingCodec.encode(new Observation.RobotPose(T0, "copter", 4, 5, 2.25, 0, true))) {
            JsonNode n = new ObjectMapper().readTree(out.json());
            JsonNode z = out.topic().equals(RecordingCodec.TF) ? n.at("/translation/z") : n.at("/pose/position/z");
            if (!z.isMissingNode()) {
                assertEquals(2.25, z.doubleValue(), 1e-9, out.topic() + " carries z for Foxglove's 3D panel");
            }
        }
    }

    @Test
    void aRecordingThatCannotStartLeavesItsFileClosed(@TempDir Path dir) throws Exception {
        org.junit.jupiter.api.Assumptions.assumeTrue(Files.isDirectory(Path.of("/proc/self/fd")), "open files are counted through /proc");
        Path file = dir.resolve("refused.mcap");
        Map<String, String> about = new HashMap<>();
        about.put("command", null); // a metadata value the format cannot hold
        org.junit.jupiter.api.Assertions.assertThrows(RuntimeException.class, () -> McapRecorder.start(file, about));
        assertEquals(List.of(), openHandlesOf(file), "the file is closed again");
    }

    private static List<Path> openHandlesOf(Path file) throws java.io.IOException {
        Path real = file.toRealPath();
        List<Path> open = new ArrayList<>();
        try (var fds = Files.list(Path.of("/proc/self/fd"))) {
            for (Path fd : fds.toList()) {
                try {
                    if (Files.readSymbolicLink(fd).equals(real)) {
                        open.add(fd);
                    }
                } catch (java.io.IOException | UnsupportedOperationException gone) {
                    // closed meanwhile, or not a link
                }
            }
        }
        return open;
    }

    @Test
    void theFileUsesFoxglovesSchemasWhereFoxgloveHasThem(@TempDir Path dir) throws Exception {
        Path file = dir.resolve("run.mcap");
        try (McapRecorder r = McapRecorder.start(file, Map.of())) {
            run().forEach(r::observe);
        }
        Map<Integer, String> schemas = new HashMap<>();
        Map<String, String> topicSchema = new HashMap<>();
        Set<String> metadata = new TreeSet<>();
        McapRecord.Statistics stats = null;
        try (McapReader reader = new McapReader(Files.newInputStream(file), file.toString(), McapReader.Options.DEFAULT)) {
            for (McapRecord x; (x = reader.next()) != null; ) {
                if (x instanceof McapRecord.Schema s) {
                    schemas.put(s.id(), s.name());
                    assertEquals("jsonschema", s.encoding());
                } else if (x instanceof McapRecord.Channel c) {
                    topicSchema.put(c.topic(), schemas.get(c.schemaId()));
                    assertEquals("json", c.messageEncoding());
                } else if (x instanceof McapRecord.Metadata m) {
                    metadata.add(m.name() + "=" + m.metadata().get("format"));
                } else if (x instanceof McapRecord.Statistics s) {
                    stats = s;
                }
            }
        }
        assertEquals("foxglove.PoseInFrame", topicSchema.get("/robots/nxt/pose"));
        assertEquals("foxglove.PoseInFrame", topicSchema.get("/robots/nxt/odometry"));
        assertEquals("foxglove.FrameTransform", topicSchema.get("/tf"));
        assertEquals("foxglove.SceneUpdate", topicSchema.get("/world/scene"));
        assertEquals("foxglove.Log", topicSchema.get("/agents/log"));
        assertEquals("robomw.SensorReading", topicSchema.get("/robots/nxt/sensors/sonar"));
        assertEquals("robomw.AgentEvent", topicSchema.get("/agents/events"));
        assertTrue(metadata.contains("robomw=" + McapRecorder.FORMAT_VERSION), metadata.toString());
        assertEquals(14, stats.messageCount(), "10 observations, plus the scene, the two true poses' transforms and the log line they bring");
        assertTrue(stats.chunkCount() >= 1);
    }

    @Test
    void aMessageThatIsNotWhatItsSchemaSaysIsAClearError() {
        IOException e = assertThrows(IOException.class,
                () -> RecordingCodec.decode("/robots/nxt/pose", "foxglove.PoseInFrame", "{\"pose\":{\"position\":{\"x\":\"one\"}}}".getBytes(), 1));
        assertTrue(e.getMessage().contains("/robots/nxt/pose") && e.getMessage().contains("orientation"), e.getMessage());
        IOException notJson = assertThrows(IOException.class,
                () -> RecordingCodec.decode("/agents/events", "robomw.AgentEvent", "{oops".getBytes(), 1));
        assertTrue(notJson.getMessage().contains("is not JSON"), notJson.getMessage());
        IOException wrongType = assertThrows(IOException.class,
                () -> RecordingCodec.decode("/robots/a/sensors/s", "robomw.SensorReading", "{\"robot\":\"a\",\"sensor\":\"s\",\"value\":\"x\",\"unit\":\"m\"}".getBytes(), 1));
        assertTrue(wrongType.getMessage().contains("'value' must be a number"), wrongType.getMessage());
    }

    @Test
    void aFileThatIsNotARecordingIsRefusedNamingTheFile(@TempDir Path dir) throws Exception {
        Path file = dir.resolve("notes.mcap");
        Files.writeString(file, "these are my notes");
        IOException e = assertThrows(IOException.class, () -> McapReplay.play(file, o -> { }, 0, () -> false));
        assertTrue(e.getMessage().contains(file.toString()) && e.getMessage().contains("not an MCAP file"), e.getMessage());
    }

    @Test
    void theVendoredFoxgloveSchemasAreTheirOwn() throws IOException {
        for (String name : List.of("foxglove.PoseInFrame", "foxglove.FrameTransform", "foxglove.SceneUpdate", "foxglove.Log")) {
            try (InputStream in = McapRecorder.class.getResourceAsStream("/io/robomw/console/schemas/" + name + ".json")) {
                String text = new String(in.readAllBytes(), java.nio.charset.StandardCharsets.UTF_8);
                assertTrue(text.contains("\"title\": \"" + name + "\""), name);
            }
        }
    }

    /** An observation with its times zeroed (a replay re-stamps them). */
    private static Object withoutTime(Observation o) {
        if (o instanceof Observation.World w) {
            return w.map();
        } else if (o instanceof Observation.RobotPose p) {
            return List.of(p.robot(), Math.round(p.x() * 1e9), Math.round(p.y() * 1e9), Math.round(p.z() * 1e9), Math.round(p.heading() * 1e9), p.truth());
        } else if (o instanceof Observation.SensorReading s) {
            return new Observation.SensorReading(0, s.robot(), s.sensor(), s.value(), s.unit());
        } else if (o instanceof Observation.RobotCommand c) {
            return new Observation.RobotCommand(0, c.robot(), c.verb(), c.args());
        } else if (o instanceof Observation.RobotStatus s) {
            return new Observation.RobotStatus(0, s.robot(), s.source(), s.reachable(), s.detail());
        } else if (o instanceof Observation.HostSeen h) {
            HostView v = h.host();
            return new HostView(v.address(), v.name(), v.up(), v.robot(), v.agents(), v.owed(), v.error(), 0);
        } else if (o instanceof Observation.AgentEvent e) {
            return new Observation.AgentEvent(0, e.agent(), e.agentClass(), e.kind(), e.host(), e.detail());
        } else if (o instanceof Observation.TopicMessage m) {
            return new Observation.TopicMessage(0, m.topic(), m.text());
        }
        return assertInstanceOf(Observation.class, o);
    }
}
