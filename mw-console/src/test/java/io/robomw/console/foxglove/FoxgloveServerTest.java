package io.robomw.console.foxglove;

import com.fasterxml.jackson.databind.JsonNode;
import com.fasterxml.jackson.databind.ObjectMapper;
import io.robomw.console.observe.Observation;
import io.robomw.console.observe.WorldMap;
import io.robomw.testkit.Await;
import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.Test;

import java.net.http.WebSocketHandshakeException;
import java.nio.charset.StandardCharsets;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.Set;
import java.util.concurrent.BlockingQueue;
import java.util.concurrent.ExecutionException;
import java.util.concurrent.LinkedBlockingQueue;
import java.util.concurrent.TimeUnit;

import static org.junit.jupiter.api.Assertions.assertArrayEquals;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertInstanceOf;
import static org.junit.jupiter.api.Assertions.assertNotNull;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;
import static org.junit.jupiter.api.Assertions.fail;

/**
 * The server over real sockets on 127.0.0.1, with the JDK's WebSocket client: handshakes, what a
 * client is sent, subscriptions, client publishing, bad input, limits.
 */
class FoxgloveServerTest {

    private static final ObjectMapper JSON = new ObjectMapper();
    private static final long T0 = 1_700_000_000_000_000_000L;
    private static final String SDK = "foxglove.sdk.v1";
    private static final String LEGACY = "foxglove.websocket.v1";

    private final List<AutoCloseable> open = new ArrayList<>();

    @AfterEach
    void closeAll() throws Exception {
        for (int i = open.size() - 1; i >= 0; i--) {
            open.get(i).close();
        }
    }

    /** A robot "nxt" the test drives; every drive call is kept. */
    private static final class FakeTeleop implements Teleop {
        final BlockingQueue<double[]> drives = new LinkedBlockingQueue<>();
        volatile String refusal;

        @Override
        public Set<String> robots() {
            return Set.of("nxt");
        }

        @Override
        public void drive(String robot, double linear, double angular) {
            if (refusal != null) {
                throw new IllegalArgumentException(refusal);
            }
            drives.add(new double[] {linear, angular});
        }

        double[] next() throws InterruptedException {
            double[] d = drives.poll(20, TimeUnit.SECONDS);
            assertNotNull(d, "the robot was not driven within 20 s");
            return d;
        }
    }

    private FoxgloveServer server(FoxgloveServer.Options options, Teleop teleop) throws Exception {
        FoxgloveServer s = FoxgloveServer.create(options);
        open.add(s);
        return s.start(teleop);
    }

    private FoxgloveServer server(Teleop teleop) throws Exception {
        return server(FoxgloveServer.Options.live("test", "127.0.0.1", 0), teleop);
    }

    private WsClient client(FoxgloveServer s, String... subprotocols) throws Exception {
        WsClient c = WsClient.connect(s.address(), subprotocols);
        open.add(c);
        return c;
    }

    private static JsonNode json(String text) throws Exception {
        return JSON.readTree(text);
    }

    private static Observation.RobotPose pose(long t, double x) {
        return new Observation.RobotPose(t, "nxt", x, 0.5, 0.25, true);
    }

    /** @return the advertised channel id of a topic, reading advertisements until it comes */
    private static long channelOf(WsClient c, String topic) throws Exception {
        while (true) {
            JsonNode a = json(c.nextOp("advertise"));
            for (JsonNode ch : a.get("channels")) {
                if (ch.get("topic").asText().equals(topic)) {
                    return ch.get("id").asLong();
                }
            }
        }
    }

    /** Waits until the server has handled everything the client sent before: a bad message's answer comes after them. */
    private static void sync(WsClient c) throws Exception {
        c.send("{\"op\":\"sync\"}");
        while (!json(c.nextOp("status")).get("message").asText().contains("unknown op \"sync\"")) {
            // an earlier status; the sync's answer comes next
        }
    }

    // ---- handshakes ----

    @Test
    void aClientOfferingTheSdkNameGetsIt() throws Exception {
        assertEquals(SDK, client(server(Teleop.NONE), SDK).subprotocol());
    }

