package io.robomw.console.server;

import org.eclipse.jetty.websocket.api.Callback;
import org.eclipse.jetty.websocket.api.Session;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.util.LinkedHashMap;
import java.util.Map;
import java.util.concurrent.RejectedExecutionException;
import java.util.concurrent.atomic.AtomicBoolean;

/**
 * One open page: sends it updates (never more than one on its way at a time, so a slow browser
 * gets fewer, larger updates instead of an ever longer queue) and serves its requests. A bad
 * request gets a reply saying what was wrong; the connection stays open.
 */
public final class ConsoleSocket extends Session.Listener.AbstractAutoDemanding {

    private static final Logger LOG = LoggerFactory.getLogger(ConsoleSocket.class);

    private final ConsoleServer server;
    private final ConsoleView.Cursor cursor = new ConsoleView.Cursor();
    private final AtomicBoolean sending = new AtomicBoolean();
    private volatile long sentVersion = -1;

    ConsoleSocket(ConsoleServer server) {
        this.server = server;
    }

    @Override
    public void onWebSocketOpen(Session session) {
        super.onWebSocketOpen(session);
        server.opened(this);
        push(System.currentTimeMillis() * 1_000_000L);
    }

    void push(long nowNanos) {
        Session s = getSession();
        if (s == null || !s.isOpen() || !sending.compareAndSet(false, true)) {
            return;
        }
        long v = server.view().version();
        if (v == sentVersion && nowNanos % 1_000_000_000L >= 100_000_000L) {
            sending.set(false); // nothing new; still send about once a second so the page can age what is stale
            return;
        }
        String text = ConsoleServer.json(server.view().update(cursor, nowNanos, server.controlsForPage()));
        sentVersion = v;
        s.sendText(text, Callback.from(() -> sending.set(false), failure -> {
            sending.set(false);
            LOG.debug("console: an update to {} failed: {}", s.getRemoteSocketAddress(), failure.toString());
        }));
    }

    /**
     * Serves a request on the server's request threads (off the WebSocket's thread: a retract may
     * wait seconds for a host); when too many wait already, the page is told at once.
     */
    @Override
    public void onWebSocketText(String text) {
        try {
            server.serve(() -> reply(serve(text)));
        } catch (RejectedExecutionException e) {
            Map<String, Object> r = new LinkedHashMap<>();
            r.put("type", "reply");
            r.put("ok", false);
            r.put("message", "the console is busy: " + ConsoleServer.MAX_QUEUED_REQUESTS + " requests wait already (or it is closing); try again");
            LOG.warn("console: refused a request from {}: {} requests wait already", getSession() == null ? "?" : getSession().getRemoteSocketAddress(),
                    ConsoleServer.MAX_QUEUED_REQUESTS);
            reply(r);
        }
    }

    private Map<String, Object> serve(String text) {
        Map<String, Object> r = new LinkedHashMap<>();
        r.put("type", "reply");
        PageRequest q;
        try {
            q = PageRequest.parse(text);
        } catch (PageRequest.BadRequest e) {
            r.put("ok", false);
            r.put("message", "bad request: " + e.getMessage());
            LOG.info("console: bad request from {}: {}", getSession() == null ? "?" : getSession().getRemoteSocketAddress(), e.getMessage());
            return r;
        }
        r.put("id", q.id());
        r.put("op", q.op().wire());
        if (!server.tokenMatches(q.token())) {
            r.put("ok", false);
            r.put("message", "refused: " + q.op().wire() + " needs the access token the console printed with its address (open that address)");
            return r;
        }
        try {
            String done = switch (q.op()) {
                case RETRACT -> server.controls().retract(q.agent());
                case DISPOSE -> server.controls().dispose(q.agent());
                case STOP -> server.controls().stop(q.robot());
            };
            r.put("ok", true);
            r.put("message", done);
            LOG.info("console: {} done: {}", q.op().wire(), done);
        } catch (Exception e) {
            r.put("ok", false);
            r.put("message", q.op().wire() + " failed: " + e.getMessage());
            LOG.warn("console: {} failed: {}", q.op().wire(), e.getMessage());
        }
        return r;
    }

    private void reply(Map<String, Object> r) {
        Session s = getSession();
        if (s != null && s.isOpen()) {
            s.sendText(ConsoleServer.json(r), Callback.NOOP);
        }
    }

    @Override
    public void onWebSocketClose(int status, String reason) {
        server.closed(this);
    }

    @Override
    public void onWebSocketError(Throwable cause) {
        LOG.debug("console: page connection failed: {}", cause.toString());
        server.closed(this);
    }

    void close() {
        Session s = getSession();
        if (s != null) {
            s.close();
        }
    }
}
