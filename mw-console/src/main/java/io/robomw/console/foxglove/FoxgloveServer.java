package io.robomw.console.foxglove;

import io.robomw.api.spi.FailurePolicy;
import io.robomw.api.spi.OwnerThread;
import io.robomw.console.observe.Observation;
import io.robomw.console.observe.Observer;
import io.robomw.console.record.McapRecorder;
import io.robomw.console.record.RecordingCodec;
import io.robomw.console.record.Schemas;
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
import java.net.URI;
import java.nio.charset.StandardCharsets;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.Map;
import java.util.Objects;
import java.util.Optional;
import java.util.Set;
import java.util.concurrent.ArrayBlockingQueue;
import java.util.concurrent.BlockingQueue;
import java.util.concurrent.ConcurrentHashMap;
import java.util.concurrent.CopyOnWriteArraySet;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicLong;

/**
 * A live Foxglove WebSocket: what a run shows (a simulated world, watched robots and hosts, a
 * replay) as the channels of its MCAP recordings, to Foxglove (or any client of the Foxglove
 * WebSocket protocol), and Twists published by a client's teleop panel to a robot's
 * {@code drive}.
 *
 * <p><b>The protocol</b>, as the Foxglove SDK 0.30.3's server speaks it (its source is the
 * reference where the legacy specification is silent): the subprotocol {@code foxglove.sdk.v1} or
 * {@code foxglove.websocket.v1} ({@link Subprotocol}; a handshake offering neither gets HTTP 400);
 * {@code serverInfo} first, then one {@code advertise} per 100 channels known, then one for each new
 * channel as it appears; {@code subscribe}/{@code unsubscribe} with the client's own subscription
 * ids; messages as binary MESSAGE_DATA frames with their log times ({@link BinaryFrames}); bad input
 * answered with a {@code status} error, the connection going on ({@link ClientSession}).
 *
 * <p><b>Channels</b> are the recordings' ({@link RecordingCodec}): {@code /robots/R/pose} as
 * {@code foxglove.PoseInFrame}, {@code /tf}, {@code /world/scene}, {@code /agents/log}, the
 * {@code robomw.*} types, JSON with JSON Schemas ({@link Schemas}), so one Foxglove layout shows a
 * live world and its recording. A channel is advertised when its first message is seen; a new
 * subscriber gets its latest message at once.
 *
 * <p><b>Capabilities.</b> Live: {@code clientPublish} (with {@code supportedEncodings: ["json"]})
 * when the server drives robots ({@link Teleop}): a client advertises a channel on
 * {@code /robots/R/cmd_vel} (or {@code /cmd_vel} when there is one robot) with schema
 * {@code geometry_msgs/Twist} or {@code geometry_msgs/msg/Twist} and publishes JSON Twists
 * ({@link Twist}), which drive R under its watchdog. Replays ({@link Options#replay}): {@code time},
 * with a TIME frame each time the recorded time moves on, and messages stamped with the times they
 * were recorded at.
 *
 * <p><b>Limits</b> (the server's memory stays bounded whatever clients do):
 * {@value #MAX_CLIENTS} clients, {@value #MAX_CHANNELS} channels, {@value #MAX_SUBSCRIPTIONS}
 * subscriptions and {@value #MAX_CLIENT_CHANNELS} advertised channels per client, client messages
 * of {@value #MAX_CLIENT_MESSAGE} bytes (a longer one closes the connection with 1009, message too
 * big), and per client {@link Options#backlog()} queued data frames (a slow client loses its oldest)
 * and as many control messages (a client too slow for those is disconnected). It listens on the
 * address it is given: 127.0.0.1 in the command line, so only this machine connects.
 *
 * <p><b>Threads.</b> {@link #observe} only queues (a source never waits for a client); the
 * {@code foxglove-encode} thread turns observations into messages and queues them for each
 * subscriber; Jetty's {@code foxglove-http} threads write to the sockets, one frame on its way per
 * client; the {@code foxglove-drive} thread calls {@link Teleop#drive}. Thread-safe.
 */