    @Test
    void aClientOfferingOnlyTheLegacyNameGetsIt() throws Exception {
        assertEquals(LEGACY, client(server(Teleop.NONE), LEGACY).subprotocol());
    }

    @Test
    void aClientOfferingBothGetsTheSdkName() throws Exception {
        assertEquals(SDK, client(server(Teleop.NONE), LEGACY, SDK).subprotocol());
    }

    @Test
    void aHandshakeOfferingNeitherIsRefusedWith400AsTheSdkRefusesIt() throws Exception {
        FoxgloveServer s = server(Teleop.NONE);
        for (String[] offered : List.of(new String[] {}, new String[] {"chat"})) {
            ExecutionException e = assertThrows(ExecutionException.class, () -> client(s, offered));
            WebSocketHandshakeException h = assertInstanceOf(WebSocketHandshakeException.class, e.getCause());
            assertEquals(400, h.getResponse().statusCode());
        }
    }

    // ---- what a client is sent ----

    @Test
    void serverInfoComesFirstThenTheChannelsKnownWithTheRecordingsSchemas() throws Exception {
        FoxgloveServer s = server(Teleop.NONE);
        s.observe(pose(T0, 1.0));
        Await.until("the pose was encoded", Duration.ofSeconds(20), () -> s.published() >= 2);
        WsClient c = client(s, SDK);
        WsClient.Frame first = c.next();
        JsonNode info = json(first.text());
        assertEquals("serverInfo", info.get("op").asText());
        assertEquals("test", info.get("name").asText());
        assertEquals(0, info.get("capabilities").size(), "no robots to drive, not a replay: no capabilities");
        assertFalse(info.has("supportedEncodings"));
        assertTrue(info.get("sessionId").asText().matches("\\d+"));
        JsonNode advertise = json(c.next().text());
        assertEquals("advertise", advertise.get("op").asText());
        JsonNode pose = null;
        for (JsonNode ch : advertise.get("channels")) {
            assertEquals("json", ch.get("encoding").asText());
            assertEquals("jsonschema", ch.get("schemaEncoding").asText());
            assertEquals(ch.get("schemaName").asText(), json(ch.get("schema").asText()).get("title").asText(), "the schema is the named JSON Schema");
            if (ch.get("topic").asText().equals("/robots/nxt/pose")) {
                pose = ch;
            }
        }
        assertNotNull(pose, "the pose channel is advertised: " + advertise);
        assertEquals("foxglove.PoseInFrame", pose.get("schemaName").asText());
        assertEquals(2, advertise.get("channels").size(), "the pose and /tf: " + advertise);
    }

    @Test
    void aChannelSeenLaterIsAdvertisedToClientsAlreadyConnected() throws Exception {
        FoxgloveServer s = server(Teleop.NONE);
        WsClient c = client(s, SDK);
        c.nextOp("serverInfo");
        s.observe(new Observation.SensorReading(T0, "nxt", "sonar", 0.7, "m"));
        JsonNode ch = json(c.nextOp("advertise")).get("channels").get(0);
        assertEquals("/robots/nxt/sensors/sonar", ch.get("topic").asText());
        assertEquals("robomw.SensorReading", ch.get("schemaName").asText());
    }

    @Test
    void aSubscriberGetsEachMessageWithItsOwnIdAndTheLogTime() throws Exception {
        FoxgloveServer s = server(Teleop.NONE);
        WsClient c = client(s, SDK);
        s.observe(pose(T0, 1.0));
        long pose = channelOf(c, "/robots/nxt/pose");
        c.send("{\"op\":\"subscribe\",\"subscriptions\":[{\"id\":42,\"channelId\":" + pose + "}]}");
        WsClient.Frame latched = c.nextBinary(1);
        assertEquals(42, latched.le().getInt(1));
        assertEquals(T0, latched.le().getLong(5), "the latest message, at once");
        s.observe(pose(T0 + 50_000_000, 1.25));
        WsClient.Frame f = c.nextBinary(1);
        assertEquals(42, f.le().getInt(1), "the client's id, not the channel's");
        assertEquals(T0 + 50_000_000, f.le().getLong(5));
        JsonNode m = JSON.readTree(new String(f.binary(), 13, f.binary().length - 13, StandardCharsets.UTF_8));
        assertEquals("world", m.get("frame_id").asText());
        assertEquals(1.25, m.get("pose").get("position").get("x").asDouble());
        assertEquals(1_700_000_000, m.get("timestamp").get("sec").asLong());
        assertEquals(50_000_000, m.get("timestamp").get("nsec").asLong());
    }

