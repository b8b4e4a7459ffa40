package io.robomw.it.security;

import io.robomw.it.demo.MwProcess;
import org.junit.jupiter.api.Test;

import java.io.BufferedReader;
import java.io.IOException;
import java.io.InputStreamReader;
import java.net.Socket;
import java.net.URI;
import java.nio.charset.StandardCharsets;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;

import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * Issue 37, found 7: the console took a WebSocket whose {@code Host} was any name, so a page of
 * another site whose name was made to resolve to 127.0.0.1 (DNS rebinding: no Origin check helps,
 * the browser thinks it is the same site) read the live data; and its CSP let the page open
 * WebSockets to any host. A real {@code mw console}, asked as such a browser would.
 */
class ConsoleRebindingIT {

    @Test
    void theConsoleAnswersOnlyToItsOwnNamesAndItsPageTalksOnlyToIt() throws Exception {
        try (MwProcess console = MwProcess.start("console-rebinding", "console", "--port", "0")) {
            String line = console.await("console at ", Duration.ofSeconds(60));
            URI page = URI.create(line.substring(line.indexOf("http://")).replaceFirst("#.*$", ""));
            int port = page.getPort();

            List<String> ours = request(port, "GET / HTTP/1.1\r\nHost: 127.0.0.1:" + port + "\r\nConnection: close\r\n\r\n");
            assertTrue(ours.get(0).contains(" 200 "), "the console's own name: " + ours.get(0));
            String csp = ours.stream().filter(h -> h.toLowerCase().startsWith("content-security-policy:")).findFirst().orElse("");
            assertTrue(csp.contains("frame-ancestors 'none'"), "no page may frame it: " + csp);
            assertTrue(csp.contains("ws://127.0.0.1:" + port) && !csp.contains(" ws: ") && !csp.contains("wss:"), "WebSockets to itself only: " + csp);

            String rebound = "GET /live HTTP/1.1\r\nHost: attacker.example:" + port + "\r\nUpgrade: websocket\r\nConnection: Upgrade\r\n"
                    + "Sec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\nSec-WebSocket-Version: 13\r\n\r\n";
            String answer = request(port, rebound).get(0);
            assertFalse(answer.contains(" 101 "), "no live data for a page of another name: " + answer);
            assertTrue(request(port, "GET / HTTP/1.1\r\nHost: attacker.example:" + port + "\r\nConnection: close\r\n\r\n").get(0).contains(" 421 "));
        }
    }

    /** @return the status line and headers of the answer */
    private static List<String> request(int port, String request) throws IOException {
        try (Socket s = new Socket("127.0.0.1", port)) {
            s.setSoTimeout(10_000);
            s.getOutputStream().write(request.getBytes(StandardCharsets.US_ASCII));
            s.getOutputStream().flush();
            BufferedReader r = new BufferedReader(new InputStreamReader(s.getInputStream(), StandardCharsets.US_ASCII));
            List<String> lines = new ArrayList<>();
            for (String l; (l = r.readLine()) != null && !l.isEmpty(); ) {
                lines.add(l);
            }
            return lines;
        }
    }
}
