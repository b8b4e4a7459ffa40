package io.robomw.agents.messaging;

import io.robomw.testkit.RecordingFailures;
import io.robomw.testkit.Await;
import io.robomw.api.Message;
import io.robomw.api.MessagingException;
import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.Test;

import java.time.Duration;
import java.util.List;
import java.util.UUID;
import java.util.concurrent.CopyOnWriteArrayList;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;

/** Two nodes in this JVM over TCP on loopback. */
class TcpMessagingTest {

    private static final Duration WAIT = Duration.ofSeconds(10);
    private final List<MessagingNode> nodes = new CopyOnWriteArrayList<>();

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
    void subscriberReceivesPublicationsInOrder() {
        MessagingNode pub = node(MessagingNode.builder("pub").bind("tcp://127.0.0.1:0"));
        MessagingNode sub = node(MessagingNode.builder("sub").connect(pub.address("tcp")));
        List<Object> got = new CopyOnWriteArrayList<>();
        sub.addMessageListener("numbers", null, m -> got.add(m.payload()));
        sub.subscribeMessage("numbers", null);
        Await.until("publisher sees the subscriber", WAIT, () -> pub.subscriberCount("numbers") == 1);
        for (int i = 0; i < 1000; i++) {
            pub.publishMessage("numbers", i, "count", null);
        }
        Await.until("1000 publications arrive", WAIT, () -> got.size() == 1000);
        for (int i = 0; i < 1000; i++) {
            assertEquals(i, got.get(i));
        }
    }

    @Test
    void aListenerThatThrowsIsReportedToTheNodesFailurePolicyAndTheLinkDeliversOn() {
        RecordingFailures failures = new RecordingFailures();
        MessagingNode pub = node(MessagingNode.builder("pub").bind("tcp://127.0.0.1:0"));
        MessagingNode sub = node(MessagingNode.builder("sub").failures(failures).connect(pub.address("tcp")));
        List<Object> got = new CopyOnWriteArrayList<>();
        sub.addMessageListener("numbers", null, m -> {
            if (m.payload().equals(1)) {
                throw new NoClassDefFoundError("org/example/Gone");
            }
            got.add(m.payload());
        });
        sub.subscribeMessage("numbers", null);
        Await.until("publisher sees the subscriber", WAIT, () -> pub.subscriberCount("numbers") == 1);
        for (int i = 0; i < 3; i++) {
            pub.publishMessage("numbers", i, "count", null);
        }
        Await.until("the publications after the failed one arrive", WAIT, () -> got.size() == 2);
        assertEquals(List.of(0, 2), got);
        List<RecordingFailures.Report> reports = failures.reports();
        assertEquals(1, reports.size(), reports.toString());
        assertEquals(false, reports.get(0).died());
        assertEquals(NoClassDefFoundError.class, reports.get(0).failure().getClass());
        assertEquals(true, reports.get(0).owner().startsWith("mw-msg-sub-"), "reported under the reading thread: " + reports.get(0).owner());
    }

    @Test
    void requestGetsItsReplyByCorrelationId() {
        MessagingNode server = node(MessagingNode.builder("server").bind("tcp://127.0.0.1:0"));
        server.addMessageListener("echo", null, m -> server.replyMessage(m, "re:" + m.payload(), "ok"));
        MessagingNode client = node(MessagingNode.builder("client"));
        UUID id = client.sendMessage("server", server.address("tcp"), null, "echo", "hello", "say");
        Message reply = client.waitForReply(id, WAIT);
        assertEquals("re:hello", reply.payload());
        assertEquals(id, reply.correlationId());
        assertEquals("server", reply.sender());
    }

    @Test
    void paperWaitForReplyTakesTheNextReplyOnTheTopicFromTheHost() {
        MessagingNode server = node(MessagingNode.builder("server").bind("tcp://127.0.0.1:0"));
        server.addMessageListener("echo", null, m -> server.replyMessage(m, m.payload(), "ok"));
        MessagingNode client = node(MessagingNode.builder("client"));
        client.sendMessage("server", server.address("tcp"), null, "echo", 42, "say");
        assertEquals(42, client.waitForReply("echo", server.address("tcp")).payload());
    }

    @Test
    void waitForReplyGivesUpAfterItsTimeout() {
        MessagingNode server = node(MessagingNode.builder("server").bind("tcp://127.0.0.1:0"));
        server.addMessageListener("silent", null, m -> { });
        MessagingNode client = node(MessagingNode.builder("client"));
        UUID id = client.sendMessage("server", server.address("tcp"), null, "silent", 1, "say");
        MessagingException e = assertThrows(MessagingException.class, () -> client.waitForReply(id, Duration.ofMillis(200)));
        assertEquals(true, e.getMessage().contains("no reply"), e.getMessage());
    }

    @Test
    void messageToTopicWithoutListenerIsRefusedWithAnError() {
        MessagingNode server = node(MessagingNode.builder("server").bind("tcp://127.0.0.1:0"));
        MessagingNode client = node(MessagingNode.builder("client"));
        UUID id = client.sendMessage("server", server.address("tcp"), null, "nobody", 1, "say");
        MessagingException e = assertThrows(MessagingException.class, () -> client.waitForReply(id, WAIT));
        assertEquals(true, e.getMessage().contains("no listener for topic 'nobody'"), e.getMessage());
        assertEquals(1, server.stats().dropped(DropReason.NO_LISTENER));
    }

    @Test
    void aTopicWhoseLastListenerWasRemovedIsForgottenAndAMessageToItIsRefusedAtOnce() {
        MessagingNode server = node(MessagingNode.builder("server").bind("tcp://127.0.0.1:0"));
        io.robomw.api.MessageListener listener = m -> server.replyMessage(m, "here", "ok");
        server.addMessageListener("gone", null, listener);
        assertEquals(true, server.listenedTopics().contains("gone"));
        server.removeMessageListener("gone", listener);
        assertEquals(false, server.listenedTopics().contains("gone"), "no longer listed: " + server.listenedTopics());
        MessagingNode client = node(MessagingNode.builder("client"));
        UUID id = client.sendMessage("server", server.address("tcp"), null, "gone", 1, "say");
        long start = System.nanoTime();
        MessagingException e = assertThrows(MessagingException.class, () -> client.waitForReply(id, Duration.ofSeconds(30)));
        assertEquals(true, e.getMessage().contains("no listener for topic 'gone'"), "refused, not timed out: " + e.getMessage());
        assertEquals(true, System.nanoTime() - start < Duration.ofSeconds(20).toNanos(), "refused well before the wait's 30 s");
    }
}