public final class FoxgloveServer implements Observer, AutoCloseable {

    private static final Logger LOG = LoggerFactory.getLogger(FoxgloveServer.class);
    /** The port Foxglove's tools use by default (foxglove_bridge, the SDK). */
    public static final int DEFAULT_PORT = 8765;
    /** Clients connected at once; one more is refused with HTTP 503. */
    public static final int MAX_CLIENTS = 32;
    /** Channels at most; messages on more topics are dropped (logged once). */
    public static final int MAX_CHANNELS = 10_000;
    /** Subscriptions one client may hold. */
    public static final int MAX_SUBSCRIPTIONS = MAX_CHANNELS;
    /** Channels one client may advertise. */
    public static final int MAX_CLIENT_CHANNELS = 64;
    /** The longest text or binary message a client may send, bytes. */
    public static final int MAX_CLIENT_MESSAGE = 1 << 20;
    /** Data frames queued per client by default (the SDK's default backlog). */
    public static final int DEFAULT_BACKLOG = 1024;
    /** Observations waiting to be encoded at most; more are dropped (counted, logged once). */
    static final int OBSERVATION_QUEUE = 65_536;
    /** Channels per advertise message when a client connects (as the SDK batches them). */
    static final int ADVERTISE_BATCH = 100;
    /** Time between two pings to every client. */
    static final long PING_NANOS = TimeUnit.SECONDS.toNanos(15);

    /** The environment variable a command reads the access token of a Foxglove WebSocket beyond this machine from. */
    public static final String TOKEN_ENV = "MW_FOXGLOVE_TOKEN";
    /** The shortest access token taken. */
    public static final int MIN_TOKEN_LENGTH = 16;

    /**
     * How to serve. Secure by default, as the console and the rosbridge: it listens on loopback;
     * an address beyond this machine needs an access token, which every client must give
     * ({@code ws://HOST:PORT/?token=TOKEN}, or {@code Authorization: Bearer TOKEN}). The Foxglove
     * WebSocket protocol has no authentication of its own, so the token is RoboMW's.
     *
     * @param name     the server's name in serverInfo (the command that runs it)
     * @param bind     the address to listen on (127.0.0.1 keeps it to this machine)
     * @param port     the port, 0 for a free one
     * @param replay   whether it serves a replay: the time capability, TIME frames, no driving
     * @param backlog  data frames queued per client before the oldest is dropped, &gt;= 1
     * @param failures where its threads' failures go
     * @param token    the access token clients must give (at least {@value #MIN_TOKEN_LENGTH} characters), or {@code null}
     *                 for none (then only a loopback bind is allowed)
     */
    public record Options(String name, String bind, int port, boolean replay, int backlog, FailurePolicy failures, String token) {
        /** Checks. */
        public Options {
            Objects.requireNonNull(name, "name");
            Objects.requireNonNull(bind, "bind");
            Objects.requireNonNull(failures, "failures");
            if (token == null && !loopback(bind)) {
                throw new IllegalArgumentException("a Foxglove WebSocket listening on " + bind + " (beyond this machine) needs an access token: give it in a "
                        + "file (--foxglove-token-file FILE) or in the environment (" + TOKEN_ENV + "); the Foxglove protocol has no authentication");
            }
            if (token != null && token.length() < MIN_TOKEN_LENGTH) {
                throw new IllegalArgumentException("a Foxglove access token must be at least " + MIN_TOKEN_LENGTH + " characters, got " + token.length());
            }
            if (port < 0 || port > 65_535) {
                throw new IllegalArgumentException("the Foxglove WebSocket's port must be 0 to 65535, got " + port);
            }
            if (backlog < 1) {
                throw new IllegalArgumentException("a Foxglove client's backlog must be >= 1 frame, got " + backlog);
            }
        }

