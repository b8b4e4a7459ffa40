package io.robomw.console.rosbridge.server;

import io.robomw.console.rosbridge.graph.Graph;
import io.robomw.console.rosbridge.graph.TopicResolver;
import io.robomw.console.rosbridge.msg.MessageReader;
import io.robomw.console.rosbridge.protocol.ClientSession;
import io.robomw.console.rosbridge.protocol.Limits;
import io.robomw.console.rosbridge.protocol.Outbox;
import org.eclipse.jetty.http.HttpHeader;
import org.eclipse.jetty.server.Handler;
import org.eclipse.jetty.server.Request;
import org.eclipse.jetty.server.Response;
import org.eclipse.jetty.server.Server;
import org.eclipse.jetty.server.ServerConnector;
import org.eclipse.jetty.util.Callback;
import org.eclipse.jetty.util.thread.QueuedThreadPool;
import org.eclipse.jetty.websocket.server.WebSocketUpgradeHandler;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.io.IOException;
import java.net.InetAddress;
import java.net.URI;
import java.net.UnknownHostException;
import java.nio.ByteBuffer;
import java.nio.charset.StandardCharsets;
import java.time.Duration;
import java.util.List;
import java.util.Set;
import java.util.concurrent.ConcurrentHashMap;
import java.util.concurrent.ScheduledExecutorService;
import java.util.concurrent.ScheduledFuture;
import java.util.concurrent.TimeUnit;

/**
 * The rosbridge endpoint's WebSocket server: embedded Jetty 12 (as the console's), one WebSocket
 * per client on any path ({@code ws://HOST:PORT/}, as rosbridge_suite serves), no subprotocol (roslibpy
 * offers none), permessage-deflate when the client offers it.
 *
 * <p>Before a connection is taken: the {@link Handshake} (token, Origin), and the connection
 * limit (one more gets HTTP 503; handshakes that race may admit one or two more for a moment). Frames are at most {@link Limits#maxMessageBytes}; a larger one
 * closes the connection (1009, as the WebSocket protocol says). Every client is pinged every
 * {@value #PING_SECONDS} s, so one that vanished without closing is found out when a ping cannot be
 * delivered; a connection with no traffic either way for {@link #IDLE_TIMEOUT} is closed.
 */
public final class RosBridgeServer implements AutoCloseable {

    private static final Logger LOG = LoggerFactory.getLogger(RosBridgeServer.class);
    /** Seconds between pings to each client. */
    static final int PING_SECONDS = 30;
    /** A connection with no traffic either way for this long is closed. */
    static final Duration IDLE_TIMEOUT = Duration.ofSeconds(4L * PING_SECONDS);

    private final Graph graph;
    private final TopicResolver resolver;
    private final MessageReader reader;
    private final Limits limits;
    private final ScheduledExecutorService timer;
    private final Handshake handshake;
    private final Server server;
    private final Set<ClientSocket> clients = ConcurrentHashMap.newKeySet();
    private ScheduledFuture<?> pinger;

    private RosBridgeServer(Graph graph, TopicResolver resolver, MessageReader reader, Limits limits, ScheduledExecutorService timer,
                            Handshake handshake, String bind, int port, String echoPath) {
        this.graph = graph;
        this.resolver = resolver;
        this.reader = reader;
        this.limits = limits;
        this.timer = timer;
        this.handshake = handshake;
        QueuedThreadPool threads = new QueuedThreadPool(16, 2);
        threads.setName("rosbridge-http");
        threads.setDaemon(true);
        this.server = new Server(threads);
        ServerConnector connector = new ServerConnector(server);
        connector.setHost(bind);
        connector.setPort(port);
        server.addConnector(connector);
        WebSocketUpgradeHandler ws = WebSocketUpgradeHandler.from(server, container -> {
            container.setMaxTextMessageSize(limits.maxMessageBytes());
            container.setMaxBinaryMessageSize(limits.maxMessageBytes());
            container.setIdleTimeout(IDLE_TIMEOUT);
            if (echoPath != null) {
                container.addMapping(echoPath, (request, response, callback) -> new EchoSocket());
            }
            container.addMapping("/*", (request, response, callback) -> {
                Handshake.Verdict v = handshake.check(Request.getPathInContext(request), request.getHttpURI().getQuery(),
                        request.getHeaders().get(HttpHeader.AUTHORIZATION), request.getHeaders().get(HttpHeader.ORIGIN));
                if (!v.accepted()) {
                    LOG.warn("rosbridge: refused a connection from {}: {}", Request.getRemoteAddr(request), v.reason());
                    Response.writeError(request, response, callback, v.status(), v.reason());
                    return null;
                }
                if (clients.size() >= limits.maxConnections()) {
                    LOG.warn("rosbridge: refused a connection from {}: already {} clients, the most it takes", Request.getRemoteAddr(request),
                            limits.maxConnections());
                    Response.writeError(request, response, callback, 503, "this rosbridge already has " + limits.maxConnections() + " clients");
                    return null;
                }
                return new ClientSocket(this);
            });
        });
        ws.setHandler(new NotAWebSocket());
        server.setHandler(ws);
    }

