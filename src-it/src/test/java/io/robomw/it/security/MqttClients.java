package io.robomw.it.security;

import org.junit.jupiter.api.Assumptions;

import java.io.IOException;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.TimeUnit;

import static org.junit.jupiter.api.Assertions.fail;

/**
 * Debian's mosquitto-clients ({@code mosquitto_sub}, {@code mosquitto_pub}): an MQTT client that
 * owes RoboMW nothing, as an attacker or a stranger's tool would be. {@code .ci/run} installs them.
 */
final class MqttClients {

    private static final Path SUB = Path.of("/usr/bin/mosquitto_sub");
    private static final Path PUB = Path.of("/usr/bin/mosquitto_pub");

    /** What a client printed (stdout and stderr) and its exit status. */
    record Run(int status, String output) {
    }

    private MqttClients() {
    }

    static void assumeInstalled() {
        Assumptions.assumeTrue(Files.isExecutable(SUB) && Files.isExecutable(PUB),
                "mosquitto-clients is not installed: apt-get install mosquitto-clients (.ci/run installs it)");
    }

    /**
     * @param port  the broker's port on 127.0.0.1
     * @param user  the user name, or {@code null} for an anonymous client
     * @param password its password
     * @param extra mosquitto_sub's other arguments
     */
    static Run sub(int port, String user, String password, String... extra) throws IOException, InterruptedException {
        return run(SUB, port, user, password, extra);
    }

    /** Likewise with mosquitto_pub. */
    static Run pub(int port, String user, String password, String... extra) throws IOException, InterruptedException {
        return run(PUB, port, user, password, extra);
    }

    private static Run run(Path tool, int port, String user, String password, String... extra) throws IOException, InterruptedException {
        List<String> command = new ArrayList<>(List.of(tool.toString(), "-h", "127.0.0.1", "-p", String.valueOf(port)));
        if (user != null) {
            command.addAll(List.of("-u", user, "-P", password));
        }
        command.addAll(List.of(extra));
        Process p = new ProcessBuilder(command).redirectErrorStream(true).start();
        if (!p.waitFor(60, TimeUnit.SECONDS)) {
            p.destroyForcibly();
            fail(tool.getFileName() + " did not end within 60 s");
        }
        return new Run(p.exitValue(), new String(p.getInputStream().readAllBytes(), StandardCharsets.UTF_8));
    }
}