        /** @param name its name @param bind its address @param port its port @return options for a live run */
        public static Options live(String name, String bind, int port) {
            return new Options(name, bind, port, false, DEFAULT_BACKLOG, FailurePolicy.logging(), null);
        }

        /** @param name its name @param bind its address @param port its port @return options for a replay */
        public static Options replay(String name, String bind, int port) {
            return new Options(name, bind, port, true, DEFAULT_BACKLOG, FailurePolicy.logging(), null);
        }

        /** @param frames data frames per client @return these options with that backlog */
        public Options withBacklog(int frames) {
            return new Options(name, bind, port, replay, frames, failures, token);
        }

        /**
         * @param bind  the address to listen on
         * @param token the access token clients must give, or {@code null} (then {@code bind} must be loopback)
         * @return these options listening there
         */
        public Options listening(String bind, String token) {
            return new Options(name, bind, port, replay, backlog, failures, token);
        }

        /** @return the options without the token, for the log */
        @Override
        public String toString() {
            return "Options[name=" + name + ", bind=" + bind + ", port=" + port + ", replay=" + replay + ", backlog=" + backlog
                    + (token == null ? "" : ", token given") + "]";
        }

        private static boolean loopback(String bind) {
            try {
                return java.net.InetAddress.getByName(bind).isLoopbackAddress();
            } catch (java.net.UnknownHostException e) {
                return false;
            }
        }

        /** @return whether a handshake carries the token (query {@code token=}, or a bearer {@code Authorization}), in constant time */
        boolean admits(String query, String authorization) {
            if (token == null) {
                return true;
            }
            byte[] want = token.getBytes(StandardCharsets.UTF_8);
            if (authorization != null && authorization.regionMatches(true, 0, "Bearer ", 0, 7)
                    && java.security.MessageDigest.isEqual(authorization.substring(7).trim().getBytes(StandardCharsets.UTF_8), want)) {
                return true;
            }
            if (query != null) {
                for (String pair : query.split("&")) {
                    int eq = pair.indexOf('=');
                    if (eq > 0 && pair.substring(0, eq).equals("token") && java.security.MessageDigest.isEqual(
                            java.net.URLDecoder.decode(pair.substring(eq + 1), StandardCharsets.UTF_8).getBytes(StandardCharsets.UTF_8), want)) {
                        return true;
                    }
                }
            }
            return false;
        }
    }

    private final Options options;
    private final String sessionId = String.valueOf(System.currentTimeMillis());
    private final Map<String, ChannelState> byTopic = new ConcurrentHashMap<>();
    private final Map<Long, ChannelState> byId = new ConcurrentHashMap<>();
    private final Set<ClientSession> sessions = new CopyOnWriteArraySet<>();
    private final BlockingQueue<Observation> observations = new ArrayBlockingQueue<>(OBSERVATION_QUEUE);
    private final AtomicLong droppedObservations = new AtomicLong();
    private final AtomicLong published = new AtomicLong();
    private final Object lock = new Object();
    private final OwnerThread encoder;
    private long nextChannelId = 1;
    private boolean channelsFull;
    private long lastTime = Long.MIN_VALUE;
    private long lastPing = System.nanoTime();
    private volatile Teleop teleop = Teleop.NONE;
    private volatile Driver driver;
    private volatile Server http;
    private boolean closed;

    private FoxgloveServer(Options options) {
        this.options = options;
        this.encoder = OwnerThread.start("foxglove-encode", Thread.NORM_PRIORITY, this::encodeSome, work -> { }, options.failures());
    }

    /**
     * Makes a server that takes observations at once (it keeps each channel's latest message), and
     * listens once {@link #start} is called.
     *
     * @param options how to serve
     * @return the server; close it
     */
    public static FoxgloveServer create(Options options) {
        return new FoxgloveServer(options);
    }

