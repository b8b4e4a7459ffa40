package io.robomw.console.server;

import io.robomw.agents.net.OwnerThreads;
import io.robomw.api.spi.FailurePolicy;
import com.fasterxml.jackson.core.JsonProcessingException;
import com.fasterxml.jackson.databind.ObjectMapper;
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
import java.io.InputStream;
import java.io.UncheckedIOException;
import java.net.URI;
import java.nio.ByteBuffer;
import java.security.SecureRandom;
import java.time.Duration;
import java.util.HexFormat;
import java.util.LinkedHashMap;
import java.util.Map;
import java.util.Set;
import java.util.concurrent.ConcurrentHashMap;
import java.util.concurrent.ArrayBlockingQueue;
import java.util.concurrent.Executors;
import java.util.concurrent.RejectedExecutionException;
import java.util.concurrent.ScheduledExecutorService;
import java.util.concurrent.ThreadPoolExecutor;
import java.util.concurrent.TimeUnit;

/**
 * The console's web server: one page ({@code /}, its script and its style, all served from this
 * jar; nothing is loaded from anywhere else) and one WebSocket ({@code /live}) per open page,
 * over which the page gets the {@link ConsoleView} about ten times a second and sends its
 * {@link PageRequest}s.
 *
 * <p>Embedded Jetty 12 (core handlers, no servlets): a well-kept server with WebSocket in the same
 * port and the same thread pool, flow control per connection, and a small footprint.
 *
 * <p><b>Who may press the buttons.</b> The page shows everything to whoever can reach its port
 * (loopback by default). Retract, dispose and stop need the access token the console prints with
 * its address ({@code http://HOST:PORT/#token=...}: in the fragment, so it is never sent in a
 * request line or a Referer); requests without it are refused. A WebSocket whose Origin is not
 * this server is refused, so another site open in the same browser cannot talk to the console.
 * Every request must name the console itself in its {@code Host} ({@link HostCheck}): a site whose
 * name was made to resolve to this machine (DNS rebinding) is refused before anything is served.
 * The page's Content-Security-Policy lets it open WebSockets to the console only, and be framed by
 * no page ({@code frame-ancestors 'none'}).
 */
public final class ConsoleServer implements AutoCloseable {

    private static final Logger LOG = LoggerFactory.getLogger(ConsoleServer.class);
    private static final long PUSH_MILLIS = 100;
    /** The most page requests (button presses) served at once; each may wait seconds for a host. */
    static final int MAX_REQUEST_THREADS = 4;
    /** The most page requests waiting for a thread; beyond them a request is refused at once, saying so. */
    static final int MAX_QUEUED_REQUESTS = 64;
    private static final Map<String, String> FILES = Map.of(
            "/", "index.html",
            "/index.html", "index.html",
            "/console.js", "console.js",
            "/console.css", "console.css");
    private static final ObjectMapper JSON = new ObjectMapper();

    private final ConsoleView view;
    private final Controls controls;
    private final String token;
    private final Server server;
    private final Set<ConsoleSocket> sockets = ConcurrentHashMap.newKeySet();
    private final ScheduledExecutorService pusher;
    /** Runs the pages' requests off the WebSockets' threads: a retract may wait seconds for a host. */
    private final ThreadPoolExecutor requests;
    private final FailurePolicy failures;
    private final Map<String, byte[]> files = new LinkedHashMap<>();
    private final HostCheck hosts;

