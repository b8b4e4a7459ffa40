package io.robomw.console.rosbridge;

import com.fasterxml.jackson.databind.JsonNode;
import io.robomw.api.Robot;
import io.robomw.console.rosbridge.protocol.Limits;
import io.robomw.sim.Simulation;
import io.robomw.testkit.Await;
import org.junit.jupiter.api.AfterAll;
import org.junit.jupiter.api.BeforeAll;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

import java.net.URI;
import java.net.http.HttpClient;
import java.net.http.HttpRequest;
import java.net.http.HttpResponse;
import java.net.http.WebSocketHandshakeException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.concurrent.CompletionException;
import java.util.concurrent.ExecutionException;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicReference;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertInstanceOf;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * The endpoint over a real socket, with a simulated robot running in real time: odometry and
 * ranges come, cmd_vel drives the robot and its watchdog stops it, a move service moves it, and
 * the safety checks refuse what they should. The client is the JDK's WebSocket.
 */
class RosBridgeTest {

    private static final Duration WITHIN = Duration.ofSeconds(30);
    private static final String ROBOT = """
            name: tester
            platform: sim
            cycle_hz: 50
            watchdog: 0.5
            capabilities: [ground]
            drive: { type: differential, wheel_diameter: 0.05, track_width: 0.1, max_speed: 0.3, left: { port: A }, right: { port: B } }
            body: { length: 0.15, width: 0.12, mass: 0.5, friction: 0.8 }
            sensors:
              - { name: sonar, type: sonar, position: front, port: S1, options: { max_range: 2.0, rate_hz: 20 } }
              - { name: ir-left, type: infrared, position: left, port: S2 }
            """;
    private static final String WORLD = """
            name: bridge-test
            arena: { width: 4, height: 3, walls: true, wall_thickness: 0.1, floor: 0.8 }
            seed: 1
            physics_hz: 100
            robots:
              - { robot: robot.yaml, name: bot-1, x: 1.0, y: 1.5, heading: 0 }
            """;

    @TempDir
    static Path dir;
    static Simulation sim;
    static RosBridge bridge;

    @BeforeAll
    static void start() throws Exception {
        Files.writeString(dir.resolve("robot.yaml"), ROBOT);
        Files.writeString(dir.resolve("world.yaml"), WORLD);
        sim = Simulation.load(dir.resolve("world.yaml"));
        sim.startRealTime(1.0);
        Robot bot = sim.robot("bot-1");
        bridge = RosBridge.builder().listen("127.0.0.1", 0).rates(new Rates(25, 0)).limits(Limits.DEFAULTS.withMaxConnections(4))
                .robot(BridgedRobot.simulated(bot, sim.world().robot("bot-1"))).start();
    }

    @AfterAll
    static void stop() {
        if (bridge != null) {
            bridge.close();
        }
        if (sim != null) {
            sim.close();
        }
    }

