package io.robomw.config.description;

import io.robomw.api.spi.AgencyConfig;
import io.robomw.api.spi.MessagingConfig;
import io.robomw.api.spi.SecretRef;
import io.robomw.config.description.DescriptionException.Problem;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

import java.nio.file.Files;
import java.nio.file.Path;
import java.util.List;
import java.util.Map;
import java.util.Optional;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/** The robot file's messaging: and agency: sections, and the defaults without them. */
class ComponentSectionsTest {

    private static final String HEAD = "name: nxt-1\nplatform: sim\n";

    private final RobotDescriptionLoader loader = new RobotDescriptionLoader();

    private Problem onlyProblem(String yaml) {
        DescriptionException e = assertThrows(DescriptionException.class, () -> loader.parse(yaml, "robot.yaml"));
        assertEquals(1, e.problems().size(), () -> "expected one problem, got " + e.problems());
        return e.problems().get(0);
    }

    @Test
    void aRobotWithoutSectionsStartsMessagingOnFirstUseAndHasAHomeNamedAfterIt() {
        RobotDescription d = loader.parse(HEAD, "robot.yaml");
        assertEquals(MessagingConfig.defaults("nxt-1", "robot.yaml"), d.messaging());
        assertTrue(d.messaging().startsOnFirstUse());
        assertEquals("nxt-1-home", d.agency().homeName());
        assertEquals(Optional.empty(), d.agency().clusterKey());
    }

    @Test
    void theSectionsSayWhereTheNodeListensWhomItConnectsToAndWhereSecretsAreKept(@TempDir Path dir) throws Exception {
        Path file = dir.resolve("robot.yaml");
        Files.writeString(file, HEAD + """
                messaging:
                  name: nxt-node
                  listen: tcp://127.0.0.1:7100
                  connect: [tcp://127.0.0.1:7000, udp://127.0.0.1:7001]
                  topics:
                    alerts: { password_file: keys/alerts.key }
                    status: { password_env: MW_STATUS_PASSWORD }
                agency:
                  home_name: lab-home
                  port: 1200
                  key_env: MY_CLUSTER
                """);
        RobotDescription d = loader.load(file);
        MessagingConfig m = d.messaging();
        assertEquals("nxt-node", m.nodeName());
        assertEquals(List.of("tcp://127.0.0.1:7100"), m.listen());
        assertEquals(List.of("tcp://127.0.0.1:7000", "udp://127.0.0.1:7001"), m.connect());
        assertEquals(Map.of(
                "alerts", new SecretRef(SecretRef.Kind.FILE, dir.resolve("keys/alerts.key").toString(), file.toString()),
                "status", new SecretRef(SecretRef.Kind.ENVIRONMENT, "MW_STATUS_PASSWORD", file.toString())), m.topicPasswords());
        AgencyConfig a = d.agency();
        assertEquals("lab-home", a.homeName());
        assertEquals(1200, a.port());
        assertEquals(Optional.of(new SecretRef(SecretRef.Kind.ENVIRONMENT, "MY_CLUSTER", file.toString())), a.clusterKey());
    }

    @Test
    void aPasswordWrittenIntoTheFileIsRefusedWithWhereItIsAndWhatToWriteInstead() {
        Problem p = onlyProblem(HEAD + "messaging:\n  topics:\n    alerts: { password: hunter2 }\n");
        assertEquals(5, p.line());
        assertTrue(p.message().contains("never write a secret") && p.message().contains("password_file"), p.toString());
    }

    @Test
    void anInlineClusterKeyIsRefusedToo() {
        Problem p = onlyProblem(HEAD + "agency:\n  key: letmein\n");
        assertEquals(4, p.line());
        assertTrue(p.message().contains("key_file") && p.message().contains("key_env"), p.toString());
    }

    @Test
    void aSecretKeptInTwoPlacesIsRefused() {
        Problem p = onlyProblem(HEAD + "agency:\n  key_file: a.key\n  key_env: B\n");
        assertTrue(p.message().contains("not both"), p.toString());
    }

    @Test
    void anAddressWithoutSchemeOrPortIsRefused() {
        assertTrue(onlyProblem(HEAD + "messaging:\n  listen: 127.0.0.1:7000\n").message().contains("scheme"));
        assertTrue(onlyProblem(HEAD + "messaging:\n  connect: [tcp://127.0.0.1]\n").message().contains("host and a port"));
    }

    @Test
    void anUnknownKeyInASectionIsNamed() {
        Problem p = onlyProblem(HEAD + "messaging:\n  listn: tcp://127.0.0.1:0\n");
        assertTrue(p.message().contains("unknown key 'messaging.listn'"), p.toString());
    }
}
