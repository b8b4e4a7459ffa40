package io.robomw.bench;

import io.robomw.console.foxglove.BinaryFrames;
import io.robomw.console.foxglove.FoxgloveServer;
import io.robomw.console.foxglove.Teleop;
import io.robomw.console.observe.Observation;
import io.robomw.console.record.RecordingCodec;
import io.robomw.it.demo.MwProcess;
import org.eclipse.jetty.server.Server;
import org.eclipse.jetty.server.ServerConnector;
import org.eclipse.jetty.util.thread.QueuedThreadPool;
import org.eclipse.jetty.websocket.api.Callback;
import org.eclipse.jetty.websocket.api.Session;
import org.eclipse.jetty.websocket.server.WebSocketUpgradeHandler;

import java.io.BufferedReader;
import java.io.File;
import java.io.InputStreamReader;
import java.lang.management.ManagementFactory;
import java.net.URI;
import java.net.http.HttpClient;
import java.net.http.WebSocket;
import java.nio.ByteBuffer;
import java.nio.charset.StandardCharsets;
import java.util.ArrayList;
import java.util.List;
import java.util.Locale;
import java.util.concurrent.CompletionStage;
import java.util.concurrent.CopyOnWriteArrayList;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicLong;

/**
 * The live Foxglove WebSocket's cost (docs/benchmarks.md, "Foxglove live stream"): the poses of
 * {@code --robots} simulated robots at {@code --hz} (each a {@code foxglove.PoseInFrame} on
 * {@code /robots/R/pose} and a {@code foxglove.FrameTransform} on {@code /tf}, as {@code SimSource}
 * makes them) to one Foxglove client in another JVM, subscribed to every channel; and, as the
 * baseline, a plain Jetty WebSocket endpoint (same Jetty, same thread pool and connector settings)
 * sending the same frames, encoded once beforehand, to the same kind of client. The figure is the
 * server JVM's CPU time per message sent in the measured window (all its threads: the source, the
 * encoder, Jetty's), with the share of messages the client got.
 *
 * <p>{@code FoxgloveBenchmark foxglove|plain [--robots N] [--hz F] [--warmup S] [--measure S]} runs
 * one case in this fresh JVM and prints {@code BENCH} lines; {@code bench/foxglove} runs both cases
 * five times, interleaved, and prints the median, min and max. {@code FoxgloveBenchmark client URL
 * foxglove|plain} is the client.
 */
public final class FoxgloveBenchmark {

    private FoxgloveBenchmark() {
    }

    public static void main(String[] args) throws Exception {
        if (args[0].equals("client")) {
            client(URI.create(args[1]), args[2].equals("foxglove"), Integer.parseInt(args[3]));
            return;
        }
        boolean foxglove = args[0].equals("foxglove");
        int robots = 100;
        double hz = 50;
        double warmup = 3;
        double measure = 10;
        for (int i = 1; i + 1 < args.length; i += 2) {
            switch (args[i]) {
                case "--robots" -> robots = Integer.parseInt(args[i + 1]);
                case "--hz" -> hz = Double.parseDouble(args[i + 1]);
                case "--warmup" -> warmup = Double.parseDouble(args[i + 1]);
                case "--measure" -> measure = Double.parseDouble(args[i + 1]);
                default -> throw new IllegalArgumentException("unknown option " + args[i]);
            }
        }
        if (foxglove) {
            runFoxglove(robots, hz, warmup, measure);
        } else {
            runPlain(robots, hz, warmup, measure);
        }
    }

    // ---- the source: robots moving on circles ----

    private static List<Observation> tick(int robots, long t, double time) {
        List<Observation> out = new ArrayList<>(robots);
        for (int r = 0; r < robots; r++) {
            double a = time * 0.5 + r;
            out.add(new Observation.RobotPose(t, "r" + r, 2 + Math.cos(a), 1.5 + Math.sin(a), a + Math.PI / 2, true));
        }
        return out;
    }

    /** Calls {@code each} every period, on this thread, until the deadline; returns ticks run. */
    private static long paced(double hz, double seconds, java.util.function.LongConsumer each) {
        long period = Math.round(1e9 / hz);
        long start = System.nanoTime();
        long end = start + Math.round(seconds * 1e9);
        long n = 0;
        for (long next = start; next < end; next += period) {
            long wait = next - System.nanoTime();
            if (wait > 0) {
                java.util.concurrent.locks.LockSupport.parkNanos(wait); // the source's pace, not a wait for a condition
            }
            each.accept(n++);
        }
        return n;
    }

