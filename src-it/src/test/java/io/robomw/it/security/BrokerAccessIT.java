package io.robomw.it.security;

import io.robomw.testkit.Ports;
import io.robomw.it.agents.HostProcess;
import io.robomw.it.demo.MwProcess;
import org.junit.jupiter.api.BeforeEach;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.Properties;
import java.util.regex.Matcher;
import java.util.regex.Pattern;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertNotEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * Issue 37, found 6: an anonymous {@code mosquitto_sub -t 'robomw/#'} on {@code mw broker} read
 * every request, reply and presence; a retained fake presence record marked a real host offline
 * and listed a fake one under its name in {@code mw agents --cluster}. Now the broker lets in its
 * user only (credentials generated on first start into a file only the user can read), a client
 * may publish a presence under its own client id only, and readers with the cluster key take only
 * presences signed with it, counting the others.
 */
class BrokerAccessIT {

    @TempDir
    Path dir;
    private Path credentials;

    @BeforeEach
    void tools() {
        MqttClients.assumeInstalled();
        credentials = dir.resolve("broker.credentials");
    }

    private MwProcess broker(int port) throws Exception {
        MwProcess broker = MwProcess.start("broker-access-" + port, "broker", "--port", String.valueOf(port), "--credentials", credentials.toString(),
                "--data", dir.resolve("data").toString());
        broker.await("mqtt broker ready", Duration.ofSeconds(60));
        return broker;
    }

    private String password() throws Exception {
        Properties p = new Properties();
        try (var r = Files.newBufferedReader(credentials)) {
            p.load(r);
        }
        return p.getProperty("password");
    }

    private String at(int port) {
        return "mqtt://127.0.0.1:" + port + "?credentials=" + credentials;
    }

    @Test
    void anAnonymousClientReadsNothingAndTheUserEverything() throws Exception {
        int port = Ports.free();
        try (MwProcess broker = broker(port);
             MwProcess node = MwProcess.start("broker-access-node", "msg", "sub", at(port), "news", "--name", "lab-node")) {
            node.await("listening to topic", Duration.ofSeconds(60));
            if (Files.exists(credentials)) {
                assertEquals("rw-------", java.nio.file.attribute.PosixFilePermissions.toString(Files.getPosixFilePermissions(credentials)),
                        "the generated credentials are the user's alone");
            }
            MqttClients.Run anonymous = MqttClients.sub(port, null, null, "-t", "robomw/#", "-v", "-C", "1", "-W", "10");
            assertNotEquals(0, anonymous.status(), "an anonymous client is refused: " + anonymous.output());
            assertFalse(anonymous.output().contains("robomw-presence"), "and reads nothing: " + anonymous.output());
            assertTrue(anonymous.output().toLowerCase().contains("not authori"), anonymous.output());

            MqttClients.Run user = MqttClients.sub(port, "robomw", password(), "-t", "robomw/presence/+", "-v", "-C", "1", "-W", "20");
            assertEquals(0, user.status(), "the broker's user gets in: " + user.output());
            assertTrue(user.output().contains("node lab-node"), user.output());
        }
    }

    @Test
    void aClientCannotReplaceAnotherNodesPresence() throws Exception {
        int port = Ports.free();
        try (MwProcess broker = broker(port);
             MwProcess node = MwProcess.start("broker-presence-node", "msg", "sub", at(port), "news", "--name", "lab-node")) {
            node.await("listening to topic", Duration.ofSeconds(60));
            MqttClients.Run before = MqttClients.sub(port, "robomw", password(), "-t", "robomw/presence/+", "-v", "-C", "1", "-W", "20");
            Matcher topic = Pattern.compile("(robomw/presence/\\S+)").matcher(before.output());
            assertTrue(topic.find(), before.output());
            MqttClients.pub(port, "robomw", password(), "-r", "-q", "1", "-t", topic.group(1), "-m", "robomw-presence 1\nnode lab-node\nstatus offline\n");
            MqttClients.Run after = MqttClients.sub(port, "robomw", password(), "-t", topic.group(1), "-C", "1", "-W", "20");
            assertTrue(after.output().contains("status online"), "the node's own presence stands: " + after.output());
        }
    }

    @Test
    void aFakeHostPresenceIsIgnoredAndCountedByReadersWithTheClusterKey() throws Exception {
        int port = Ports.free();
        Path key = Attacker.keyFile(dir);
        try (MwProcess broker = broker(port);
             HostProcess host = HostProcess.start("lab-a", "--key-file", key.toString(), "--messaging", at(port))) {
            String fake = "robomw-presence 1\nnode lab-a\nstatus online\ntime 2030-01-01T00:00:00Z\nclient evil\nsession-expiry 0\n"
                    + "messaging mqtt://127.0.0.1:1\nhost lab-a rmi://127.0.0.1:1/lab-a\n";
            MqttClients.Run published = MqttClients.pub(port, "robomw", password(), "-i", "evil", "-r", "-q", "1", "-t", "robomw/presence/evil", "-m", fake);
            assertEquals(0, published.status(), "a client may publish its own presence: " + published.output());
            String[] listed = {""};
            // a reader takes what the broker sends within a moment of quiet: on a loaded machine it may ask again
            io.robomw.testkit.Await.until("mw agents --cluster lists the real host", Duration.ofSeconds(120), () -> {
                try (MwProcess agents = MwProcess.start("broker-presence-agents", "agents", "--cluster", at(port), "--key-file", key.toString())) {
                    agents.waitFor(Duration.ofSeconds(60));
                    listed[0] = agents.output();
                    return listed[0].contains(host.address());
                } catch (Exception e) {
                    throw new IllegalStateException(e);
                }
            }, () -> listed[0]);
            assertTrue(listed[0].contains("1 agent host at"), "only the real host: " + listed[0]);
            assertFalse(listed[0].contains("rmi://127.0.0.1:1/lab-a"), "the fake one is not listed: " + listed[0]);
            assertTrue(listed[0].contains("presence record ignored") || listed[0].contains("presence records ignored"), "and is counted: " + listed[0]);
        }
    }
}
