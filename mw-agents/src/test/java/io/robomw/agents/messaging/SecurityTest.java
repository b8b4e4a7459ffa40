package io.robomw.agents.messaging;

import io.robomw.testkit.Await;
import io.robomw.api.MessagingException;
import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.Test;

import java.io.Serializable;
import java.time.Duration;
import java.util.List;
import java.util.UUID;
import java.util.concurrent.CopyOnWriteArrayList;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/** Passwords, the allow-list and their counters, over TCP on loopback. */
class SecurityTest {

    private static final Duration WAIT = Duration.ofSeconds(10);
    private final List<MessagingNode> nodes = new CopyOnWriteArrayList<>();

    /** A payload type that is not on anybody's allow-list unless added. */
    record Secret(String text) implements Serializable {
    }

    @AfterEach
    void closeNodes() {
        nodes.forEach(MessagingNode::close);
    }

    private MessagingNode node(MessagingNode.Builder b) {
        MessagingNode n = b.build();
        nodes.add(n);
        return n;
    }

    @Test
    void publicationWithTheWrongPasswordIsDroppedAndCounted() {
        MessagingNode pub = node(MessagingNode.builder("pub").bind("tcp://127.0.0.1:0"));
        MessagingNode sub = node(MessagingNode.builder("sub").connect(pub.address("tcp")));
        List<Object> got = new CopyOnWriteArrayList<>();
        sub.addMessageListener("cmd", "right", m -> got.add(m.payload()));
        sub.subscribeMessage("cmd", "right");
        Await.until("publisher sees the subscriber", WAIT, () -> pub.subscriberCount("cmd") == 1);
        pub.publishMessage("cmd", "forged", "go", "wrong");
        pub.publishMessage("cmd", "unsigned", "go", null);
        pub.publishMessage("cmd", "genuine", "go", "right");
        Await.until("the genuine publication arrives", WAIT, () -> got.size() == 1);
        assertEquals(List.of("genuine"), got);
        assertEquals(1, sub.stats().dropped(DropReason.BAD_MAC));
        assertEquals(1, sub.stats().dropped(DropReason.MISSING_MAC));
    }

    @Test
    void listenerWithTheWrongPasswordIsRefused() {
        MessagingNode n = node(MessagingNode.builder("n"));
        n.addMessageListener("cmd", "right", m -> { });
        MessagingException e = assertThrows(MessagingException.class, () -> n.addMessageListener("cmd", "wrong", m -> { }));
        assertTrue(e.getMessage().contains("password is wrong"), e.getMessage());
        assertThrows(MessagingException.class, () -> n.subscribeMessage("cmd", null));
    }

    @Test
    void requestWithAWrongOrMissingPasswordIsRefusedSayingSo() {
        MessagingNode server = node(MessagingNode.builder("server").bind("tcp://127.0.0.1:0"));
        server.addMessageListener("cmd", "right", m -> server.replyMessage(m, "done", "ok"));
        MessagingNode client = node(MessagingNode.builder("client"));
        UUID bad = client.sendMessage("server", server.address("tcp"), "wrong", "cmd", "x", "go");
        MessagingException wrong = assertThrows(MessagingException.class, () -> client.waitForReply(bad, WAIT));
        assertTrue(wrong.getMessage().contains("topic 'cmd' is password-protected and the message had a wrong password"), wrong.getMessage());
        UUID none = client.sendMessage("server", server.address("tcp"), null, "cmd", "x", "go");
        MessagingException missing = assertThrows(MessagingException.class, () -> client.waitForReply(none, WAIT));
        assertTrue(missing.getMessage().contains("had no password"), missing.getMessage());
        assertEquals(1, server.stats().dropped(DropReason.MISSING_MAC));
        UUID good = client.sendMessage("server", server.address("tcp"), "right", "cmd", "x", "go");
        assertEquals("done", client.waitForReply(good, WAIT).payload());
        assertEquals(1, server.stats().dropped(DropReason.BAD_MAC));
    }

    @Test
    void passwordProtectedRequestToATopicNobodyListensToIsRefusedAtOnce() {
        MessagingNode server = node(MessagingNode.builder("server").bind("tcp://127.0.0.1:0"));
        MessagingNode client = node(MessagingNode.builder("client"));
        UUID id = client.sendMessage("server", server.address("tcp"), "pw", "nobody", "x", "go");
        MessagingException e = assertThrows(MessagingException.class, () -> client.waitForReply(id, WAIT));
        assertTrue(e.getMessage().contains("no listener for topic 'nobody'"), e.getMessage());
    }

    @Test
    void payloadOfAClassNotOnTheAllowListIsRejected() {
        MessagingNode server = node(MessagingNode.builder("server").bind("tcp://127.0.0.1:0"));
        List<Object> got = new CopyOnWriteArrayList<>();
        server.addMessageListener("data", null, m -> got.add(m.payload()));
        MessagingNode client = node(MessagingNode.builder("client"));
        UUID id = client.sendMessage("server", server.address("tcp"), null, "data", new Secret("x"), "store");
        MessagingException e = assertThrows(MessagingException.class, () -> client.waitForReply(id, WAIT));
        assertTrue(e.getMessage().contains(Secret.class.getName()), e.getMessage());
        assertEquals(1, server.stats().dropped(DropReason.REJECTED_CLASS));
        assertEquals(List.of(), got);
    }