    private ConsoleServer(ConsoleView view, Controls controls, String bind, int port, FailurePolicy failures) {
        this.view = view;
        this.controls = controls;
        this.failures = failures;
        byte[] secret = new byte[16];
        new SecureRandom().nextBytes(secret);
        this.token = HexFormat.of().formatHex(secret);
        for (String f : Set.copyOf(FILES.values())) {
            files.put(f, resource(f));
        }
        QueuedThreadPool threads = new QueuedThreadPool(16, 2);
        threads.setName("console-http");
        threads.setDaemon(true);
        this.server = new Server(threads);
        ServerConnector connector = new ServerConnector(server);
        connector.setHost(bind);
        connector.setPort(port);
        server.addConnector(connector);
        WebSocketUpgradeHandler ws = WebSocketUpgradeHandler.from(server, container -> {
            container.setMaxTextMessageSize(PageRequest.MAX_LENGTH);
            container.setIdleTimeout(Duration.ofMinutes(10));
            container.addMapping("/live", (request, response, callback) -> {
                String origin = request.getHeaders().get(HttpHeader.ORIGIN);
                String host = request.getHeaders().get(HttpHeader.HOST);
                if (origin != null && !sameOrigin(origin, host)) {
                    LOG.warn("console: refused a WebSocket from origin {} (this console is {})", origin, host);
                    Response.writeError(request, response, callback, 403, "origin " + origin + " may not use this console");
                    return null;
                }
                return new ConsoleSocket(this);
            });
        });
        ws.setHandler(new Files());
        this.hosts = new HostCheck(bind, this::port);
        server.setHandler(new OwnHostOnly(ws));
        this.pusher = Executors.newSingleThreadScheduledExecutor(r -> OwnerThreads.thread("console-push", r, failures));
        this.requests = new ThreadPoolExecutor(MAX_REQUEST_THREADS, MAX_REQUEST_THREADS, 30, TimeUnit.SECONDS,
                new ArrayBlockingQueue<>(MAX_QUEUED_REQUESTS), new OwnerThreads("console-request", failures), new ThreadPoolExecutor.AbortPolicy());
        requests.allowCoreThreadTimeOut(true);
    }

    /**
     * Starts serving.
     *
     * @param view     what to show
     * @param controls what the buttons do
     * @param bind     the address to listen on (127.0.0.1 keeps it to this machine)
     * @param port     the port, 0 for a free one
     * @param failures where what its push and request threads catch goes
     * @return the running server
     * @throws IOException if the port cannot be used
     */
    public static ConsoleServer start(ConsoleView view, Controls controls, String bind, int port, FailurePolicy failures) throws IOException {
        ConsoleServer s = new ConsoleServer(view, controls, bind, port, failures);
        try {
            s.server.start();
        } catch (Exception e) {
            s.close();
            throw new IOException("the console cannot listen on " + bind + ":" + port + ": " + e.getMessage(), e);
        }
        s.pusher.scheduleWithFixedDelay(OwnerThreads.rounds(failures, s::push), PUSH_MILLIS, PUSH_MILLIS, TimeUnit.MILLISECONDS);
        LOG.info("console serving at {}", s.address());
        return s;
    }

    /** @return the page's address, without the token */
    public URI address() {
        ServerConnector c = (ServerConnector) server.getConnectors()[0];
        String host = c.getHost() == null || c.getHost().equals("0.0.0.0") ? "127.0.0.1" : c.getHost();
        return URI.create("http://" + (host.contains(":") ? "[" + host + "]" : host) + ":" + c.getLocalPort() + "/");
    }

    /** @return the address to open: the page with the access token that the buttons need */
    public String pageWithToken() {
        return address() + "#token=" + token;
    }

    /** @return the port it listens on */
    public int port() {
        return ((ServerConnector) server.getConnectors()[0]).getLocalPort();
    }

    ConsoleView view() {
        return view;
    }

    Controls controls() {
        return controls;
    }

    boolean tokenMatches(String given) {
        return given != null && java.security.MessageDigest.isEqual(given.getBytes(java.nio.charset.StandardCharsets.UTF_8),
                token.getBytes(java.nio.charset.StandardCharsets.UTF_8));
    }

    void opened(ConsoleSocket s) {
        sockets.add(s);
    }

    void closed(ConsoleSocket s) {
        sockets.remove(s);
    }

    Map<String, Object> controlsForPage() {
        Map<String, Object> c = new LinkedHashMap<>();
        c.put("agents", controls.agentsControllable());
        c.put("agentsWhyNot", controls.agentsWhyNot());
        c.put("robots", controls != Controls.NONE);
        c.put("stoppable", new java.util.TreeSet<>(controls.stoppableRobots()));
        return c;
    }

