package io.robomw.console.server;

import com.fasterxml.jackson.databind.JsonNode;
import com.fasterxml.jackson.databind.ObjectMapper;
import io.robomw.testkit.Await;
import io.robomw.console.observe.HostView;
import io.robomw.console.observe.Observation;
import io.robomw.console.observe.WorldMap;
import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.BeforeEach;
import org.junit.jupiter.api.Test;

import java.net.URI;
import java.net.http.HttpClient;
import java.net.http.HttpRequest;
import java.net.http.HttpResponse;
import java.net.http.WebSocket;
import java.net.http.WebSocketHandshakeException;
import java.time.Duration;
import java.util.List;
import java.util.UUID;
import java.util.concurrent.BlockingQueue;
import java.util.concurrent.CompletionException;
import java.util.concurrent.CompletionStage;
import java.util.concurrent.CopyOnWriteArrayList;
import java.util.concurrent.LinkedBlockingQueue;
import java.util.concurrent.TimeUnit;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertInstanceOf;
import static org.junit.jupiter.api.Assertions.assertNotNull;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/** The console's server on loopback, spoken to as a page would: HTTP for the files, the WebSocket for updates and requests. */
class ConsoleServerTest {

    private static final ObjectMapper JSON = new ObjectMapper();
    private static final Duration WITHIN = Duration.ofSeconds(10);
    private final List<String> retracted = new CopyOnWriteArrayList<>();
    private final ConsoleView view = new ConsoleView("test");
    private ConsoleServer server;
    private final HttpClient http = HttpClient.newHttpClient();

    /** A test double of the buttons: remembers what it was asked. */
    private final Controls controls = new Controls() {
        @Override
        public boolean agentsControllable() {
            return true;
        }

        @Override
        public String retract(UUID agent) {
            retracted.add(agent.toString());
            return "retract sent";
        }

        @Override
        public String dispose(UUID agent) {
            throw new IllegalStateException("agent " + agent + " is not at any host this console watches");
        }

        @Override
        public String stop(String robot) {
            return "robot " + robot + " stopped";
        }

        @Override
        public java.util.Set<String> stoppableRobots() {
            return java.util.Set.of("nxt");
        }
    };

    @BeforeEach
    void start() throws Exception {
        server = ConsoleServer.start(view, controls, "127.0.0.1", 0, io.robomw.api.spi.FailurePolicy.logging());
    }

    @AfterEach
    void stop() {
        server.close();
    }

    private final class Page implements WebSocket.Listener {
        final BlockingQueue<JsonNode> received = new LinkedBlockingQueue<>();
        private final StringBuilder partial = new StringBuilder();
        WebSocket socket;

        @Override
        public CompletionStage<?> onText(WebSocket webSocket, CharSequence data, boolean last) {
            partial.append(data);
            if (last) {
                try {
                    received.add(JSON.readTree(partial.toString()));
                } catch (Exception e) {
                    throw new AssertionError("the console sent text that is not JSON: " + partial, e);
                }
                partial.setLength(0);
            }
            webSocket.request(1);
            return null;
        }

        JsonNode next(String type) throws InterruptedException {
            long deadline = System.nanoTime() + WITHIN.toNanos();
            while (true) {
                JsonNode n = received.poll(Math.max(1, deadline - System.nanoTime()), TimeUnit.NANOSECONDS);
                assertNotNull(n, "no " + type + " message within " + WITHIN);
                if (n.get("type").asText().equals(type)) {
                    return n;
                }
            }
        }
    }

    private Page open() {
        Page p = new Page();
        p.socket = http.newWebSocketBuilder().header("Origin", "http://127.0.0.1:" + server.port())
                .buildAsync(URI.create("ws://127.0.0.1:" + server.port() + "/live"), p).join();
        return p;
    }

