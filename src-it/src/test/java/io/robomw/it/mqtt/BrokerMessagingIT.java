package io.robomw.it.mqtt;

import io.robomw.testkit.Await;
import io.robomw.agents.messaging.MessagingNode;
import io.robomw.agents.messaging.PresenceRecord;
import io.robomw.agents.messaging.mqtt.BrokerDirectory;
import io.robomw.api.Message;
import io.robomw.api.Pose;
import io.robomw.api.Position;
import io.robomw.api.ReturnType;
import io.robomw.api.Robot;
import io.robomw.api.Robots;
import io.robomw.api.SensorType;
import io.robomw.api.UnsupportedActionException;
import io.robomw.it.messaging.PeerProcess;
import org.junit.jupiter.api.AfterAll;
import org.junit.jupiter.api.BeforeAll;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.TestInstance;

import java.nio.file.Path;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.UUID;
import java.util.concurrent.ExecutorService;
import java.util.concurrent.Executors;
import java.util.concurrent.Future;
import java.util.concurrent.TimeUnit;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * Messaging through an MQTT 5 broker in its own process, between this JVM and peers in others,
 * all on 127.0.0.1: publications and requests across three JVMs, a wrong topic password, a broker
 * restart in the middle of a QoS 1 stream, a subscriber away and back with a persistent session,
 * a remote robot driven through the broker, and presence with a will. Subclasses say which broker.
 */
@TestInstance(TestInstance.Lifecycle.PER_CLASS)
abstract class BrokerMessagingIT {

    static final Duration WAIT = Duration.ofSeconds(60);

    Broker broker;
    PeerProcess server;
    PeerProcess subscriber;
    MessagingNode local;

    abstract Broker.Kind kind();

    String name(String role) {
        return role + "-" + kind().name().toLowerCase(java.util.Locale.ROOT);
    }

    @BeforeAll
    void start() throws Exception {
        broker = Broker.start(kind(), name("broker"));
        server = PeerProcess.peer(name("server"), List.of());
        server.ask("echo echo -", "OK");
        server.ask("listen guarded right", "OK");
        server.ask("bind " + broker.address(), "BOUND");
        subscriber = PeerProcess.peer(name("subscriber"), List.of());
        subscriber.ask("subscribe numbers -", "OK");
        subscriber.ask("bind " + broker.address(), "BOUND");
        local = MessagingNode.builder(name("local")).bind(broker.address()).build();
    }

    @AfterAll
    void stop() {
        for (AutoCloseable c : new AutoCloseable[]{local, server, subscriber, broker}) {
            if (c != null) {
                try {
                    c.close();
                } catch (Exception e) {
                    // closing anyway
                }
            }
        }
    }

    @Test
    void publicationsReachASubscriberInAnotherJvmInOrder() {
        for (int i = 0; i < 2000; i++) {
            local.publishMessage("numbers", i, "count", null);
        }
        assertEquals("COUNT numbers 2000 ordered=true", subscriber.ask("await numbers 2000 60", "COUNT", WAIT.plusSeconds(10)));
    }

    @Test
    void requestsFromTwoJvmsEachGetTheirOwnReply() throws Exception {
        ExecutorService pool = Executors.newFixedThreadPool(4);
        try {
            List<Future<?>> done = new ArrayList<>();
            for (int t = 0; t < 4; t++) {
                int thread = t;
                done.add(pool.submit(() -> {
                    for (int i = 0; i < 50; i++) {
                        String payload = "t" + thread + "-" + i;
                        UUID id = local.sendMessage(name("server"), broker.address(), null, "echo", payload, "ask");
                        Message reply = local.waitForReply(id, WAIT);
                        assertEquals(payload, reply.payload());
                        assertEquals(id, reply.correlationId());
                    }
                    return null;
                }));
            }
            assertEquals("REPLY from-subscriber",
                    subscriber.ask("request " + broker.address() + " " + name("server") + " echo from-subscriber -", "REPLY"));
            for (Future<?> f : done) {
                f.get(WAIT.toSeconds(), TimeUnit.SECONDS);
            }
        } finally {
            pool.shutdownNow();
        }
    }