    /**
     * Listens for clients.
     *
     * @param teleop the robots clients may drive ({@link Teleop#NONE}: none, and no clientPublish;
     *               a replay drives none whatever it is given)
     * @return this
     * @throws IOException if the port cannot be used (the message names address and port)
     */
    public FoxgloveServer start(Teleop teleop) throws IOException {
        synchronized (lock) {
            if (http != null || closed) {
                throw new IllegalStateException("a Foxglove server starts once, and not after it was closed");
            }
            this.teleop = options.replay() ? Teleop.NONE : Objects.requireNonNull(teleop, "teleop");
            this.driver = new Driver(this.teleop, options.failures());
            QueuedThreadPool threads = new QueuedThreadPool(16, 2);
            threads.setName("foxglove-http");
            threads.setDaemon(true);
            Server server = new Server(threads);
            ServerConnector connector = new ServerConnector(server);
            connector.setHost(options.bind());
            connector.setPort(options.port());
            server.addConnector(connector);
            io.robomw.console.server.HostCheck hosts = new io.robomw.console.server.HostCheck(options.bind(), connector::getLocalPort);
            WebSocketUpgradeHandler ws = WebSocketUpgradeHandler.from(server, container -> {
                container.setMaxTextMessageSize(MAX_CLIENT_MESSAGE);
                container.setMaxBinaryMessageSize(MAX_CLIENT_MESSAGE);
                container.setIdleTimeout(Duration.ofMinutes(2));
                container.addMapping("/*", (request, response, callback) -> {
                    String host = request.getHeaders().get(HttpHeader.HOST);
                    if (!hosts.allows(host)) {
                        // a page of a site whose name was made to resolve to this machine (DNS rebinding) reads nothing
                        LOG.warn("foxglove: refused a handshake for Host {} (this server answers to {} on port {})", host, hosts.names(),
                                connector.getLocalPort());
                        Response.writeError(request, response, callback, 421, "this server answers to " + hosts.names() + ", not to '" + host + "'");
                        return null;
                    }
                    if (!options.admits(request.getHttpURI().getQuery(), request.getHeaders().get(HttpHeader.AUTHORIZATION))) {
                        LOG.warn("foxglove: refused a handshake from {} without the access token", Request.getRemoteAddr(request));
                        Response.writeError(request, response, callback, 401, "this Foxglove server needs its access token: ws://HOST:PORT/?token=TOKEN");
                        return null;
                    }
                    Optional<Subprotocol> p = Subprotocol.choose(request.getSubProtocols());
                    if (p.isEmpty()) {
                        LOG.info("foxglove: refused a handshake from {} offering subprotocols {} (neither {} nor {})", Request.getRemoteAddr(request),
                                request.getSubProtocols(), Subprotocol.SDK_V1.wire(), Subprotocol.WEBSOCKET_V1.wire());
                        Response.writeError(request, response, callback, 400, "Missing expected sec-websocket-protocol header: offer "
                                + Subprotocol.SDK_V1.wire() + " or " + Subprotocol.WEBSOCKET_V1.wire());
                        return null;
                    }
                    if (sessions.size() >= MAX_CLIENTS) {
                        Response.writeError(request, response, callback, 503, "this Foxglove server has " + MAX_CLIENTS + " clients, its most; try again later");
                        return null;
                    }
                    response.setAcceptedSubProtocol(p.get().wire());
                    String origin = request.getHeaders().get(HttpHeader.ORIGIN);
                    String peer = Request.getRemoteAddr(request) + ":" + Request.getRemotePort(request);
                    return new ClientSession(this, p.get(), Origins.mayDrive(origin), peer, options.backlog());
                });
            });
            ws.setHandler(new NotAWebSocket());
            server.setHandler(ws);
            try {
                server.start();
            } catch (Exception e) {
                try {
                    server.stop();
                } catch (Exception ignored) {
                    // it did not start
                }
                driver.close();
                throw new IOException("the Foxglove WebSocket cannot listen on " + options.bind() + ":" + options.port() + ": " + e.getMessage(), e);
            }
            this.http = server;
        }
        LOG.info("foxglove: serving at {}", address());
        return this;
    }