    // ---- the two cases ----

    private static void runFoxglove(int robots, double hz, double warmup, double measure) throws Exception {
        try (FoxgloveServer server = FoxgloveServer.create(FoxgloveServer.Options.live("bench", "127.0.0.1", 0)).start(Teleop.NONE)) {
            long epoch = System.currentTimeMillis() * 1_000_000L;
            for (Observation o : tick(robots, epoch, 0)) {
                server.observe(o); // every channel exists before the client subscribes
            }
            long deadline = System.nanoTime() + TimeUnit.SECONDS.toNanos(30);
            while (server.published() < 2L * robots && System.nanoTime() < deadline) {
                Thread.sleep(10); // a benchmark harness: waits for the first tick to be encoded
            }
            try (ClientProcess client = ClientProcess.start(server.address(), "foxglove", robots + 1)) { // a pose channel per robot, and /tf
                java.util.function.LongConsumer each = n -> {
                    long t = epoch + Math.round(n * 1e9 / hz);
                    for (Observation o : tick(robots, t, n / hz)) {
                        server.observe(o);
                    }
                };
                paced(hz, warmup, each);
                measured("foxglove", robots, hz, measure, client, each);
            }
        }
    }

    private static void runPlain(int robots, double hz, double warmup, double measure) throws Exception {
        List<Session> sessions = new CopyOnWriteArrayList<>();
        QueuedThreadPool threads = new QueuedThreadPool(16, 2);
        threads.setName("plain-http");
        threads.setDaemon(true);
        Server server = new Server(threads);
        ServerConnector connector = new ServerConnector(server);
        connector.setHost("127.0.0.1");
        connector.setPort(0);
        server.addConnector(connector);
        server.setHandler(WebSocketUpgradeHandler.from(server, c -> c.addMapping("/*", (rq, rs, cb) -> new PlainEndpoint(sessions))));
        server.start();
        try {
            // The same frames the Foxglove server sends: MESSAGE_DATA with the codec's JSON, encoded once here.
            long epoch = System.currentTimeMillis() * 1_000_000L;
            List<byte[]> frames = new ArrayList<>();
            int sub = 1;
            for (Observation o : tick(robots, epoch, 0)) {
                for (RecordingCodec.Out m : RecordingCodec.encode(o)) {
                    ByteBuffer b = BinaryFrames.messageData(sub++, epoch, m.json());
                    byte[] a = new byte[b.remaining()];
                    b.get(a);
                    frames.add(a);
                }
            }
            URI uri = URI.create("ws://127.0.0.1:" + connector.getLocalPort() + "/");
            try (ClientProcess client = ClientProcess.start(uri, "plain", 0)) {
                java.util.function.LongConsumer each = n -> {
                    for (Session s : sessions) {
                        for (byte[] f : frames) {
                            s.sendBinary(ByteBuffer.wrap(f), Callback.NOOP);
                        }
                    }
                };
                paced(hz, warmup, each);
                measured("plain", robots, hz, measure, client, each);
            }
        } finally {
            server.stop();
        }
    }

    /** The baseline's endpoint: keeps its session to send to. Public: Jetty calls it through method handles. */
    public static final class PlainEndpoint extends Session.Listener.AbstractAutoDemanding {
        private final List<Session> sessions;

        PlainEndpoint(List<Session> sessions) {
            this.sessions = sessions;
        }

        @Override
        public void onWebSocketOpen(Session s) {
            super.onWebSocketOpen(s);
            sessions.add(s);
        }
    }

    private static void measured(String name, int robots, double hz, double measure, ClientProcess client, java.util.function.LongConsumer each) throws Exception {
        com.sun.management.OperatingSystemMXBean os = (com.sun.management.OperatingSystemMXBean) ManagementFactory.getOperatingSystemMXBean();
        long received0 = client.received();
        long cpu0 = os.getProcessCpuTime();
        ThreadCpu threads = ThreadCpu.now();
        long ticks = paced(hz, measure, each);
        long cpu = os.getProcessCpuTime() - cpu0;
        String busy = threads.since();
        long sent = ticks * robots * 2;
        long received = client.receivedAfterQuiet() - received0;
        System.out.println("threads " + busy);
        System.out.println(BenchReport.line(name + "-cpu-us-per-msg", cpu / 1e3 / sent, "us"));
        System.out.println(BenchReport.line(name + "-delivered", Math.min(1.0, (double) received / sent), "share"));
        System.out.println(BenchReport.line(name + "-msgs-per-s", sent / measure, "msg/s"));
    }