    @Test
    void aPlainMqttClientsPublicationReachesASubscriberAsTextButNotAProtectedTopic() throws Exception {
        java.util.concurrent.BlockingQueue<Message> plain = new java.util.concurrent.LinkedBlockingQueue<>();
        java.util.concurrent.BlockingQueue<Message> guarded = new java.util.concurrent.LinkedBlockingQueue<>();
        local.addMessageListener("sensors/light", null, plain::add);
        local.subscribeMessage("sensors/light", null);
        local.addMessageListener("sensors/guarded", "pw", guarded::add);
        local.subscribeMessage("sensors/guarded", "pw");
        var device = plainDevice(name("device"));
        try {
            device.publishWith().topic("robomw/pub/sensors/guarded").qos(com.hivemq.client.mqtt.datatypes.MqttQos.AT_LEAST_ONCE)
                    .payload("forged".getBytes(java.nio.charset.StandardCharsets.UTF_8)).send();
            device.publishWith().topic("robomw/pub/sensors/light").qos(com.hivemq.client.mqtt.datatypes.MqttQos.AT_LEAST_ONCE)
                    .payload("412 lux".getBytes(java.nio.charset.StandardCharsets.UTF_8)).send();
        } finally {
            device.disconnect();
        }
        Message m = plain.poll(WAIT.toSeconds(), TimeUnit.SECONDS);
        assertTrue(m != null, "the plain client's publication arrived");
        assertEquals("412 lux", m.payload());
        assertEquals("mqtt", m.sender());
        assertTrue(guarded.isEmpty(), "an unsigned publication on a password-protected topic is dropped");
        assertTrue(local.stats().dropped(io.robomw.agents.messaging.DropReason.MISSING_MAC) >= 1);
    }

    @Test
    void aWrongTopicPasswordIsRefusedAtTheReceiver() {
        long before = dropped(server, "BAD_MAC");
        local.sendMessage(name("server"), broker.address(), "wrong", "guarded", 0, "go");
        local.sendMessage(name("server"), broker.address(), "right", "guarded", 1, "go");
        assertTrue(server.ask("await guarded 1 60", "COUNT", WAIT.plusSeconds(10)).startsWith("COUNT guarded 1 "));
        assertEquals(before + 1, dropped(server, "BAD_MAC"), "the frame signed with the wrong password was dropped, the right one delivered");
        assertTrue(server.ask("count guarded", "COUNT").startsWith("COUNT guarded 1 "));
    }

    @Test
    void aSubscriberAwayAndBackWithAPersistentSessionGetsWhatWasPublishedMeanwhile() throws Exception {
        String address = broker.address() + "?session-expiry=600&client-id=" + name("away");
        try (PeerProcess away = PeerProcess.peer(name("away"), List.of())) {
            away.ask("subscribe news -", "OK");
            away.ask("bind " + address, "BOUND");
        }
        for (int i = 0; i < 100; i++) {
            local.publishMessage("news", i, "count", null);
        }
        try (PeerProcess back = PeerProcess.peer(name("away"), List.of())) {
            back.ask("subscribe news -", "OK");
            back.ask("bind " + address, "BOUND");
            assertEquals("COUNT news 100 ordered=true", back.ask("await news 100 60", "COUNT", WAIT.plusSeconds(10)));
        }
    }

    @Test
    void aBrokerRestartInTheMiddleOfAQos1StreamLosesNothing() throws Exception {
        // A broker of its own: the others' clean sessions would lose what is sent to them while they reconnect.
        try (Broker own = Broker.start(kind(), name("restart-broker"));
             PeerProcess sub = PeerProcess.peer(name("stream-sub"), List.of());
             MessagingNode publisher = MessagingNode.builder(name("stream-pub")).bind(own.address() + "?session-expiry=600").build()) {
            sub.ask("subscribe stream pw", "OK");
            sub.ask("bind " + own.address() + "?session-expiry=600&client-id=" + name("stream-sub"), "BOUND");
            int n = 3000;
            for (int i = 0; i < n / 2; i++) {
                publisher.publishMessage("stream", i, "count", "pw");
            }
            own.restart();
            for (int i = n / 2; i < n; i++) {
                publisher.publishMessage("stream", i, "count", "pw");
            }
            sub.ask("await stream " + n + " 90", "COUNT", WAIT.plusSeconds(60));
            assertEquals("DISTINCT stream " + n + " of " + n, sub.ask("distinct stream", "DISTINCT"),
                    "every publication arrived once (QoS 1 resends; the HMAC'd frames' replay guard drops duplicates)");
        }
    }