    @Test
    void payloadOfAnAllowedClassIsDelivered() {
        MessagingNode server = node(MessagingNode.builder("server").settings(MessagingSettings.defaults().allowPayloadTypes(Secret.class))
                .bind("tcp://127.0.0.1:0"));
        List<Object> got = new CopyOnWriteArrayList<>();
        server.addMessageListener("data", null, m -> got.add(m.payload()));
        MessagingNode client = node(MessagingNode.builder("client"));
        client.sendMessage("server", server.address("tcp"), null, "data", new Secret("x"), "store");
        Await.until("the allowed payload arrives", WAIT, () -> got.size() == 1);
        assertEquals(new Secret("x"), got.get(0));
    }

    @Test
    void payloadTooLargeForTheFrameLimitIsRefusedAtTheSender() {
        MessagingNode server = node(MessagingNode.builder("server").bind("tcp://127.0.0.1:0"));
        MessagingNode client = node(MessagingNode.builder("client").settings(MessagingSettings.defaults().withMaxFrameSize(4096)));
        MessagingException e = assertThrows(MessagingException.class,
                () -> client.sendMessage("server", server.address("tcp"), null, "data", new byte[5000], "store"));
        assertTrue(e.getMessage().contains("maximum frame size of 4096"), e.getMessage());
    }

    /** Issue 37: a protected topic's payloads are sealed under its password; a subscriber that registered it without one reads nothing. */
    @Test
    void aProtectedPublicationIsReadOnlyBySubscribersWithThePassword() {
        MessagingNode pub = node(MessagingNode.builder("pub").bind("tcp://127.0.0.1:0"));
        MessagingNode stranger = node(MessagingNode.builder("stranger").connect(pub.address("tcp")));
        MessagingNode member = node(MessagingNode.builder("member").connect(pub.address("tcp")));
        List<Object> strangerGot = new CopyOnWriteArrayList<>();
        List<Object> memberGot = new CopyOnWriteArrayList<>();
        stranger.addMessageListener("secret", null, m -> strangerGot.add(m.payload()));
        stranger.subscribeMessage("secret", null);
        member.addMessageListener("secret", "s3cret", m -> memberGot.add(m.payload()));
        member.subscribeMessage("secret", "s3cret");
        Await.until("the publisher sees both subscribers", WAIT, () -> pub.subscriberCount("secret") == 2);
        pub.publishMessage("secret", "the launch code", "tell", "s3cret");
        Await.until("the member reads it and the stranger drops it", WAIT,
                () -> memberGot.size() == 1 && stranger.stats().dropped(DropReason.ENCRYPTED) == 1);
        assertEquals(List.of("the launch code"), memberGot);
        assertEquals(List.of(), strangerGot);
    }

    /** Issue 37: a receiver keeps its replay window across a restart, so a frame captured before it is refused after. */
    @Test
    void aRestartedReceiverRefusesAFrameItTookBeforeItsRestart(@org.junit.jupiter.api.io.TempDir java.nio.file.Path replays) throws Exception {
        try (java.net.DatagramSocket tap = new java.net.DatagramSocket(0, java.net.InetAddress.getLoopbackAddress())) {
            tap.setSoTimeout(10_000);
            MessagingNode first = MessagingNode.builder("door").replayDirectory(replays).bind("udp://127.0.0.1:0").build();
            int port = Integer.parseInt(first.address("udp").replaceAll("^.*:(\\d+).*$", "$1"));
            List<Object> got = new CopyOnWriteArrayList<>();
            first.addMessageListener("cmd", "s3cret", m -> got.add(m.payload()));
            MessagingNode sender = node(MessagingNode.builder("sender"));
            sender.sendMessage("door", "udp://127.0.0.1:" + tap.getLocalPort(), "s3cret", "cmd", "open", "go");
            java.net.DatagramPacket captured = new java.net.DatagramPacket(new byte[65_536], 65_536);
            tap.receive(captured);
            byte[] frame = java.util.Arrays.copyOf(captured.getData(), captured.getLength());
            tap.send(new java.net.DatagramPacket(frame, frame.length, java.net.InetAddress.getLoopbackAddress(), port));
            Await.until("the receiver takes it", WAIT, () -> got.size() == 1);
            first.close();

            MessagingNode restarted = node(MessagingNode.builder("door").replayDirectory(replays).bind("udp://127.0.0.1:" + port));
            List<Object> again = new CopyOnWriteArrayList<>();
            restarted.addMessageListener("cmd", "s3cret", m -> again.add(m.payload()));
            tap.send(new java.net.DatagramPacket(frame, frame.length, java.net.InetAddress.getLoopbackAddress(), port));
            Await.until("the restarted receiver refuses the replay", WAIT, () -> restarted.stats().dropped(DropReason.REPLAYED) == 1);
            assertEquals(List.of(), again);
            assertTrue(java.nio.file.Files.exists(replays.resolve("door.replay")));
        }
    }
}