    @Test
    void afterUnsubscribingNoMoreMessagesComeOnThatSubscription() throws Exception {
        FoxgloveServer s = server(Teleop.NONE);
        WsClient c = client(s, SDK);
        s.observe(pose(T0, 1.0));
        long pose = channelOf(c, "/robots/nxt/pose");
        c.send("{\"op\":\"subscribe\",\"subscriptions\":[{\"id\":42,\"channelId\":" + pose + "},{\"id\":43,\"channelId\":" + (pose == 1 ? 2 : 1) + "}]}");
        c.nextBinary(1);
        c.nextBinary(1);
        c.send("{\"op\":\"unsubscribe\",\"subscriptionIds\":[42]}");
        sync(c);
        s.observe(pose(T0 + 1, 2.0)); // its pose would come before its transform on /tf, had 42 stayed
        while (true) {
            WsClient.Frame f = c.nextBinary(1);
            int id = f.le().getInt(1);
            if (id == 42 && f.le().getLong(5) == T0 + 1) {
                fail("a message came on subscription 42 after it was ended");
            }
            if (id == 43 && f.le().getLong(5) == T0 + 1) {
                break;
            }
        }
    }

    @Test
    void aClientConnectingLaterGetsTheArenaSentOnceAtTheStart() throws Exception {
        FoxgloveServer s = server(Teleop.NONE);
        WorldMap world = new WorldMap("arena", 4, 3, true, 0.1, 0.8, List.of(), List.of(), List.of());
        s.observe(new Observation.World(T0, world));
        Await.until("the world was encoded", Duration.ofSeconds(20), () -> s.published() >= 2);
        WsClient c = client(s, SDK);
        long scene = channelOf(c, "/world/scene");
        c.send("{\"op\":\"subscribe\",\"subscriptions\":[{\"id\":7,\"channelId\":" + scene + "}]}");
        WsClient.Frame f = c.nextBinary(1);
        assertEquals(7, f.le().getInt(1));
        assertTrue(new String(f.binary(), StandardCharsets.UTF_8).contains("\"cubes\""));
    }

    // ---- bad input ----

    @Test
    void badMessagesGetStatusErrorsAndTheConnectionGoesOn() throws Exception {
        FoxgloveServer s = server(Teleop.NONE);
        WsClient c = client(s, SDK);
        s.observe(pose(T0, 1.0));
        long pose = channelOf(c, "/robots/nxt/pose");
        List<String> expected = List.of("Invalid message: not JSON", "Unknown binary opcode 255", "Unknown channel ID: 999",
                "Server does not support clientPublish capability", "Server does not support parameters capability", "Empty binary message");
        c.send("{oops");
        c.send(new byte[] {(byte) 0xFF, 1, 2});
        c.send("{\"op\":\"subscribe\",\"subscriptions\":[{\"id\":1,\"channelId\":999}]}");
        c.send("{\"op\":\"advertise\",\"channels\":[{\"id\":1,\"topic\":\"/cmd_vel\",\"encoding\":\"json\",\"schemaName\":\"geometry_msgs/Twist\"}]}");
        c.send("{\"op\":\"getParameters\",\"parameterNames\":[]}");
        c.send(new byte[0]);
        for (String e : expected) {
            JsonNode status = json(c.nextOp("status"));
            assertEquals(2, status.get("level").asInt(), "an error: " + status);
            assertTrue(status.get("message").asText().startsWith(e), status + " should start with " + e);
        }
        c.send("{\"op\":\"subscribe\",\"subscriptions\":[{\"id\":5,\"channelId\":" + pose + "}]}");
        assertEquals(5, c.nextBinary(1).le().getInt(1), "the connection still serves");
        c.send("{\"op\":\"subscribe\",\"subscriptions\":[{\"id\":5,\"channelId\":" + (pose == 1 ? 2 : 1) + "}]}");
        assertEquals("Subscription ID was already used: 5; ignoring subscription", json(c.nextOp("status")).get("message").asText());
        c.send("{\"op\":\"subscribe\",\"subscriptions\":[{\"id\":6,\"channelId\":" + pose + "}]}");
        JsonNode warning = json(c.nextOp("status"));
        assertEquals(1, warning.get("level").asInt());
        assertEquals("Client is already subscribed to channel: " + pose + "; ignoring subscription", warning.get("message").asText());
    }