    /** A plain MQTT client (no RoboMW), connected to the shared broker. */
    private com.hivemq.client.mqtt.mqtt5.Mqtt5BlockingClient plainDevice(String id) throws java.io.IOException {
        int port = Integer.parseInt(broker.address().substring(broker.address().lastIndexOf(':') + 1));
        var deviceBuilder = com.hivemq.client.mqtt.MqttClient.builder().useMqttVersion5().identifier(id).serverHost("127.0.0.1").serverPort(port);
        // mw broker lets in only its user (issue 37): the device gives the credentials the broker generated for this machine
        io.robomw.agents.messaging.mqtt.BrokerCredentials user = io.robomw.agents.messaging.mqtt.BrokerCredentials.load(null, java.util.Map.of(), "127.0.0.1");
        if (user.username() != null && broker.kind() == Broker.Kind.EMBEDDED) {
            deviceBuilder = deviceBuilder.simpleAuth().username(user.username()).password(user.password()).applySimpleAuth();
        }
        var device = deviceBuilder.buildBlocking();
        device.connect();
        return device;
    }

    /**
     * A sensor-sized publication without a password travels apart from its frame: a RoboMW
     * subscriber gets the whole message, and a plain MQTT client gets the scan's bytes as they are
     * (the frame's head beside them, as the user property {@code robomw-frame}). A PUBLISH whose
     * head is not one is dropped as malformed, counted, and the node goes on.
     */
    @Test
    void aSensorSizedPublicationIsThePlainPayloadForAnMqttClientAndAWholeMessageForANode() throws Exception {
        byte[] scan = new byte[100_000];
        new java.util.Random(36).nextBytes(scan);
        java.util.concurrent.BlockingQueue<Message> got = new java.util.concurrent.LinkedBlockingQueue<>();
        local.addMessageListener("sensors/scan", null, got::add);
        local.subscribeMessage("sensors/scan", null);
        var device = plainDevice(name("scan-reader"));
        try (var seen = device.publishes(com.hivemq.client.mqtt.MqttGlobalPublishFilter.ALL);
             MessagingNode scanner = MessagingNode.builder(name("scanner")).bind(broker.address()).build()) {
            device.subscribeWith().topicFilter("robomw/pub/sensors/scan").qos(com.hivemq.client.mqtt.datatypes.MqttQos.AT_LEAST_ONCE).send();
            scanner.publishMessage("sensors/scan", scan, "lidar", null);
            Message m = got.poll(WAIT.toSeconds(), TimeUnit.SECONDS);
            assertTrue(m != null, "the scan reached the subscribed node");
            assertTrue(java.util.Arrays.equals(scan, (byte[]) m.payload()), "the node got the scan's bytes");
            assertEquals(name("scanner"), m.sender());
            var raw = seen.receive(WAIT.toSeconds(), TimeUnit.SECONDS).orElseThrow(() -> new AssertionError("the plain client got nothing"));
            assertTrue(java.util.Arrays.equals(scan, raw.getPayloadAsBytes()), "the plain client got the scan's bytes as they are, "
                    + raw.getPayloadAsBytes().length + " bytes");
            assertTrue(raw.getUserProperties().asList().stream().anyMatch(u -> u.getName().toString().equals("robomw-frame")),
                    "the frame's head is beside them: " + raw.getUserProperties());

            long malformed = local.stats().dropped(io.robomw.agents.messaging.DropReason.MALFORMED);
            device.publishWith().topic("robomw/pub/sensors/scan").qos(com.hivemq.client.mqtt.datatypes.MqttQos.AT_LEAST_ONCE)
                    .userProperties().add("robomw-frame", "not a head!").applyUserProperties().payload(scan).send();
            Await.until("the PUBLISH with a bad head counted as malformed", WAIT,
                    () -> local.stats().dropped(io.robomw.agents.messaging.DropReason.MALFORMED) > malformed, () -> String.valueOf(local.stats()));
            scanner.publishMessage("sensors/scan", scan, "lidar", null);
            Message again = got.poll(WAIT.toSeconds(), TimeUnit.SECONDS);
            assertTrue(again != null && java.util.Arrays.equals(scan, (byte[]) again.payload()), "the node went on: the next scan arrived");
            assertTrue(got.isEmpty(), "the bad one was not delivered: " + got);
        } finally {
            device.disconnect();
        }
    }

