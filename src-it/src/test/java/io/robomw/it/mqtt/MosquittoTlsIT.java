package io.robomw.it.mqtt;

import io.robomw.agents.messaging.MessagingNode;
import io.robomw.agents.messaging.MessagingSettings;
import io.robomw.agents.messaging.TestKeys;
import io.robomw.agents.messaging.security.TlsSettings;
import io.robomw.api.MessagingException;
import org.junit.jupiter.api.AfterAll;
import org.junit.jupiter.api.BeforeAll;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.TestInstance;
import org.junit.jupiter.api.io.TempDir;

import java.io.IOException;
import java.nio.file.Path;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.UUID;
import java.util.concurrent.TimeUnit;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * {@code mqtts://}: Mosquitto with a TLS listener whose certificate (made at test time, for
 * 127.0.0.1) the nodes' trust store holds; a node whose trust store does not hold it is refused
 * at the handshake, naming the broker.
 */
@TestInstance(TestInstance.Lifecycle.PER_CLASS)
class MosquittoTlsIT {

    @TempDir
    static Path dir;
    Broker broker;
    TestKeys keys;

    @BeforeAll
    void start() throws Exception {
        keys = TestKeys.create(dir);
        String pw = TestKeys.PASSWORD;
        run("keytool", "-genkeypair", "-alias", "broker", "-keyalg", "EC", "-groupname", "secp256r1", "-dname", "CN=127.0.0.1",
                "-ext", "SAN=ip:127.0.0.1", "-validity", "2", "-keystore", dir.resolve("broker.p12").toString(), "-storetype", "PKCS12",
                "-storepass", pw, "-keypass", pw);
        run("keytool", "-exportcert", "-alias", "broker", "-keystore", dir.resolve("broker.p12").toString(), "-storepass", pw,
                "-file", dir.resolve("broker.cer").toString());
        run("keytool", "-importcert", "-noprompt", "-alias", "broker", "-file", dir.resolve("broker.cer").toString(),
                "-keystore", dir.resolve("broker-trust.p12").toString(), "-storetype", "PKCS12", "-storepass", pw);
        run("openssl", "pkcs12", "-in", dir.resolve("broker.p12").toString(), "-passin", "pass:" + pw, "-nodes",
                "-out", dir.resolve("broker.pem").toString());
        broker = Broker.mosquittoWithTls("broker-tls", dir.resolve("broker.pem"));
    }

    @AfterAll
    void stop() {
        if (broker != null) {
            broker.close();
        }
    }

    private MessagingSettings trusting() {
        return MessagingSettings.defaults().withTls(new TlsSettings(dir.resolve("node.p12"), TestKeys.PASSWORD,
                dir.resolve("broker-trust.p12"), TestKeys.PASSWORD));
    }

    @Test
    void nodesThatTrustTheBrokersCertificateTalkThroughIt() {
        assertTrue(broker.address().startsWith("mqtts://"), broker.address());
        try (MessagingNode a = MessagingNode.builder("tls-a").settings(trusting()).bind(broker.address()).build();
             MessagingNode b = MessagingNode.builder("tls-b").settings(trusting()).bind(broker.address()).build()) {
            a.addMessageListener("cmd", "pw", m -> a.replyMessage(m, "done " + m.payload(), "ok"));
            UUID id = b.sendMessage("tls-a", broker.address(), "pw", "cmd", "go", "run");
            assertEquals("done go", b.waitForReply(id, Duration.ofSeconds(30)).payload());
            try (io.robomw.agents.messaging.mqtt.BrokerDirectory d = io.robomw.agents.messaging.mqtt.BrokerDirectory.open(broker.address(),
                    Duration.ofSeconds(10), trusting().tls())) {
                d.awaitQuiet(Duration.ofSeconds(5));
                assertTrue(d.find("tls-a").isPresent(), "presence read over TLS: " + d.records());
            }
        } catch (java.io.IOException e) {
            throw new java.io.UncheckedIOException(e);
        }
    }

    @Test
    void aNodeThatDoesNotTrustTheBrokerIsRefusedAtTheHandshake() {
        MessagingSettings stranger = MessagingSettings.defaults().withTls(keys.node()); // trusts only the node key, not the broker
        MessagingException e = assertThrows(MessagingException.class,
                () -> MessagingNode.builder("tls-stranger").settings(stranger).bind(broker.address()).build());
        assertTrue(e.getMessage().contains("127.0.0.1") && e.getMessage().matches("(?s).*(SSL|PKIX|certif|handshake).*"), e.getMessage());
    }

    private static void run(String... command) throws IOException, InterruptedException {
        List<String> c = new ArrayList<>(List.of(command));
        if (c.get(0).equals("keytool")) {
            c.set(0, Path.of(System.getProperty("java.home"), "bin", "keytool").toString());
        }
        Process p = new ProcessBuilder(c).redirectErrorStream(true).start();
        String out = new String(p.getInputStream().readAllBytes(), java.nio.charset.StandardCharsets.UTF_8);
        if (!p.waitFor(60, TimeUnit.SECONDS) || p.exitValue() != 0) {
            throw new IOException(String.join(" ", command) + " failed: " + out);
        }
    }
}