    @Test
    void aClientMessageOverTheLimitClosesTheConnectionAsTooBig() throws Exception {
        WsClient c = client(server(Teleop.NONE), SDK);
        c.nextOp("serverInfo");
        try {
            c.send("{\"op\":\"" + "x".repeat(FoxgloveServer.MAX_CLIENT_MESSAGE) + "\"}");
        } catch (ExecutionException e) {
            // the server may close before the whole message is written
        }
        assertEquals(1009, c.closeCode());
    }

    @Test
    void aSlowClientLosesItsOldestMessagesNotTheServersMemory() throws Exception {
        FoxgloveServer s = server(FoxgloveServer.Options.live("test", "127.0.0.1", 0).withBacklog(8), Teleop.NONE);
        WsClient c = client(s, SDK);
        String text = "x".repeat(200_000);
        s.observe(new Observation.TopicMessage(T0, "big", "0 " + text));
        long big = channelOf(c, "/topics/big");
        c.send("{\"op\":\"subscribe\",\"subscriptions\":[{\"id\":1,\"channelId\":" + big + "}]}");
        c.nextBinary(1);
        c.reading(false);
        int n = 300; // 60 MB: more than the sockets hold, so frames wait in the client's queue
        for (int i = 1; i <= n; i++) {
            s.observe(new Observation.TopicMessage(T0 + i, "big", i + " " + text));
        }
        Await.until("frames were dropped for the slow client", Duration.ofSeconds(60), () -> s.droppedForClients() > 0,
                () -> "published " + s.published() + ", dropped " + s.droppedForClients());
        c.reading(true);
        long last = 0;
        while (last != T0 + n) {
            WsClient.Frame f = c.nextBinary(1);
            assertTrue(f.le().getLong(5) > last, "in order");
            last = f.le().getLong(5);
        }
        assertTrue(s.droppedForClients() > 0);
    }

    // ---- client publishing ----

    @Test
    void aTwistPublishedOnTheRobotsCmdVelDrivesIt() throws Exception {
        FakeTeleop robot = new FakeTeleop();
        FoxgloveServer s = server(robot);
        WsClient c = client(s, SDK);
        JsonNode info = json(c.nextOp("serverInfo"));
        assertEquals("[\"clientPublish\"]", info.get("capabilities").toString());
        assertEquals("[\"json\"]", info.get("supportedEncodings").toString());
        c.send("{\"op\":\"advertise\",\"channels\":[{\"id\":3,\"topic\":\"/robots/nxt/cmd_vel\",\"encoding\":\"json\",\"schemaName\":\"geometry_msgs/Twist\"}]}");
        c.send(WsClient.clientMessage(3, "{\"linear\":{\"x\":0.2,\"y\":0,\"z\":0},\"angular\":{\"x\":0,\"y\":0,\"z\":0.5}}"));
        assertArrayEquals(new double[] {0.2, 0.5}, robot.next());
        c.send("{\"op\":\"unadvertise\",\"channelIds\":[3]}");
        assertArrayEquals(new double[] {0, 0}, robot.next(), "the robot stops when its driver goes");
    }

    @Test
    void theOnlyRobotAlsoListensOnCmdVelAndTheRos2TypeNameIsTaken() throws Exception {
        FakeTeleop robot = new FakeTeleop();
        WsClient c = client(server(robot), LEGACY);
        c.send("{\"op\":\"advertise\",\"channels\":[{\"id\":1,\"topic\":\"/cmd_vel\",\"encoding\":\"json\",\"schemaName\":\"geometry_msgs/msg/Twist\"}]}");
        c.send(WsClient.clientMessage(1, "{\"linear\":{\"x\":-0.1},\"angular\":{\"z\":0}}"));
        assertArrayEquals(new double[] {-0.1, 0}, robot.next());
    }

