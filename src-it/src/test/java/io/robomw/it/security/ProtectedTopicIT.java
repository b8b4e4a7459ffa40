package io.robomw.it.security;

import io.robomw.testkit.Ports;
import io.robomw.it.demo.MwProcess;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertNotEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * Issue 37, found 5: {@code mw msg sub tcp://... secret} with no password printed a topic
 * published with a password. Now a protected topic's payloads are encrypted under its password
 * (AES-256-GCM): only a subscriber that registered the topic with the password reads them, and a
 * sniffer on the wire reads nothing.
 */
class ProtectedTopicIT {

    private static final String SECRET = "the launch code is 0000";

    @TempDir
    Path dir;

    @Test
    void aSubscriberWithoutThePasswordReadsNothingOfAProtectedTopic() throws Exception {
        Path password = Files.writeString(dir.resolve("topic.password"), "s3cret\n");
        int port = Ports.free();
        try (MwProcess pub = MwProcess.start("protected-pub", "msg", "pub", "tcp://127.0.0.1:" + port, "secret", SECRET, "--password-file",
                password.toString(), "--count", "0", "--rate", "5");
             TcpTap tap = new TcpTap(port)) {
            pub.await("publishing on", Duration.ofSeconds(60));
            try (MwProcess stranger = MwProcess.start("protected-stranger", "msg", "sub", "tcp://127.0.0.1:" + tap.port(), "secret",
                    "--count", "1", "--timeout", "15s")) {
                assertNotEquals(0, stranger.waitFor(Duration.ofSeconds(60)), "no message reached a subscriber without the password");
                assertFalse(stranger.output().contains("launch code"), stranger.output());
            }
            assertFalse(new String(tap.sentToClients(), StandardCharsets.ISO_8859_1).contains("launch code"),
                    "nothing of it can be read on the wire");
            try (MwProcess member = MwProcess.start("protected-member", "msg", "sub", "tcp://127.0.0.1:" + port, "secret", "--password-file",
                    password.toString(), "--count", "1", "--timeout", "30s")) {
                assertEquals(0, member.waitFor(Duration.ofSeconds(60)), member.output());
                assertTrue(member.output().contains(SECRET), "a subscriber with the password reads it: " + member.output());
            }
        }
    }
}