    /**
     * Starts serving.
     *
     * @param graph          the topics and services
     * @param resolver       makes topics on first use
     * @param reader         reads client messages
     * @param limits         the bounds
     * @param timer          throttles and pings
     * @param token          the access token, or {@code null} (then only a loopback bind is allowed)
     * @param allowedOrigins web origins besides this machine's that browsers may connect from
     * @param bind           the address to listen on
     * @param port           the port, 0 for a free one
     * @param echoPath       a path for a plain WebSocket echo (benchmarks), or {@code null}
     * @return the running server
     * @throws IOException              if the port cannot be used
     * @throws IllegalArgumentException if the bind is not loopback and there is no token
     */
    public static RosBridgeServer start(Graph graph, TopicResolver resolver, MessageReader reader, Limits limits, ScheduledExecutorService timer,
                                        String token, List<String> allowedOrigins, String bind, int port, String echoPath) throws IOException {
        checkAccess(bind, token);
        RosBridgeServer s = new RosBridgeServer(graph, resolver, reader, limits, timer, new Handshake(token, allowedOrigins), bind, port, echoPath);
        try {
            s.server.start();
        } catch (Exception e) {
            s.close();
            throw new IOException("the rosbridge cannot listen on " + bind + ":" + port + ": " + e.getMessage(), e);
        }
        s.pinger = timer.scheduleWithFixedDelay(s::pingAll, PING_SECONDS, PING_SECONDS, TimeUnit.SECONDS);
        return s;
    }

    /** @return its address, {@code ws://HOST:PORT/} */
    public URI address() {
        ServerConnector c = (ServerConnector) server.getConnectors()[0];
        String host = c.getHost() == null || c.getHost().equals("0.0.0.0") ? "127.0.0.1" : c.getHost();
        return URI.create("ws://" + (host.contains(":") ? "[" + host + "]" : host) + ":" + c.getLocalPort() + "/");
    }

    /** @return the port it listens on */
    public int port() {
        return ((ServerConnector) server.getConnectors()[0]).getLocalPort();
    }

    /** @return clients connected now */
    public int clients() {
        return clients.size();
    }

    /** @return messages dropped so far for clients that did not keep up, over the clients connected now */
    public long dropped() {
        return clients.stream().mapToLong(c -> c.counts()[1]).sum();
    }

    Limits limits() {
        return limits;
    }

    ScheduledExecutorService timer() {
        return timer;
    }

    ClientSession newSession(Outbox outbox, String name) {
        return new ClientSession(graph, resolver, reader, limits, outbox, name);
    }

    void opened(ClientSocket c) {
        clients.add(c);
    }

    void closed(ClientSocket c) {
        clients.remove(c);
    }

    private void pingAll() {
        for (ClientSocket c : clients) {
            c.ping();
        }
    }

    /**
     * @param bind  where a bridge would listen
     * @param token its access token, or {@code null}
     * @throws IllegalArgumentException if the bind is beyond this machine and there is no token, or the token is too short
     */
    public static void checkAccess(String bind, String token) {
        if (token == null && !loopback(bind)) {
            throw new IllegalArgumentException("a rosbridge listening on " + bind + " (beyond this machine) needs an access token: give it in a file "
                    + "(--token-file FILE) or in the environment (MW_ROSBRIDGE_TOKEN); ROS 2's rosbridge has no authentication (docs/ros2.md)");
        }
        if (token != null && token.length() < 16) {
            throw new IllegalArgumentException("a rosbridge access token must be at least 16 characters, got " + token.length());
        }
    }

    static boolean loopback(String bind) {
        try {
            return InetAddress.getByName(bind).isLoopbackAddress();
        } catch (UnknownHostException e) {
            return false;
        }
    }

    /** Plain HTTP on the bridge's port: 426, saying what it is. */
    private static final class NotAWebSocket extends Handler.Abstract {
        @Override
        public boolean handle(Request request, Response response, Callback callback) {
            response.setStatus(426);
            response.getHeaders().put(HttpHeader.CONTENT_TYPE, "text/plain; charset=utf-8");
            response.getHeaders().put(HttpHeader.UPGRADE, "websocket");
            response.write(true, ByteBuffer.wrap("this is a rosbridge v2 WebSocket endpoint (RoboMW): connect with roslibpy or roslibjs, see docs/ros2.md\n"
                    .getBytes(StandardCharsets.UTF_8)), callback);
            return true;
        }
    }

    @Override
    public void close() {
        if (pinger != null) {
            pinger.cancel(false);
        }
        for (ClientSocket c : clients) {
            c.close(1001, "the rosbridge is stopping");
        }
        try {
            server.stop();
        } catch (Exception e) {
            LOG.warn("rosbridge: stopping the web server failed: {}", e.toString());
        }
    }
}