    @Test
    void twistDrivesTheRobotAndItsWatchdogStopsItWhenTheClientStopsPublishing() throws Exception {
        try (WsClient c = WsClient.connect(bridge.address())) {
            c.send("{'op':'subscribe','id':'s','topic':'/bot_1/odom','type':'nav_msgs/msg/Odometry'}");
            JsonNode first = c.awaitPublish("/bot_1/odom", WITHIN);
            assertEquals("bot_1/odom", first.at("/msg/header/frame_id").asText());
            assertEquals("bot_1/base_link", first.at("/msg/child_frame_id").asText());
            assertEquals(36, first.at("/msg/pose/covariance").size());
            double x0 = first.at("/msg/pose/pose/position/x").doubleValue();
            c.send("{'op':'advertise','id':'a','topic':'/bot_1/cmd_vel','type':'geometry_msgs/msg/Twist'}");
            AtomicReference<JsonNode> last = new AtomicReference<>(first);
            long until = System.nanoTime() + Duration.ofMillis(1500).toNanos();
            while (System.nanoTime() < until) {
                c.send("{'op':'publish','topic':'/bot_1/cmd_vel','msg':{'linear':{'x':0.2,'y':0,'z':0},'angular':{'x':0,'y':0,'z':0}}}");
                JsonNode m = c.frames.poll(100, TimeUnit.MILLISECONDS); // publishes at about 10 Hz, as a teleop does
                if (m != null && m.path("topic").asText().equals("/bot_1/odom")) {
                    last.set(m);
                }
            }
            Await.until("the robot drove forward", WITHIN, () -> {
                JsonNode m = c.frames.poll();
                if (m != null) {
                    last.set(m);
                }
                return last.get().at("/msg/pose/pose/position/x").doubleValue() > x0 + 0.05;
            }, () -> "odometry " + last.get().at("/msg/pose/pose/position"));
            Await.until("the watchdog stopped it after the client stopped publishing", WITHIN, () -> {
                JsonNode m = c.frames.poll();
                if (m != null) {
                    last.set(m);
                }
                return m != null && m.at("/msg/twist/twist/linear/x").doubleValue() == 0.0;
            }, () -> "twist " + last.get().at("/msg/twist/twist/linear"));
            double stoppedAt = last.get().at("/msg/pose/pose/position/x").doubleValue();
            long settled = System.nanoTime() + Duration.ofSeconds(1).toNanos();
            JsonNode later = last.get();
            while (System.nanoTime() < settled) {
                later = c.awaitPublish("/bot_1/odom", WITHIN);
            }
            assertEquals(stoppedAt, later.at("/msg/pose/pose/position/x").doubleValue(), 1e-3, "it stays where it stopped, a second later");
            assertEquals(0.0, later.at("/msg/twist/twist/linear/x").doubleValue());
        }
    }

    @Test
    void aMoveServiceAnswersOnceTheRobotHasMoved() throws Exception {
        try (WsClient c = WsClient.connect(bridge.address())) {
            double before = sim.robot("bot-1").pose().x();
            c.send("{'op':'call_service','id':'m1','service':'/bot_1/move','args':{'distance':0.1,'speed':0.2}}");
            JsonNode r = c.await(f -> f.path("id").asText().equals("m1"), WITHIN, "the move's answer");
            assertEquals("service_response", r.get("op").asText());
            assertTrue(r.get("result").booleanValue(), r.toString());
            assertTrue(r.at("/values/success").booleanValue(), r.toString());
            assertEquals(before + 0.1, sim.robot("bot-1").pose().x(), 0.02, "the robot covered the distance before the answer");
            c.send("{'op':'call_service','id':'m2','service':'/bot_1/move','args':{'distance':0.1,'speed':5}}");
            JsonNode tooFast = c.await(f -> f.path("id").asText().equals("m2"), WITHIN, "the refusal");
            assertTrue(tooFast.get("result").booleanValue());
            assertEquals(false, tooFast.at("/values/success").booleanValue(), tooFast.toString());
            assertTrue(tooFast.at("/values/message").asText().contains("refused"), tooFast.toString());
        }
    }

    @Test
    void rangesComeWithTheSensorsLimitsAndTheStaticTransformsPlaceTheSensors() throws Exception {
        try (WsClient c = WsClient.connect(bridge.address())) {
            c.send("{'op':'subscribe','id':'r','topic':'/bot_1/range/sonar'}");
            JsonNode range = c.awaitPublish("/bot_1/range/sonar", WITHIN);
            assertEquals("bot_1/sonar", range.at("/msg/header/frame_id").asText());
            assertEquals(0, range.at("/msg/radiation_type").intValue(), "ULTRASOUND");
            assertEquals(2.0, range.at("/msg/max_range").doubleValue(), 1e-6, "the robot file's max_range");
            double metres = range.at("/msg/range").doubleValue();
            assertTrue(metres > 0 && metres <= 2.0, "a reading in range: " + metres);
            c.send("{'op':'subscribe','id':'t','topic':'/tf_static'}");
            JsonNode mounts = c.awaitPublish("/tf_static", WITHIN);
            assertEquals(2, mounts.at("/msg/transforms").size());
            assertEquals("bot_1/base_link", mounts.at("/msg/transforms/1/header/frame_id").asText());
            assertEquals("bot_1/ir_left", mounts.at("/msg/transforms/1/child_frame_id").asText());
            assertEquals(Math.sin(Math.PI / 4), mounts.at("/msg/transforms/1/transform/rotation/z").doubleValue(), 1e-6, "facing left");
            c.send("{'op':'subscribe','id':'tf','topic':'/tf'}");
            JsonNode tf = c.awaitPublish("/tf", WITHIN);
            assertEquals("bot_1/odom", tf.at("/msg/transforms/0/header/frame_id").asText());
        }
    }

