package io.robomw.agents.messaging;

import io.robomw.api.MessagingException;
import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.BeforeAll;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

import java.nio.file.Path;
import java.time.Duration;
import java.util.List;
import java.util.UUID;
import java.util.concurrent.CopyOnWriteArrayList;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;

/** Mutual TLS over TCP: both sides must hold a trusted key. */
class TlsTest {

    @TempDir
    static Path dir;
    private static TestKeys keys;
    private final List<MessagingNode> nodes = new CopyOnWriteArrayList<>();

    @BeforeAll
    static void makeKeys() throws Exception {
        keys = TestKeys.create(dir);
    }

    @AfterEach
    void closeNodes() {
        nodes.forEach(MessagingNode::close);
    }

    private MessagingNode node(String name, MessagingSettings settings, String bind) {
        MessagingNode.Builder b = MessagingNode.builder(name).settings(settings);
        if (bind != null) {
            b.bind(bind);
        }
        MessagingNode n = b.build();
        nodes.add(n);
        return n;
    }

    @Test
    void peersWithTrustedKeysTalk() {
        MessagingNode server = node("server", MessagingSettings.defaults().withTls(keys.node()), "tcp://127.0.0.1:0");
        server.addMessageListener("echo", null, m -> server.replyMessage(m, m.payload(), "ok"));
        MessagingNode client = node("client", MessagingSettings.defaults().withTls(keys.node()), null);
        UUID id = client.sendMessage("server", server.address("tcp"), null, "echo", "over tls", "say");
        assertEquals("over tls", client.waitForReply(id, Duration.ofSeconds(10)).payload());
    }

    @Test
    void aCallerWithoutReplySpinGetsItsRepliesOverTls() {
        // Without a reply spin a caller reads a plain link itself; a TLS link stays with its reader thread (and its read timeout).
        MessagingSettings noSpin = MessagingSettings.defaults().withTls(keys.node()).withReplySpin(Duration.ZERO);
        MessagingNode server = node("server", noSpin, "tcp://127.0.0.1:0");
        server.addMessageListener("echo", null, m -> server.replyMessage(m, m.payload(), "ok"));
        MessagingNode client = node("client", noSpin, null);
        for (int i = 0; i < 200; i++) {
            UUID id = client.sendMessage("server", server.address("tcp"), null, "echo", "over tls " + i, "say");
            assertEquals("over tls " + i, client.waitForReply(id, Duration.ofSeconds(10)).payload());
        }
    }

    @Test
    void clientWithAnUntrustedKeyIsTurnedAway() {
        MessagingNode server = node("server", MessagingSettings.defaults().withTls(keys.node()), "tcp://127.0.0.1:0");
        List<Object> got = new CopyOnWriteArrayList<>();
        server.addMessageListener("echo", null, m -> got.add(m.payload()));
        MessagingNode client = node("client", MessagingSettings.defaults().withTls(keys.stranger()).withReplyTimeout(Duration.ofSeconds(2)), null);
        assertThrows(MessagingException.class, () -> {
            UUID id = client.sendMessage("server", server.address("tcp"), null, "echo", "let me in", "say");
            client.waitForReply(id, Duration.ofSeconds(2));
        });
        assertEquals(List.of(), got);
    }

    @Test
    void plainClientIsTurnedAway() {
        MessagingNode server = node("server", MessagingSettings.defaults().withTls(keys.node()), "tcp://127.0.0.1:0");
        List<Object> got = new CopyOnWriteArrayList<>();
        server.addMessageListener("echo", null, m -> got.add(m.payload()));
        MessagingNode client = node("client", MessagingSettings.defaults(), null);
        assertThrows(MessagingException.class, () -> {
            UUID id = client.sendMessage("server", server.address("tcp"), null, "echo", "plain", "say");
            client.waitForReply(id, Duration.ofSeconds(2));
        });
        assertEquals(List.of(), got);
    }
}
