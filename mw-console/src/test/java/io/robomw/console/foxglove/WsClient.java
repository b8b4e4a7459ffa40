package io.robomw.console.foxglove;

import java.io.ByteArrayOutputStream;
import java.net.URI;
import java.net.http.HttpClient;
import java.net.http.WebSocket;
import java.nio.ByteBuffer;
import java.nio.ByteOrder;
import java.time.Duration;
import java.util.concurrent.BlockingQueue;
import java.util.concurrent.CompletionStage;
import java.util.concurrent.LinkedBlockingQueue;
import java.util.concurrent.TimeUnit;

import static org.junit.jupiter.api.Assertions.assertNotNull;
import static org.junit.jupiter.api.Assertions.fail;

/**
 * A small Foxglove WebSocket client for the tests, on the JDK's own WebSocket (an independent
 * implementation of the framing): collects what the server sends, text and binary, in order.
 * With {@code reading(false)} it stops taking frames, as a client that does not keep up.
 */
final class WsClient implements AutoCloseable {

    static final Duration WAIT = Duration.ofSeconds(20);

    /** A frame received: text, or binary bytes. */
    record Frame(String text, byte[] binary) {
        ByteBuffer le() {
            return ByteBuffer.wrap(binary).order(ByteOrder.LITTLE_ENDIAN);
        }
    }

    private final BlockingQueue<Frame> frames = new LinkedBlockingQueue<>();
    private final WebSocket socket;
    private volatile boolean reading = true;
    private volatile WebSocket pending;
    private final java.util.concurrent.CompletableFuture<Integer> closedWith = new java.util.concurrent.CompletableFuture<>();

    private WsClient(URI uri, String origin, String... subprotocols) throws Exception {
        WebSocket.Builder b = HttpClient.newHttpClient().newWebSocketBuilder().connectTimeout(WAIT);
        if (origin != null) {
            b.header("Origin", origin);
        }
        if (subprotocols.length > 0) {
            b.subprotocols(subprotocols[0], java.util.Arrays.copyOfRange(subprotocols, 1, subprotocols.length));
        }
        this.socket = b.buildAsync(uri, new Listener()).get(WAIT.toSeconds(), TimeUnit.SECONDS);
    }

    static WsClient connect(URI uri, String... subprotocols) throws Exception {
        return new WsClient(uri, null, subprotocols);
    }

    static WsClient connectFrom(String origin, URI uri, String... subprotocols) throws Exception {
        return new WsClient(uri, origin, subprotocols);
    }

    /** @return the close code the server sent, waiting for it */
    int closeCode() throws Exception {
        return closedWith.get(WAIT.toSeconds(), TimeUnit.SECONDS);
    }

    String subprotocol() {
        return socket.getSubprotocol();
    }

    private final class Listener implements WebSocket.Listener {
        private final StringBuilder text = new StringBuilder();
        private final ByteArrayOutputStream binary = new ByteArrayOutputStream();

        @Override
        public CompletionStage<?> onText(WebSocket ws, CharSequence data, boolean last) {
            text.append(data);
            if (last) {
                frames.add(new Frame(text.toString(), null));
                text.setLength(0);
            }
            more(ws);
            return null;
        }

        @Override
        public CompletionStage<?> onBinary(WebSocket ws, ByteBuffer data, boolean last) {
            byte[] b = new byte[data.remaining()];
            data.get(b);
            binary.writeBytes(b);
            if (last) {
                frames.add(new Frame(null, binary.toByteArray()));
                binary.reset();
            }
            more(ws);
            return null;
        }

        @Override
        public CompletionStage<?> onClose(WebSocket ws, int statusCode, String reason) {
            closedWith.complete(statusCode);
            return null;
        }

        @Override
        public void onError(WebSocket ws, Throwable error) {
            closedWith.completeExceptionally(error);
        }

        private void more(WebSocket ws) {
            if (reading) {
                ws.request(1);
            } else {
                pending = ws;
            }
        }
    }

    /** Stops or resumes reading frames (a stopped client lets the server's socket fill up). */
    void reading(boolean on) {
        reading = on;
        WebSocket ws = pending;
        if (on && ws != null) {
            pending = null;
            ws.request(1);
        }
    }

    Frame next() throws InterruptedException {
        Frame f = frames.poll(WAIT.toMillis(), TimeUnit.MILLISECONDS);
        assertNotNull(f, "the server sent nothing within " + WAIT);
        return f;
    }

    /** @return the next text frame whose op is {@code op}, skipping others */
    String nextOp(String op) throws InterruptedException {
        long deadline = System.nanoTime() + WAIT.toNanos();
        while (System.nanoTime() < deadline) {
            Frame f = frames.poll(deadline - System.nanoTime(), TimeUnit.NANOSECONDS);
            if (f != null && f.text() != null && f.text().contains("\"op\":\"" + op + "\"")) {
                return f.text();
            }
        }
        return fail("no '" + op + "' message within " + WAIT);
    }

    /** @return the next binary frame with that opcode, skipping others */
    Frame nextBinary(int opcode) throws InterruptedException {
        long deadline = System.nanoTime() + WAIT.toNanos();
        while (System.nanoTime() < deadline) {
            Frame f = frames.poll(deadline - System.nanoTime(), TimeUnit.NANOSECONDS);
            if (f != null && f.binary() != null && f.binary().length > 0 && f.binary()[0] == opcode) {
                return f;
            }
        }
        return fail("no binary frame with opcode " + opcode + " within " + WAIT);
    }

    /** @return frames received and not taken yet */
    int waiting() {
        return frames.size();
    }

    void send(String text) throws Exception {
        socket.sendText(text, true).get(WAIT.toSeconds(), TimeUnit.SECONDS);
    }

    void send(byte[] binary) throws Exception {
        socket.sendBinary(ByteBuffer.wrap(binary), true).get(WAIT.toSeconds(), TimeUnit.SECONDS);
    }

    /** A client MESSAGE_DATA frame. */
    static byte[] clientMessage(long channelId, String json) {
        byte[] payload = json.getBytes(java.nio.charset.StandardCharsets.UTF_8);
        return ByteBuffer.allocate(5 + payload.length).order(ByteOrder.LITTLE_ENDIAN).put((byte) 1).putInt((int) channelId).put(payload).array();
    }

    @Override
    public void close() {
        socket.abort();
    }
}