    static String json(Object o) {
        try {
            return JSON.writeValueAsString(o);
        } catch (JsonProcessingException e) {
            throw new IllegalStateException("cannot write the console's view as JSON: " + e.getMessage(), e);
        }
    }

    /**
     * Sends every page what it has not seen; a page whose last update is still on its way is
     * skipped this time. A failed push is reported, and the next one comes.
     */
    private void push() {
        long now = System.currentTimeMillis() * 1_000_000L;
        for (ConsoleSocket s : sockets) {
            s.push(now);
        }
    }

    /**
     * Runs a page's request on one of the server's request threads.
     *
     * @param request the request's work
     * @throws RejectedExecutionException if {@value #MAX_QUEUED_REQUESTS} requests wait already, or the server is closed
     */
    void serve(Runnable request) {
        requests.execute(request);
    }

    private static boolean sameOrigin(String origin, String host) {
        if (host == null) {
            return false;
        }
        try {
            URI o = URI.create(origin);
            String authority = o.getAuthority();
            return authority != null && authority.equalsIgnoreCase(host);
        } catch (IllegalArgumentException e) {
            return false;
        }
    }

    private static byte[] resource(String name) {
        try (InputStream in = ConsoleServer.class.getResourceAsStream("/io/robomw/console/web/" + name)) {
            if (in == null) {
                throw new IllegalStateException("the console's " + name + " is missing from its jar");
            }
            return in.readAllBytes();
        } catch (IOException e) {
            throw new UncheckedIOException(e);
        }
    }

    /** Refuses every request whose Host is not one of the console's names, before the page or the WebSocket sees it. */
    private final class OwnHostOnly extends Handler.Wrapper {
        OwnHostOnly(Handler inner) {
            super(inner);
        }

        @Override
        public boolean handle(Request request, Response response, Callback callback) throws Exception {
            String host = request.getHeaders().get(HttpHeader.HOST);
            if (!hosts.allows(host)) {
                LOG.warn("console: refused a request for Host {} (this console answers to {} on port {}; a DNS rebinding?)", host, hosts.names(), port());
                Response.writeError(request, response, callback, 421, "this console answers to " + hosts.names() + " on port " + port()
                        + ", not to '" + host + "'");
                return true;
            }
            return super.handle(request, response, callback);
        }
    }

    /** The page's three files, and 404 for anything else. */
    private final class Files extends Handler.Abstract {
        @Override
        public boolean handle(Request request, Response response, Callback callback) {
            String path = Request.getPathInContext(request);
            String file = FILES.get(path);
            if (file == null || !"GET".equals(request.getMethod()) && !"HEAD".equals(request.getMethod())) {
                Response.writeError(request, response, callback, 404, "not here: the console has only its page, /");
                return true;
            }
            String type = file.endsWith(".html") ? "text/html; charset=utf-8" : file.endsWith(".js") ? "text/javascript; charset=utf-8"
                    : "text/css; charset=utf-8";
            response.getHeaders().put(HttpHeader.CONTENT_TYPE, type);
            response.getHeaders().put(HttpHeader.CACHE_CONTROL, "no-cache");
            // The Host was checked (OwnHostOnly): the page may open WebSockets to this console and nowhere else, and no page may frame it.
            String self = request.getHeaders().get(HttpHeader.HOST).strip();
            response.getHeaders().put("Content-Security-Policy", "default-src 'self'; connect-src 'self' ws://" + self
                    + "; img-src 'self' data:; frame-ancestors 'none'");
            response.getHeaders().put("X-Frame-Options", "DENY");
            response.getHeaders().put("X-Content-Type-Options", "nosniff");
            response.write(true, ByteBuffer.wrap(files.get(file)), callback);
            return true;
        }
    }

    @Override
    public void close() {
        pusher.shutdownNow();
        requests.shutdownNow();
        for (ConsoleSocket s : sockets) {
            s.close();
        }
        try {
            server.stop();
        } catch (Exception e) {
            LOG.warn("console: stopping the web server failed: {}", e.toString());
        }
    }
}
