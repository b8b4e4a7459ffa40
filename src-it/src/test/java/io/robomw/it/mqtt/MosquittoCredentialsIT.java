package io.robomw.it.mqtt;

import io.robomw.agents.messaging.MessagingNode;
import io.robomw.api.Message;
import io.robomw.api.MessagingException;
import org.junit.jupiter.api.AfterAll;
import org.junit.jupiter.api.BeforeAll;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.TestInstance;
import org.junit.jupiter.api.io.TempDir;

import java.nio.file.Files;
import java.nio.file.Path;
import java.nio.file.attribute.PosixFilePermissions;
import java.time.Duration;
import java.util.UUID;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * Broker credentials from a file: Mosquitto with one user and no anonymous access lets in a node
 * whose address names the credentials file, and refuses one without credentials or with the
 * wrong password, saying which broker refused it.
 */
@TestInstance(TestInstance.Lifecycle.PER_CLASS)
class MosquittoCredentialsIT {

    @TempDir
    Path dir;
    Broker broker;

    @BeforeAll
    void start() throws Exception {
        broker = Broker.mosquittoWithUser("broker-credentials", "robot", "s3cret-pw");
    }

    @AfterAll
    void stop() {
        if (broker != null) {
            broker.close();
        }
    }

    private Path credentials(String file, String password) throws Exception {
        Path f = dir.resolve(file);
        Files.writeString(f, "username=robot\npassword=" + password + "\n");
        Files.setPosixFilePermissions(f, PosixFilePermissions.fromString("rw-------"));
        return f;
    }

    @Test
    void aNodeWithTheCredentialsFileGetsIn() throws Exception {
        String address = broker.address() + "?credentials=" + credentials("good", "s3cret-pw");
        try (MessagingNode a = MessagingNode.builder("cred-a").bind(address).build();
             MessagingNode b = MessagingNode.builder("cred-b").bind(address).build()) {
            a.addMessageListener("cmd", null, m -> a.replyMessage(m, "done", "ok"));
            UUID id = b.sendMessage("cred-a", address, null, "cmd", "go", "run");
            Message reply = b.waitForReply(id, Duration.ofSeconds(30));
            assertEquals("done", reply.payload());
        }
    }

    @Test
    void aNodeWithoutCredentialsOrWithAWrongPasswordIsRefusedNamingTheBroker() throws Exception {
        MessagingException anonymous = assertThrows(MessagingException.class, () -> MessagingNode.builder("cred-anon").bind(broker.address()).build());
        assertTrue(anonymous.getMessage().contains("127.0.0.1") && anonymous.getMessage().contains("refused"), anonymous.getMessage());
        String wrong = broker.address() + "?credentials=" + credentials("wrong", "not-it");
        MessagingException e = assertThrows(MessagingException.class, () -> MessagingNode.builder("cred-wrong").bind(wrong).build());
        assertTrue(e.getMessage().contains("refused"), e.getMessage());
        assertTrue(!e.getMessage().contains("not-it"), "the password is not in the message: " + e.getMessage());
    }
}
