package io.robomw.it.security;

import io.robomw.testkit.Ports;
import io.robomw.it.agents.HostProcess;
import io.robomw.it.demo.MwProcess;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

import java.nio.file.Files;
import java.nio.file.Path;
import java.nio.file.attribute.PosixFilePermissions;
import java.time.Duration;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertNotEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * Issue 37, found 4: {@code mw robot} drove any served robot without a password by default (also
 * through the host's agent-messaging port), and the password was an option's value that showed in
 * {@code ps}. Now {@code mw host --serve} needs a password (from a file or the environment), mutual
 * TLS, or an explicit, loudly logged {@code --serve-insecure}; callers without the password are refused.
 */
class ServedRobotIT {

    @TempDir
    Path dir;

    private static String world() throws Exception {
        return Path.of(ServedRobotIT.class.getResource("/robots/sim-world.yaml").toURI()).toString();
    }

    private Path passwordFile() throws Exception {
        Path f = dir.resolve("serve.password");
        Files.writeString(f, "robot s3cret\n");
        Files.setPosixFilePermissions(f, PosixFilePermissions.fromString("rw-------"));
        return f;
    }

    private static int robot(String name, String address, String... verb) throws Exception {
        String[] args = new String[2 + verb.length];
        args[0] = "robot";
        args[1] = address;
        System.arraycopy(verb, 0, args, 2, verb.length);
        try (MwProcess robot = MwProcess.start(name, args)) {
            return robot.waitFor(Duration.ofSeconds(60));
        }
    }

    @Test
    void aServedRobotNeedsItsPasswordAndTheHostRefusesToServeWithoutOne() throws Exception {
        Path key = Attacker.keyFile(dir);
        try (MwProcess open = MwProcess.start("serve-without-password", "host", "--name", "open", "--port", String.valueOf(Ports.free()),
                "--world", world(), "--world-robot", "sim-1", "--key-file", key.toString(), "--serve", "tcp://127.0.0.1:0")) {
            assertEquals(2, open.waitFor(Duration.ofSeconds(60)), "a host does not serve a robot to anyone by default: " + open.output());
        }
        String why = Files.readString(Path.of("target", "it-logs", "serve-without-password.log"));
        assertTrue(why.contains("--serve-password-file") && why.contains("--serve-insecure"), "it says what to give: " + why);

        Path password = passwordFile();
        try (HostProcess host = HostProcess.start("served", "--world", world(), "--world-robot", "sim-1", "--key-file", key.toString(),
                "--serve", "tcp://127.0.0.1:0", "--serve-password-file", password.toString())) {
            assertNotEquals(0, robot("served-no-password", host.served(), "move", "0.2", "0.1"), "a caller without the password is refused");
            String refusal = Files.readString(Path.of("target", "it-logs", "served-no-password.log"));
            assertTrue(refusal.contains("password"), "it is told a password is needed: " + refusal);
            String messagingPort = host.messaging() + "/sim-1";
            assertNotEquals(0, robot("served-by-messaging-port", messagingPort, "move", "0.2", "0.1"),
                    "nor through the host's agent-messaging port");
            assertEquals(0, robot("served-with-password", host.served() + "?password-file=" + password, "move", "0.2", "0.1"),
                    "a caller with the password file drives it");
        }
    }

    @Test
    void servingWithoutAPasswordTakesAnExplicitOptionAndIsLoud() throws Exception {
        Path key = Attacker.keyFile(dir);
        try (HostProcess host = HostProcess.start("served-insecure", "--world", world(), "--world-robot", "sim-1", "--key-file", key.toString(),
                "--serve", "tcp://127.0.0.1:0", "--serve-insecure")) {
            assertTrue(host.log().contains("WITHOUT A PASSWORD"), "the host says so: " + host.log());
            assertEquals(0, robot("served-insecure-robot", host.served(), "pose"), "a lab that asked for it gets it");
        }
    }
}