    /** @return where clients connect, {@code ws://127.0.0.1:8765} */
    public URI address() {
        String host = options.bind().equals("0.0.0.0") ? "127.0.0.1" : options.bind();
        return URI.create("ws://" + (host.contains(":") ? "[" + host + "]" : host) + ":" + port());
    }

    /** @return the port it listens on (the one chosen, for port 0) */
    public int port() {
        Server s = http;
        if (s == null) {
            throw new IllegalStateException("the Foxglove server is not started");
        }
        return ((ServerConnector) s.getConnectors()[0]).getLocalPort();
    }

    // ---- observations in ----

    @Override
    public void observe(Observation o) {
        if (!observations.offer(o) && droppedObservations.getAndIncrement() == 0) {
            LOG.warn("foxglove: observations come faster than they can be encoded; some are being dropped (counted)");
        }
    }

    /** The encoder thread's round: up to a thousand observations. */
    private int encodeSome() throws InterruptedException {
        pingNowAndThen();
        Observation o = observations.poll(100, TimeUnit.MILLISECONDS);
        int n = 0;
        while (o != null) {
            encode(o);
            if (++n == 1000) {
                break;
            }
            o = observations.poll();
        }
        return n;
    }

    private void encode(Observation o) {
        long t = Math.max(0, o.timeNanos());
        List<RecordingCodec.Out> out = RecordingCodec.encode(o);
        if (options.replay() && t > lastTime && !(o instanceof Observation.Batch)) {
            lastTime = t;
            for (ClientSession s : sessions) {
                s.sendData(BinaryFrames.time(t));
            }
        }
        for (RecordingCodec.Out m : out) {
            ChannelState c = channelFor(m);
            if (c != null) {
                c.publish(t, m.json());
                published.incrementAndGet();
            }
        }
    }

    private ChannelState channelFor(RecordingCodec.Out m) {
        ChannelState c = byTopic.get(m.topic());
        if (c != null) {
            return c;
        }
        synchronized (lock) {
            if (byTopic.size() >= MAX_CHANNELS) {
                if (!channelsFull) {
                    channelsFull = true;
                    LOG.warn("foxglove: {} channels, the most this server keeps; messages on new topics ({} first) are dropped", MAX_CHANNELS, m.topic());
                }
                return null;
            }
            c = new ChannelState(new Channel(nextChannelId++, m.topic(), m.schema(), new String(Schemas.json(m.schema()), StandardCharsets.UTF_8)));
            byTopic.put(m.topic(), c);
            byId.put(c.channel().id(), c);
            String advertise = ServerMessages.advertise(List.of(c.channel()));
            for (ClientSession s : sessions) {
                s.sendControl(advertise);
            }
            return c;
        }
    }

    private void pingNowAndThen() {
        long now = System.nanoTime();
        if (now - lastPing > PING_NANOS) {
            lastPing = now;
            sessions.forEach(ClientSession::ping);
        }
    }

    // ---- clients ----

    /** A client connected: it gets serverInfo and every channel known, in that order, before anything else. */
    void opened(ClientSession s) {
        synchronized (lock) {
            if (closed) {
                s.close(1001, "the server is stopping");
                return;
            }
            sessions.add(s);
            s.sendControl(serverInfo(s));
            List<Channel> all = byId.values().stream().map(ChannelState::channel).sorted((a, b) -> Long.compare(a.id(), b.id())).toList();
            for (int i = 0; i < all.size(); i += ADVERTISE_BATCH) {
                s.sendControl(ServerMessages.advertise(all.subList(i, Math.min(all.size(), i + ADVERTISE_BATCH))));
            }
        }
        LOG.info("foxglove: client {} connected ({}{})", s.peer(), s.subprotocol().wire(), offersClientPublish() && !s.mayPublish() ? ", watching only: its origin may not drive" : "");
    }