    // ---- the client, in its own JVM ----

    /** The client JVM: connects, subscribes to everything, and prints how many messages it got when asked. */
    private static final class ClientProcess implements AutoCloseable {
        private final Process process;
        private final BufferedReader out;

        private ClientProcess(Process process) {
            this.process = process;
            this.out = new BufferedReader(new InputStreamReader(process.getInputStream(), StandardCharsets.UTF_8));
        }

        static ClientProcess start(URI uri, String mode, int channels) throws Exception {
            String java = System.getProperty("java.home") + File.separator + "bin" + File.separator + "java";
            Process p = new ProcessBuilder(java, "-Xmx512m", "-cp", System.getProperty("java.class.path"), FoxgloveBenchmark.class.getName(),
                    "client", uri.toString(), mode, String.valueOf(channels)).redirectError(ProcessBuilder.Redirect.INHERIT).start();
            ClientProcess c = new ClientProcess(p);
            String ready = c.out.readLine();
            if (ready == null || !ready.startsWith("ready")) {
                c.close();
                throw new IllegalStateException("the client did not start: " + ready);
            }
            if (channels > 0 && !ready.equals("ready " + channels)) {
                c.close();
                throw new IllegalStateException("the client subscribed to " + ready + ", expected " + channels + " channels");
            }
            return c;
        }

        long received() throws Exception {
            process.getOutputStream().write('\n');
            process.getOutputStream().flush();
            return Long.parseLong(out.readLine().trim());
        }

        /** @return messages received, once they stop growing for a moment (what was in flight has arrived) */
        long receivedAfterQuiet() throws Exception {
            long last = -1;
            for (int i = 0; i < 50; i++) {
                long now = received();
                if (now == last) {
                    return now;
                }
                last = now;
                Thread.sleep(200); // a benchmark harness, not a test: waits for in-flight frames to land
            }
            return last;
        }

        @Override
        public void close() {
            process.destroy();
            try {
                process.waitFor(10, TimeUnit.SECONDS);
            } catch (InterruptedException e) {
                Thread.currentThread().interrupt();
            }
            process.destroyForcibly();
        }
    }

    private static void client(URI uri, boolean foxglove, int expectedChannels) throws Exception {
        AtomicLong received = new AtomicLong();
        CountDownLatch advertised = new CountDownLatch(Math.max(1, expectedChannels));
        List<Long> channels = new CopyOnWriteArrayList<>();
        WebSocket.Builder b = HttpClient.newHttpClient().newWebSocketBuilder();
        if (foxglove) {
            b.subprotocols("foxglove.sdk.v1");
        }
        WebSocket ws = b.buildAsync(uri, new WebSocket.Listener() {
            private final StringBuilder text = new StringBuilder();

            @Override
            public CompletionStage<?> onText(WebSocket w, CharSequence data, boolean last) {
                text.append(data);
                if (last) {
                    String t = text.toString();
                    text.setLength(0);
                    if (t.contains("\"op\":\"advertise\"")) {
                        java.util.regex.Matcher m = java.util.regex.Pattern.compile("\"id\":(\\d+),\"topic\"").matcher(t);
                        while (m.find()) {
                            channels.add(Long.parseLong(m.group(1)));
                            advertised.countDown();
                        }
                    }
                }
                w.request(1);
                return null;
            }

            @Override
            public CompletionStage<?> onBinary(WebSocket w, ByteBuffer data, boolean last) {
                if (last) {
                    received.incrementAndGet();
                }
                w.request(1);
                return null;
            }
        }).get(30, TimeUnit.SECONDS);
        if (foxglove) {
            if (!advertised.await(30, TimeUnit.SECONDS)) {
                throw new IllegalStateException("no advertise from " + uri);
            }
            StringBuilder sub = new StringBuilder("{\"op\":\"subscribe\",\"subscriptions\":[");
            for (int i = 0; i < channels.size(); i++) {
                sub.append(i == 0 ? "" : ",").append("{\"id\":").append(channels.get(i)).append(",\"channelId\":").append(channels.get(i)).append('}');
            }
            ws.sendText(sub.append("]}"), true).get(30, TimeUnit.SECONDS);
        }
        System.out.println("ready " + channels.size());
        System.out.flush();
        BufferedReader in = new BufferedReader(new InputStreamReader(System.in, StandardCharsets.UTF_8));
        while (in.readLine() != null) {
            System.out.println(received.get());
            System.out.flush();
        }
        ws.abort();
        System.out.printf(Locale.ROOT, "%d%n", received.get());
    }
}