    @Test
    void aDisconnectingDriverStopsTheRobot() throws Exception {
        FakeTeleop robot = new FakeTeleop();
        FoxgloveServer s = server(robot);
        WsClient c = WsClient.connect(s.address(), SDK);
        c.send("{\"op\":\"advertise\",\"channels\":[{\"id\":1,\"topic\":\"/robots/nxt/cmd_vel\",\"encoding\":\"json\",\"schemaName\":\"geometry_msgs/Twist\"}]}");
        c.send(WsClient.clientMessage(1, "{\"linear\":{\"x\":0.1},\"angular\":{\"z\":0.3}}"));
        assertArrayEquals(new double[] {0.1, 0.3}, robot.next());
        c.close();
        assertArrayEquals(new double[] {0, 0}, robot.next());
    }

    @Test
    void whatCannotDriveIsToldToTheClient() throws Exception {
        FakeTeleop robot = new FakeTeleop();
        WsClient c = client(server(robot), SDK);
        c.send("{\"op\":\"advertise\",\"channels\":[{\"id\":1,\"topic\":\"/robots/ft/cmd_vel\",\"encoding\":\"json\",\"schemaName\":\"geometry_msgs/Twist\"},"
                + "{\"id\":2,\"topic\":\"/robots/nxt/cmd_vel\",\"encoding\":\"cdr\",\"schemaName\":\"geometry_msgs/msg/Twist\"},"
                + "{\"id\":3,\"topic\":\"/robots/nxt/cmd_vel\",\"encoding\":\"json\",\"schemaName\":\"geometry_msgs/Twist\"}]}");
        JsonNode w1 = json(c.nextOp("status"));
        assertEquals(1, w1.get("level").asInt());
        assertTrue(w1.get("message").asText().contains("/robots/R/cmd_vel for R in [nxt]"), w1.toString());
        assertTrue(json(c.nextOp("status")).get("message").asText().contains("as JSON (encoding \"json\"), not \"cdr\""));
        c.send(WsClient.clientMessage(9, "{}"));
        assertEquals("Unknown channel ID: 9", json(c.nextOp("status")).get("message").asText());
        c.send(WsClient.clientMessage(3, "{\"linear\":{\"x\":0.1,\"y\":1},\"angular\":{}}"));
        assertTrue(json(c.nextOp("status")).get("message").asText().startsWith("message on channel 3 (/robots/nxt/cmd_vel): Twist linear.y = 1.0 cannot be driven"));
        robot.refusal = "0.9 m/s is above robot nxt's max_speed 0.5 m/s";
        c.send(WsClient.clientMessage(3, "{\"linear\":{\"x\":0.9},\"angular\":{}}"));
        assertEquals("robot nxt could not drive: 0.9 m/s is above robot nxt's max_speed 0.5 m/s", json(c.nextOp("status")).get("message").asText());
        c.send(WsClient.clientMessage(1, "{\"linear\":{\"x\":0.1},\"angular\":{}}")); // ignored: no robot ft
        sync(c);
        assertTrue(robot.drives.isEmpty(), "nothing was driven");
    }

    @Test
    void aPageFromAnotherSiteMayWatchButNotDrive() throws Exception {
        FakeTeleop robot = new FakeTeleop();
        FoxgloveServer s = server(robot);
        WsClient evil = WsClient.connectFrom("https://example.com", s.address(), SDK);
        open.add(evil);
        assertEquals(0, json(evil.nextOp("serverInfo")).get("capabilities").size());
        evil.send("{\"op\":\"advertise\",\"channels\":[{\"id\":1,\"topic\":\"/robots/nxt/cmd_vel\",\"encoding\":\"json\",\"schemaName\":\"geometry_msgs/Twist\"}]}");
        assertTrue(json(evil.nextOp("status")).get("message").asText().startsWith("Server does not support clientPublish capability for a page from this origin"));
        WsClient foxglove = WsClient.connectFrom("https://app.foxglove.dev", s.address(), SDK);
        open.add(foxglove);
        assertEquals("[\"clientPublish\"]", json(foxglove.nextOp("serverInfo")).get("capabilities").toString());
        WsClient local = WsClient.connectFrom("http://localhost:8080", s.address(), SDK);
        open.add(local);
        assertEquals("[\"clientPublish\"]", json(local.nextOp("serverInfo")).get("capabilities").toString());
    }