    /**
     * A camera's driver refills its frame buffer as soon as {@code publishMessage} returned: what
     * was published is the frame as it was then, even when it waits in the queue for a broker that
     * is away and is sent only after it is back.
     */
    @Test
    void aSensorSizedPublicationIsTakenAsItWasWhenPublishMessageReturned() throws Exception {
        java.util.concurrent.BlockingQueue<Message> got = new java.util.concurrent.LinkedBlockingQueue<>();
        try (Broker own = Broker.start(kind(), name("reuse-broker"));
             MessagingNode reader = MessagingNode.builder(name("reuse-reader")).bind(own.address() + "?session-expiry=600&client-id=" + name("reuse-reader")).build();
             MessagingNode camera = MessagingNode.builder(name("camera")).bind(own.address()).build()) {
            reader.addMessageListener("frames", null, got::add);
            reader.subscribeMessage("frames", null);
            byte[] buffer = new byte[200_000];
            java.util.Arrays.fill(buffer, (byte) 1);
            own.stop();
            camera.publishMessage("frames", buffer, "image", null);
            java.util.Arrays.fill(buffer, (byte) 2);
            own.restart();
            Message m = got.poll(WAIT.toSeconds(), TimeUnit.SECONDS);
            assertTrue(m != null, "the frame arrived once the broker was back");
            byte[] frame = (byte[]) m.payload();
            assertEquals(200_000, frame.length);
            assertTrue(frame[0] == 1 && frame[199_999] == 1, "the frame as published (1), not as the buffer was refilled after (2): " + frame[0]);
        }
    }

    @Test
    void whileTheBrokerIsAwayAtMostMaxQueuedMessagesWaitAndTheNextIsRefusedNamingTheBroker() throws Exception {
        try (Broker own = Broker.start(kind(), name("bounded-broker"));
             MessagingNode bounded = MessagingNode.builder(name("bounded")).bind(own.address() + "?max-queued=20").build()) {
            own.stop();
            Refusal r = publishUntilRefused(bounded, "bounded", i -> i, 100);
            assertTrue(r.refused() != null && r.accepted() <= 20, r.accepted() + " publications were accepted with the broker away");
            assertTrue(r.refused().getMessage().contains(own.address()), r.refused().getMessage());
        }
    }

    /**
     * Sensor-sized messages fill the queue by their bytes long before its count: with the broker
     * away, 100 KB scans wait up to {@code max-queued-bytes} (1 MiB here; 64 MiB by default), not
     * {@code max-queued} of them (10,000: a gigabyte), and the next is refused naming the broker.
     */
    @Test
    void whileTheBrokerIsAwaySensorSizedMessagesWaitUpToMaxQueuedBytes() throws Exception {
        try (Broker own = Broker.start(kind(), name("bytes-broker"));
             MessagingNode bounded = MessagingNode.builder(name("bytes")).bind(own.address() + "?max-queued-bytes=1048576").build()) {
            own.stop();
            byte[] scan = new byte[100_000];
            Refusal r = publishUntilRefused(bounded, "scans", i -> scan, 1000);
            assertTrue(r.refused() != null && r.accepted() >= 1 && r.accepted() <= 10, r.accepted() + " scans of 100 KB were accepted with the broker away");
            String message = r.refused().getMessage();
            assertTrue(message.contains(own.address()) && message.contains("max-queued-bytes 1048576"), message);
        }
    }

