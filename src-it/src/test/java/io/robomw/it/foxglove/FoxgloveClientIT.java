package io.robomw.it.foxglove;

import com.fasterxml.jackson.databind.JsonNode;
import io.robomw.it.demo.MwProcess;
import org.junit.jupiter.api.Test;

import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.List;

import static io.robomw.it.foxglove.PythonClients.field;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * RoboMW's live Foxglove WebSocket, seen by a Foxglove client: a small Python client written from
 * the protocol (src/test/python/foxglove_probe.py), run in the same test against foxglove-sdk
 * 0.30.3's own server (the reference implementation: so the probe itself is shown right) and
 * against {@code mw sim --foxglove} in its own JVM. Each time it gets serverInfo, the channels with
 * their JSON Schemas, pose messages with log times, and drives a robot by publishing Twists as a
 * teleop panel does, and the robot's pose changes.
 */
class FoxgloveClientIT {

    private static final Duration START = Duration.ofSeconds(90);

    /** What the probe must have seen from any right server: the protocol, a pose channel and its messages, a robot driven. */
    private static void assertSawAndDrove(List<JsonNode> lines, String server) {
        assertEquals("foxglove.sdk.v1", field(lines, "subprotocol").asText(), server + ": offered both names, the SDK's is chosen");
        JsonNode info = field(lines, "serverInfo");
        assertTrue(info.get("capabilities").toString().contains("clientPublish"), server + ": " + info);
        assertTrue(info.get("supportedEncodings").toString().contains("json"), server + ": " + info);
        JsonNode channel = field(lines, "channel");
        assertEquals("foxglove.PoseInFrame", channel.get("schemaName").asText(), server + ": " + channel);
        assertEquals("jsonschema", channel.get("schemaEncoding").asText(), server + ": " + channel);
        assertEquals("foxglove.PoseInFrame", channel.get("schema").get("title").asText(), server + ": the schema is a JSON Schema");
        List<JsonNode> messages = lines.stream().filter(l -> l.has("message")).toList();
        assertEquals(3, messages.size(), server + ": " + lines);
        long previous = 0;
        for (JsonNode m : messages) {
            long logTime = m.get("logTime").asLong();
            assertTrue(logTime > 1_600_000_000_000_000_000L && logTime >= previous, server + ": log times are ns since the epoch, in order: " + lines);
            previous = logTime;
            assertEquals("world", m.get("message").get("frame_id").asText());
            JsonNode stamp = m.get("message").get("timestamp");
            assertEquals(logTime, stamp.get("sec").asLong() * 1_000_000_000L + stamp.get("nsec").asLong(), server + ": stamped with its log time");
        }
        double before = field(lines, "before").get("pose").get("position").get("x").asDouble();
        double after = field(lines, "after").get("pose").get("position").get("x").asDouble();
        assertTrue(after > before + 0.15, server + ": 2 s at 0.2 m/s should move the robot forwards, x went " + before + " -> " + after);
        assertTrue(field(lines, "done").asBoolean());
    }

    @Test
    void theProbeSeesAndDrivesFoxglovesReferenceServerAndRoboMWAlike() throws Exception {
        try (PythonClients.ReferenceServer reference = new PythonClients.ReferenceServer("/robots/probe/pose")) {
            List<JsonNode> lines = PythonClients.probe("foxglove-probe-reference", reference.url(), "/robots/probe/pose",
                    "--drive", "/robots/probe/cmd_vel", "--seconds", "2", "--linear", "0.2");
            assertSawAndDrove(lines, "foxglove-sdk 0.30.3");
            assertEquals("rejected", field(lines, "legacy").asText(), "the SDK refuses the legacy name (protocols/ros-and-foxglove.md)");
            assertEquals(400, field(lines, "status").asInt());
        }
        try (MwProcess sim = MwProcess.start("foxglove-sim", "sim", "examples/worlds/arena.yaml", "--foxglove", "0", "--duration", "10m")) {
            String url = sim.await("foxglove at ", START).replaceFirst(".*foxglove at ", "").strip();
            List<JsonNode> lines = PythonClients.probe("foxglove-probe-robomw", url, "/robots/nxt/pose",
                    "--drive", "/robots/nxt/cmd_vel", "--seconds", "2", "--linear", "0.2");
            assertSawAndDrove(lines, "mw sim --foxglove");
            assertEquals("accepted", field(lines, "legacy").asText(), "RoboMW also takes foxglove.websocket.v1");
            assertTrue(field(lines, "serverInfo").get("name").asText().startsWith("mw sim examples/worlds/arena.yaml"));
        }
    }

    @Test
    void aReplayServesTheRecordingInRecordedTimeWithTheTimeCapability() throws Exception {
        Path dir = Files.createDirectories(Path.of("target", "it-foxglove"));
        Path recording = dir.resolve("arena.mcap").toAbsolutePath();
        try (MwProcess record = MwProcess.start("foxglove-record", "sim", "examples/worlds/arena.yaml", "--realtime", "--duration", "5s", "--record", recording.toString())) {
            assertEquals(0, record.waitFor(START));
        }
        long replayStarted = System.currentTimeMillis() * 1_000_000L;
        try (MwProcess replay = MwProcess.start("foxglove-replay", "replay", recording.toString(), "--no-console", "--foxglove", "0", "--speed", "0.1")) {
            String url = replay.await("foxglove at ", START).replaceFirst(".*foxglove at ", "").strip();
            List<JsonNode> lines = PythonClients.probe("foxglove-probe-replay", url, "/robots/nxt/pose", "--messages", "3");
            JsonNode info = field(lines, "serverInfo");
            assertEquals("[\"time\"]", info.get("capabilities").toString(), "a replay tells its time and drives nothing: " + info);
            assertEquals("foxglove.PoseInFrame", field(lines, "channel").get("schemaName").asText());
            long serverTime = field(lines, "serverTime").asLong();
            assertTrue(serverTime > 1_600_000_000_000_000_000L && serverTime < replayStarted, "the replay's time is the recorded time, before the replay began: " + serverTime);
            List<JsonNode> messages = lines.stream().filter(l -> l.has("message")).toList();
            assertEquals(3, messages.size());
            for (JsonNode m : messages) {
                long logTime = m.get("logTime").asLong();
                assertTrue(logTime < replayStarted, "messages keep the times they were recorded at: " + logTime);
                JsonNode stamp = m.get("message").get("timestamp");
                assertEquals(logTime, stamp.get("sec").asLong() * 1_000_000_000L + stamp.get("nsec").asLong());
            }
        }
    }
}