    @Test
    void thePageAndItsScriptComeFromTheConsoleItselfAndNothingElseIsServed() throws Exception {
        HttpResponse<String> page = http.send(HttpRequest.newBuilder(server.address()).build(), HttpResponse.BodyHandlers.ofString());
        assertEquals(200, page.statusCode());
        assertTrue(page.body().contains("<script src=\"console.js\">"));
        String csp = page.headers().firstValue("Content-Security-Policy").orElse("");
        assertTrue(csp.contains("default-src 'self'") && csp.contains("frame-ancestors 'none'"), csp);
        assertTrue(csp.contains("connect-src 'self' ws://127.0.0.1:" + server.port() + ";") && !csp.matches(".*\\sws:\\s.*") && !csp.contains("wss:"),
                "WebSockets to the console only: " + csp);
        HttpResponse<String> script = http.send(HttpRequest.newBuilder(server.address().resolve("/console.js")).build(), HttpResponse.BodyHandlers.ofString());
        assertEquals("text/javascript; charset=utf-8", script.headers().firstValue("Content-Type").orElseThrow());
        String withoutSvgNamespace = script.body().replace("\"http://www.w3.org/2000/svg\"", "");
        assertFalse(withoutSvgNamespace.contains("http://") || withoutSvgNamespace.contains("https://"), "the script loads nothing from elsewhere");
        HttpResponse<String> other = http.send(HttpRequest.newBuilder(server.address().resolve("/etc/passwd")).build(), HttpResponse.BodyHandlers.ofString());
        assertEquals(404, other.statusCode());
        HttpResponse<String> climbing = http.send(HttpRequest.newBuilder(URI.create(server.address() + "..%2F..%2Fetc%2Fpasswd")).build(),
                HttpResponse.BodyHandlers.ofString());
        assertTrue(climbing.statusCode() == 400 || climbing.statusCode() == 404, "refused: " + climbing.statusCode());
    }

    @Test
    void aPageGetsTheWorldRobotsAndHostsThenOnlyNewTrailPoints() throws Exception {
        view.observe(new Observation.World(1, new WorldMap("arena", 4, 3, true, 0.1, 0.8, List.of(), List.of(), List.of())));
        view.observe(new Observation.RobotPose(1_000_000_000L, "nxt", 1, 1, 0, true));
        view.observe(new Observation.HostSeen(1, new HostView("rmi://127.0.0.1:1/a", "a", true, "nxt", List.of(), null, "", 1)));
        Page p = open();
        JsonNode first = p.next("update");
        assertEquals("arena", first.get("world").get("name").asText());
        assertEquals("nxt", first.get("robots").get(0).get("name").asText());
        assertEquals(1, first.get("robots").get(0).get("trail").size());
        assertEquals("a", first.get("hosts").get(0).get("name").asText());
        assertTrue(first.get("hosts").get(0).get("owed").isNull(), "owed deliveries: not reported");
        assertEquals("nxt", first.get("controls").get("stoppable").get(0).asText());
        view.observe(new Observation.RobotPose(2_000_000_000L, "nxt", 1.5, 1, 0, true));
        Await.until("the page gets the new trail point alone", WITHIN, () -> {
            JsonNode u = p.received.poll();
            return u != null && u.get("robots").get(0).get("trail").size() == 1
                    && u.get("robots").get(0).get("trail").get(0).get(1).asDouble() == 1.5 && !u.has("world");
        });
    }

    @Test
    void badRequestsGetARepliedReasonAndTheConnectionStaysOpen() throws Exception {
        Page p = open();
        p.next("update");
        p.socket.sendText("this is not JSON", true).join();
        JsonNode r = p.next("reply");
        assertFalse(r.get("ok").asBoolean());
        assertTrue(r.get("message").asText().startsWith("bad request: not JSON"), r.toString());
        p.socket.sendText("{\"op\":\"stop\",\"robot\":\"nxt\",\"token\":\"" + token() + "\",\"id\":3}", true).join();
        JsonNode stopped = p.next("reply");
        assertTrue(stopped.get("ok").asBoolean(), stopped.toString());
        assertEquals(3, stopped.get("id").asInt());
        assertEquals("robot nxt stopped", stopped.get("message").asText());
    }

