package io.robomw.console.rosbridge.server;

import io.robomw.console.rosbridge.protocol.ClientSession;
import io.robomw.console.rosbridge.protocol.Outbox;
import io.robomw.console.rosbridge.protocol.Transport;
import org.eclipse.jetty.websocket.api.Callback;
import org.eclipse.jetty.websocket.api.Session;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.nio.ByteBuffer;

/**
 * One client's WebSocket: hands its frames to its {@link ClientSession} and sends what its
 * {@link Outbox} gives, one frame at a time. Jetty calls the {@code onWebSocket...} methods one
 * at a time per connection. Public only because Jetty calls its listener methods through method
 * handles.
 */
public final class ClientSocket extends Session.Listener.AbstractAutoDemanding implements Transport {

    private static final Logger LOG = LoggerFactory.getLogger(ClientSocket.class);

    private final RosBridgeServer server;
    private volatile ClientSession session;
    private volatile Outbox outbox;
    private volatile String name = "a rosbridge client";

    ClientSocket(RosBridgeServer server) {
        this.server = server;
    }

    @Override
    public void onWebSocketOpen(Session s) {
        super.onWebSocketOpen(s);
        name = "rosbridge client " + s.getRemoteSocketAddress();
        outbox = new Outbox(this, server.limits(), server.timer(), name);
        session = server.newSession(outbox, name);
        server.opened(this);
        LOG.info("rosbridge: {} connected", name);
    }

    @Override
    public void onWebSocketText(String text) {
        ClientSession c = session;
        if (c != null) {
            c.onText(text);
        }
    }

    @Override
    public void onWebSocketBinary(ByteBuffer payload, Callback callback) {
        ClientSession c = session;
        byte[] data = new byte[payload.remaining()];
        payload.get(data);
        callback.succeed();
        if (c != null) {
            c.onBinary(data);
        }
    }

    @Override
    public void onWebSocketClose(int status, String reason) {
        ended();
        LOG.info("rosbridge: {} disconnected ({}{})", name, status, reason == null || reason.isEmpty() ? "" : ": " + reason);
    }

    @Override
    public void onWebSocketError(Throwable cause) {
        LOG.debug("rosbridge: {} failed: {}", name, cause.toString());
        ended();
    }

    private void ended() {
        ClientSession c = session;
        if (c != null) {
            c.close();
        }
        server.closed(this);
    }

    @Override
    public void sendText(String text, Runnable done) {
        Session s = getSession();
        if (s == null || !s.isOpen()) {
            done.run();
            return;
        }
        s.sendText(text, Callback.from(done, failure -> done.run()));
    }

    @Override
    public void sendBinary(byte[] data, Runnable done) {
        Session s = getSession();
        if (s == null || !s.isOpen()) {
            done.run();
            return;
        }
        s.sendBinary(ByteBuffer.wrap(data), Callback.from(done, failure -> done.run()));
    }

    @Override
    public void close(int code, String reason) {
        Session s = getSession();
        if (s != null) {
            s.close(code, reason, Callback.NOOP);
        }
    }

    /** Sends a ping, so a client that vanished without closing is found out by the idle timeout. */
    void ping() {
        Session s = getSession();
        if (s != null && s.isOpen()) {
            s.sendPing(ByteBuffer.allocate(0), Callback.NOOP);
        }
    }

    /** @return frames sent to this client, and messages dropped because it did not keep up */
    long[] counts() {
        Outbox o = outbox;
        return o == null ? new long[2] : new long[] {o.sentFrames(), o.dropped()};
    }
}
