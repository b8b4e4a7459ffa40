package io.robomw.console.rosbridge;

import com.fasterxml.jackson.databind.JsonNode;
import com.fasterxml.jackson.databind.ObjectMapper;

import java.net.URI;
import java.net.http.HttpClient;
import java.net.http.WebSocket;
import java.nio.ByteBuffer;
import java.time.Duration;
import java.util.concurrent.BlockingQueue;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.CompletionStage;
import java.util.concurrent.LinkedBlockingQueue;
import java.util.concurrent.TimeUnit;
import java.util.function.Predicate;

/**
 * A WebSocket client for the bridge's tests: the JDK's own, which shares no code with the server.
 * Keeps every text frame it gets, parsed, and the close code.
 */
final class WsClient implements AutoCloseable {

    private static final ObjectMapper JSON = new ObjectMapper();

    final BlockingQueue<JsonNode> frames = new LinkedBlockingQueue<>();
    final CompletableFuture<Integer> closed = new CompletableFuture<>();
    /** Held: an HttpClient no one references closes its connections when it is collected. */
    private final HttpClient http = HttpClient.newHttpClient();
    private final WebSocket socket;

    private WsClient(URI uri, String origin) throws Exception {
        WebSocket.Builder b = http.newWebSocketBuilder().connectTimeout(Duration.ofSeconds(20));
        if (origin != null) {
            b.header("Origin", origin);
        }
        this.socket = b.buildAsync(uri, new WebSocket.Listener() {
            private final StringBuilder text = new StringBuilder();

            @Override
            public CompletionStage<?> onText(WebSocket ws, CharSequence data, boolean last) {
                text.append(data);
                if (last) {
                    try {
                        frames.add(JSON.readTree(text.toString()));
                    } catch (Exception e) {
                        throw new AssertionError("the bridge sent a frame that is not JSON: " + text, e);
                    }
                    text.setLength(0);
                }
                ws.request(1);
                return null;
            }

            @Override
            public CompletionStage<?> onBinary(WebSocket ws, ByteBuffer data, boolean last) {
                ws.request(1);
                return null;
            }

            @Override
            public CompletionStage<?> onClose(WebSocket ws, int statusCode, String reason) {
                closed.complete(statusCode);
                return null;
            }

            @Override
            public void onError(WebSocket ws, Throwable error) {
                closed.complete(-1);
            }
        }).get(30, TimeUnit.SECONDS);
    }

    static WsClient connect(URI uri) throws Exception {
        return new WsClient(uri, null);
    }

    static WsClient connect(URI uri, String origin) throws Exception {
        return new WsClient(uri, origin);
    }

    void send(String json) throws Exception {
        socket.sendText(json.replace('\'', '"'), true).get(10, TimeUnit.SECONDS);
    }

    /** @return the next frame that matches, dropping the others, within the deadline */
    JsonNode await(Predicate<JsonNode> match, Duration within, String what) throws InterruptedException {
        long deadline = System.nanoTime() + within.toNanos();
        while (true) {
            JsonNode f = frames.poll(Math.max(0, deadline - System.nanoTime()), TimeUnit.NANOSECONDS);
            if (f == null) {
                throw new AssertionError("no " + what + " within " + within);
            }
            if (match.test(f)) {
                return f;
            }
        }
    }

    /** @return the next message published on the topic */
    JsonNode awaitPublish(String topic, Duration within) throws InterruptedException {
        return await(f -> f.path("op").asText().equals("publish") && f.path("topic").asText().equals(topic), within, "message on " + topic);
    }

    @Override
    public void close() {
        socket.abort();
    }
}