    @Test
    void buttonsNeedTheAccessTokenPrintedWithTheAddress() throws Exception {
        Page p = open();
        p.next("update");
        UUID agent = UUID.randomUUID();
        p.socket.sendText("{\"op\":\"retract\",\"agent\":\"" + agent + "\",\"token\":\"guess\"}", true).join();
        JsonNode refused = p.next("reply");
        assertFalse(refused.get("ok").asBoolean());
        assertTrue(refused.get("message").asText().contains("needs the access token"), refused.toString());
        assertTrue(retracted.isEmpty());
        p.socket.sendText("{\"op\":\"retract\",\"agent\":\"" + agent + "\",\"token\":\"" + token() + "\"}", true).join();
        assertTrue(p.next("reply").get("ok").asBoolean());
        assertEquals(List.of(agent.toString()), retracted);
        p.socket.sendText("{\"op\":\"dispose\",\"agent\":\"" + agent + "\",\"token\":\"" + token() + "\"}", true).join();
        JsonNode failed = p.next("reply");
        assertFalse(failed.get("ok").asBoolean());
        assertTrue(failed.get("message").asText().contains("is not at any host this console watches"), failed.toString());
    }

    @Test
    void aWebSocketFromAnotherSiteIsRefused() {
        CompletionException e = assertThrows(CompletionException.class, () -> http.newWebSocketBuilder().header("Origin", "http://evil.example")
                .buildAsync(URI.create("ws://127.0.0.1:" + server.port() + "/live"), new Page()).join());
        WebSocketHandshakeException h = assertInstanceOf(WebSocketHandshakeException.class, e.getCause());
        assertEquals(403, h.getResponse().statusCode());
    }

    /** What a page of another site gets when its name was made to resolve to this machine (DNS rebinding): refused, page and WebSocket alike. */
    @Test
    void aRequestNamingAnotherHostIsRefused() throws Exception {
        assertTrue(rawStatus("GET / HTTP/1.1\r\nHost: 127.0.0.1:" + server.port() + "\r\nConnection: close\r\n\r\n").contains(" 200 "));
        assertTrue(rawStatus("GET / HTTP/1.1\r\nHost: localhost:" + server.port() + "\r\nConnection: close\r\n\r\n").contains(" 200 "));
        assertTrue(rawStatus("GET / HTTP/1.1\r\nHost: rebound.example:" + server.port() + "\r\nConnection: close\r\n\r\n").contains(" 421 "));
        assertTrue(rawStatus("GET / HTTP/1.1\r\nHost: 127.0.0.1:1\r\nConnection: close\r\n\r\n").contains(" 421 "), "another port");
        String upgrade = rawStatus("GET /live HTTP/1.1\r\nHost: rebound.example:" + server.port() + "\r\nUpgrade: websocket\r\nConnection: Upgrade\r\n"
                + "Sec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\nSec-WebSocket-Version: 13\r\n\r\n");
        assertTrue(upgrade.contains(" 421 "), "no WebSocket without an Origin either: " + upgrade);
    }

    private String rawStatus(String request) throws java.io.IOException {
        try (java.net.Socket s = new java.net.Socket("127.0.0.1", server.port())) {
            s.setSoTimeout(10_000);
            s.getOutputStream().write(request.getBytes(java.nio.charset.StandardCharsets.US_ASCII));
            s.getOutputStream().flush();
            java.io.BufferedReader r = new java.io.BufferedReader(new java.io.InputStreamReader(s.getInputStream(), java.nio.charset.StandardCharsets.US_ASCII));
            return r.readLine();
        }
    }

    private String token() {
        return server.pageWithToken().substring(server.pageWithToken().indexOf("#token=") + 7);
    }
}
