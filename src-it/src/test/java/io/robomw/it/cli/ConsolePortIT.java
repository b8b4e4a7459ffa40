package io.robomw.it.cli;

import io.robomw.it.demo.MwProcess;
import org.junit.jupiter.api.Test;

import java.io.IOException;
import java.net.InetAddress;
import java.net.InetSocketAddress;
import java.net.ServerSocket;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;

import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

/** {@code mw console} whose default port is taken takes a free one and says so, where a port given with --port is kept. */
class ConsolePortIT {

    @Test
    void theDefaultPortTakenTheConsoleChoosesAFreeOneAndPrintsIt() throws Exception {
        // Port 8080 is taken: by this socket, or by whatever else on the machine holds it already.
        try (ServerSocket taken = holdIfFree(8080); MwProcess console = MwProcess.start("console-port", "console")) {
            String line = console.await("console at ", Duration.ofSeconds(60));
            assertTrue(line.startsWith("console at http://127.0.0.1:"), line);
            assertFalse(line.startsWith("console at http://127.0.0.1:8080/"), "not the taken port: " + line);
            String log = Files.readString(Path.of("target", "it-logs", "console-port.log"));
            assertTrue(log.contains("mw console: port 8080 on 127.0.0.1 is taken; the page takes a free port instead"), log);
        }
    }

    private static ServerSocket holdIfFree(int port) throws IOException {
        ServerSocket s = new ServerSocket();
        try {
            s.bind(new InetSocketAddress(InetAddress.getLoopbackAddress(), port));
        } catch (IOException alreadyTaken) {
            // someone else holds it: taken all the same
        }
        return s;
    }
}