    /**
     * A sender faster than the broker is held at {@code max-in-flight} while connected, not left to
     * pile messages up in the client: with the broker stalled (SIGSTOP: the connection stays up),
     * 8 publications are taken, the ninth waits the send timeout and is refused naming the bound.
     * Once the broker goes on, sending goes on and every publication taken arrives, in order.
     */
    @Test
    void whileConnectedASenderFasterThanTheBrokerIsHeldAtMaxInFlight() throws Exception {
        java.util.concurrent.BlockingQueue<Message> got = new java.util.concurrent.LinkedBlockingQueue<>();
        try (Broker own = Broker.start(kind(), name("window-broker"));
             MessagingNode reader = MessagingNode.builder(name("window-reader")).bind(own.address()).build();
             MessagingNode sender = MessagingNode.builder(name("window"))
                     .settings(io.robomw.agents.messaging.MessagingSettings.defaults().withSendTimeout(Duration.ofSeconds(2)))
                     .bind(own.address() + "?max-in-flight=8").build()) {
            reader.addMessageListener("window", null, got::add);
            reader.subscribeMessage("window", null);
            Refusal r;
            own.pause();
            try {
                r = publishUntilRefused(sender, "window", i -> i, 100);
            } finally {
                own.resume();
            }
            assertEquals(8, r.accepted(), "publications taken while the broker acknowledged none");
            assertTrue(r.refused().getMessage().contains("max-in-flight 8") && r.refused().getMessage().contains(own.address()),
                    r.refused().getMessage());
            sender.publishMessage("window", 8, "count", null);
            List<Object> arrived = new ArrayList<>();
            Await.until("the 9 publications at the reader", WAIT, () -> {
                for (Message m; (m = got.poll()) != null; ) {
                    arrived.add(m.payload());
                }
                return arrived.size() >= 9;
            }, arrived::toString);
            assertEquals(List.of(0, 1, 2, 3, 4, 5, 6, 7, 8), arrived);
        }
    }

    /** How many publications a node took before it refused one, and the refusal ({@code null} if it took them all). */
    private record Refusal(int accepted, io.robomw.api.MessagingException refused) {
    }

    private static Refusal publishUntilRefused(MessagingNode node, String topic, java.util.function.IntFunction<java.io.Serializable> payload,
                                               int most) {
        for (int i = 0; i < most; i++) {
            try {
                node.publishMessage(topic, payload.apply(i), "count", null);
            } catch (io.robomw.api.MessagingException e) {
                return new Refusal(i, e);
            }
        }
        return new Refusal(most, null);
    }

    @Test
    void aRemoteRobotIsDrivenThroughTheBroker() throws Exception {
        Path world = Path.of(getClass().getResource("/robots/sim-world.yaml").toURI());
        try (PeerProcess host = PeerProcess.peer(name("robot-host"), List.of())) {
            host.ask("bind " + broker.address(), "BOUND");
            host.ask("sim " + world + " sim-1 20", "SERVING sim-1");
            try (Robot robot = Robots.remote(broker.address() + "/sim-1")) {
                assertEquals("sim-1", robot.name());
                robot.resetPose(Pose.ORIGIN);
                double before = robot.getValue(Position.FRONT, SensorType.SONAR, ReturnType.CENTIMETERS);
                robot.move(0.25, 0.2);
                double after = robot.getValue(Position.FRONT, SensorType.SONAR, ReturnType.CENTIMETERS);
                assertEquals(25.0, before - after, 3.0, "the wall in front came 25 cm closer (" + before + " -> " + after + ")");
                UnsupportedActionException e = assertThrows(UnsupportedActionException.class, () -> robot.move(1.0, 5.0));
                assertEquals("sim-1", e.robot());
            }
            PresenceRecord p = awaitPresence(name("robot-host"), true);
            assertEquals(List.of("sim-1"), p.robots());
            host.process().destroyForcibly().waitFor(10, TimeUnit.SECONDS);
            assertFalse(awaitPresence(name("robot-host"), false).online(), "the broker published the host's will when it vanished");
        }
    }

    /** Reads the presences until the node's has the wanted status (a will comes after the keep-alive runs out). */
    private PresenceRecord awaitPresence(String node, boolean online) throws Exception {
        try (BrokerDirectory d = BrokerDirectory.open(broker.address(), Duration.ofSeconds(10))) {
            java.util.concurrent.atomic.AtomicReference<PresenceRecord> found = new java.util.concurrent.atomic.AtomicReference<>();
            Await.until((online ? "an online" : "an offline") + " presence of " + node, WAIT, () -> {
                d.records().stream().filter(p -> p.node().equals(node) && p.online() == online).findFirst().ifPresent(found::set);
                return found.get() != null;
            }, () -> String.valueOf(d.records()));
            return found.get();
        }
    }

    private static long dropped(PeerProcess peer, String reason) {
        String stats = peer.ask("stats", "STATS");
        for (String part : stats.split(" ")) {
            if (part.startsWith(reason + "=")) {
                return Long.parseLong(part.substring(reason.length() + 1));
            }
        }
        throw new AssertionError("no " + reason + " in " + stats);
    }
}