    void closed(ClientSession s) {
        if (sessions.remove(s)) {
            LOG.info("foxglove: client {} disconnected{}", s.peer(), s.dropped() > 0 ? " (" + s.dropped() + " messages were dropped for it)" : "");
        }
    }

    private String serverInfo(ClientSession s) {
        List<String> capabilities = new ArrayList<>();
        List<String> encodings = new ArrayList<>();
        if (options.replay()) {
            capabilities.add(ServerMessages.TIME);
        } else if (offersClientPublish() && s.mayPublish()) {
            capabilities.add(ServerMessages.CLIENT_PUBLISH);
            encodings.add(Schemas.MESSAGE_ENCODING);
        }
        return ServerMessages.serverInfo(options.name(), capabilities, encodings, Map.of("robomw.format", McapRecorder.FORMAT_VERSION), sessionId);
    }

    /** @return whether clients may publish to drive robots */
    boolean offersClientPublish() {
        return teleop != Teleop.NONE;
    }

    /** @return the channel with that id, or null */
    ChannelState channel(long id) {
        return byId.get(id);
    }

    Driver driver() {
        return driver;
    }

    /**
     * @param topic a client channel's topic
     * @return the robot a Twist on it drives: R for {@code /robots/R/cmd_vel}, or the only robot
     *         for {@code /cmd_vel}
     */
    Optional<String> robotFor(String topic) {
        Set<String> robots = teleop.robots();
        if (topic.equals("/cmd_vel") || topic.equals("cmd_vel")) {
            return robots.size() == 1 ? Optional.of(robots.iterator().next()) : Optional.empty();
        }
        String[] parts = topic.split("/", -1);
        if (parts.length == 4 && parts[0].isEmpty() && parts[1].equals("robots") && parts[3].equals("cmd_vel") && robots.contains(parts[2])) {
            return Optional.of(parts[2]);
        }
        return Optional.empty();
    }

    /** @return the robots that can be driven, for an error message */
    String describeDrivable() {
        Set<String> robots = teleop.robots();
        return robots.isEmpty() ? " (this server drives no robot now)"
                : " for R in " + robots.stream().sorted().toList() + (robots.size() == 1 ? ", or on /cmd_vel" : "");
    }

    /** @return clients connected now */
    public int clients() {
        return sessions.size();
    }

    /** @return messages queued for subscribers so far (each message counted once, whatever its subscribers) */
    public long published() {
        return published.get();
    }

    /** @return data frames dropped so far for the clients connected now, because they were slower than the data */
    public long droppedForClients() {
        return sessions.stream().mapToLong(ClientSession::dropped).sum();
    }

    /** @return observations dropped because they came faster than they could be encoded */
    public long droppedObservations() {
        return droppedObservations.get();
    }

    /** Answers a plain HTTP request: this port is a WebSocket. */
    private static final class NotAWebSocket extends Handler.Abstract {
        @Override
        public boolean handle(Request request, Response response, Callback callback) {
            Response.writeError(request, response, callback, 400, "this is RoboMW's Foxglove WebSocket: open it in Foxglove "
                    + "(Open connection, Foxglove WebSocket, ws://HOST:PORT), or connect with the subprotocol " + Subprotocol.SDK_V1.wire());
            return true;
        }
    }

    /** Disconnects every client, stops listening and stops the threads; a robot driven by a client is handed a zero Twist first. */
    @Override
    public void close() {
        Server s;
        synchronized (lock) {
            if (closed) {
                return;
            }
            closed = true;
            s = http;
        }
        for (ClientSession c : sessions) {
            c.close(1001, "the server is stopping");
        }
        if (s != null) {
            try {
                s.stop();
            } catch (Exception e) {
                LOG.warn("foxglove: stopping the WebSocket server failed: {}", e.toString());
            }
        }
        encoder.close();
        Driver d = driver;
        if (d != null) {
            d.close();
        }
    }
}