    @Test
    void plainHttpIsToldThisIsAWebSocketEndpoint() throws Exception {
        HttpResponse<String> r = HttpClient.newHttpClient().send(HttpRequest.newBuilder(URI.create("http://127.0.0.1:" + bridge.port() + "/")).build(),
                HttpResponse.BodyHandlers.ofString());
        assertEquals(426, r.statusCode());
        assertTrue(r.body().contains("rosbridge v2"));
    }

    @Test
    void aFrameOverTheMessageLimitClosesTheConnection() throws Exception {
        try (RosBridge small = RosBridge.builder().listen("127.0.0.1", 0).limits(Limits.DEFAULTS.withMaxMessageBytes(4096)).start();
             WsClient c = WsClient.connect(small.address())) {
            c.send("{'op':'publish','topic':'/x','msg':{'data':'" + "x".repeat(10_000) + "'}}");
            assertEquals(1009, c.closed.get(30, TimeUnit.SECONDS), "1009: message too big");
        }
    }

    @Test
    void oneClientMoreThanTheLimitIsRefused() throws Exception {
        try (RosBridge one = RosBridge.builder().listen("127.0.0.1", 0).limits(Limits.DEFAULTS.withMaxConnections(1)).start();
             WsClient first = WsClient.connect(one.address())) {
            Await.until("the first client is counted", WITHIN, () -> one.clients() == 1);
            assertEquals(503, handshakeStatus(() -> WsClient.connect(one.address())));
        }
    }

    @Test
    void aTokenIsNeededWhereOneIsSetAndBeyondLoopback() throws Exception {
        String token = "a-long-enough-secret-token";
        try (RosBridge guarded = RosBridge.builder().listen("127.0.0.1", 0).token(token).start()) {
            assertEquals(401, handshakeStatus(() -> WsClient.connect(guarded.address())));
            try (WsClient c = WsClient.connect(URI.create(guarded.address() + "?token=" + token))) {
                c.send("{'op':'call_service','id':'v','service':'/rosapi/get_ros_version'}");
                JsonNode v = c.await(f -> f.path("id").asText().equals("v"), WITHIN, "an answer");
                assertEquals(2, v.at("/values/version").intValue());
            }
        }
        IllegalArgumentException e = assertThrows(IllegalArgumentException.class, () -> RosBridge.builder().listen("0.0.0.0", 0).start());
        assertTrue(e.getMessage().contains("needs an access token"), e.getMessage());
    }

    @Test
    void aPageFromAnotherSiteIsRefused() throws Exception {
        assertEquals(403, handshakeStatus(() -> WsClient.connect(bridge.address(), "https://evil.example.com")));
        try (WsClient local = WsClient.connect(bridge.address(), "http://localhost:8000")) {
            local.send("{'op':'call_service','id':'n','service':'/rosapi/nodes'}");
            JsonNode nodes = local.await(f -> f.path("id").asText().equals("n"), WITHIN, "the nodes");
            assertTrue(nodes.at("/values/nodes").toString().contains("/bot_1"), nodes.toString());
        }
    }

    /** What a connection that should be refused... */
    private interface Connect {
        WsClient connect() throws Exception;
    }

    private static int handshakeStatus(Connect connect) {
        ExecutionException e = assertThrows(ExecutionException.class, () -> {
            try (WsClient c = connect.connect()) {
                throw new AssertionError("the connection was taken");
            }
        });
        Throwable cause = e.getCause() instanceof CompletionException ce && ce.getCause() != null ? ce.getCause() : e.getCause();
        return assertInstanceOf(WebSocketHandshakeException.class, cause).getResponse().statusCode();
    }
}