    // ---- replays ----

    @Test
    void aReplayOffersTheTimeCapabilityAndSendsTheRecordedTime() throws Exception {
        FoxgloveServer s = server(FoxgloveServer.Options.replay("replay", "127.0.0.1", 0), new FakeTeleop());
        WsClient c = client(s, SDK);
        assertEquals("[\"time\"]", json(c.nextOp("serverInfo")).get("capabilities").toString(), "a replay drives nothing");
        s.observe(pose(T0 + 123, 1.0));
        WsClient.Frame time = c.nextBinary(2);
        assertEquals(9, time.binary().length);
        assertEquals(T0 + 123, time.le().getLong(1));
    }

    /** Issue 37: a handshake naming another Host (a DNS-rebinding page) is refused before it is a session. */
    @Test
    void aHandshakeNamingAnotherHostIsRefused() throws Exception {
        FoxgloveServer s = server(Teleop.NONE);
        String handshake = "GET / HTTP/1.1\r\nHost: %s\r\nUpgrade: websocket\r\nConnection: Upgrade\r\n"
                + "Sec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\nSec-WebSocket-Version: 13\r\nSec-WebSocket-Protocol: foxglove.websocket.v1\r\n\r\n";
        assertTrue(status(s.port(), handshake.formatted("rebound.example:" + s.port())).contains(" 421 "));
        assertTrue(status(s.port(), handshake.formatted("127.0.0.1:" + s.port())).contains(" 101 "));
    }

    /** Issue 37: as the console and the rosbridge, an address beyond this machine needs an access token, and a client without it gets nothing. */
    @Test
    void aBindBeyondThisMachineNeedsATokenAndAClientWithoutItIsRefused() throws Exception {
        IllegalArgumentException e = assertThrows(IllegalArgumentException.class, () -> FoxgloveServer.Options.live("test", "0.0.0.0", 0));
        assertTrue(e.getMessage().contains("0.0.0.0") && e.getMessage().contains(FoxgloveServer.TOKEN_ENV), e.getMessage());
        assertThrows(IllegalArgumentException.class, () -> FoxgloveServer.Options.live("test", "127.0.0.1", 0).listening("192.0.2.7", null));
        assertThrows(IllegalArgumentException.class, () -> FoxgloveServer.Options.live("test", "127.0.0.1", 0).listening("192.0.2.7", "short"));
        String token = "a-token-of-some-length";
        assertFalse(FoxgloveServer.Options.live("test", "127.0.0.1", 0).listening("192.0.2.7", token).toString().contains(token),
                "the options' text does not show the token");
        FoxgloveServer s = server(FoxgloveServer.Options.live("test", "127.0.0.1", 0).listening("127.0.0.1", token), Teleop.NONE);
        String handshake = "GET /%s HTTP/1.1\r\nHost: 127.0.0.1:" + s.port() + "\r\nUpgrade: websocket\r\nConnection: Upgrade\r\n%s"
                + "Sec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\nSec-WebSocket-Version: 13\r\nSec-WebSocket-Protocol: foxglove.websocket.v1\r\n\r\n";
        assertTrue(status(s.port(), handshake.formatted("", "")).contains(" 401 "));
        assertTrue(status(s.port(), handshake.formatted("?token=a-token-of-some-lengtH", "")).contains(" 401 "));
        assertTrue(status(s.port(), handshake.formatted("?token=" + token, "")).contains(" 101 "));
        assertTrue(status(s.port(), handshake.formatted("", "Authorization: Bearer " + token + "\r\n")).contains(" 101 "));
    }

    private static String status(int port, String request) throws java.io.IOException {
        try (java.net.Socket socket = new java.net.Socket("127.0.0.1", port)) {
            socket.setSoTimeout(10_000);
            socket.getOutputStream().write(request.getBytes(java.nio.charset.StandardCharsets.US_ASCII));
            return new java.io.BufferedReader(new java.io.InputStreamReader(socket.getInputStream(), java.nio.charset.StandardCharsets.US_ASCII)).readLine();
        }
    }
}
