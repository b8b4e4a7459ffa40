package io.robomw.bench;

import com.fasterxml.jackson.databind.JsonNode;
import com.fasterxml.jackson.databind.ObjectMapper;
import io.robomw.console.rosbridge.RosBridge;

import java.io.BufferedReader;
import java.io.IOException;
import java.io.InputStreamReader;
import java.net.InetAddress;
import java.net.InetSocketAddress;
import java.net.ServerSocket;
import java.net.URI;
import java.net.http.HttpClient;
import java.net.http.WebSocket;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.ArrayList;
import java.util.Arrays;
import java.util.List;
import java.util.Locale;
import java.util.concurrent.BlockingQueue;
import java.util.concurrent.CompletionStage;
import java.util.concurrent.LinkedBlockingQueue;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicLong;
import java.util.function.Consumer;

/**
 * The rosbridge endpoint's speed (docs/benchmarks.md, "rosbridge (issue 34)"), outside
 * {@code mvn verify}: run by {@code bench/rosbridge} ({@code bench/all --cases rosbridge}), each
 * sample in fresh JVMs. Two cases, each with its baseline in the same run:
 *
 * <ul>
 *   <li><b>Odometry fan-out</b>: {@code mw sim examples/worlds/swarm-100.yaml --rosbridge PORT
 *   --rosbridge-odom-rate 50} in its own JVM, and one client (the JDK's WebSocket, in this JVM)
 *   subscribed to all 100 robots' {@code /<ns>/odom}: the messages per second it gets (5,000 is
 *   every one), the CPU per message of the endpoint's own threads ({@code rosbridge-*}: sampling
 *   the poses, building and encoding the messages, the socket), and of the whole server JVM over
 *   its baseline, the same JVM in the same run before the client subscribed (the world alone).
 *   CPU is read from /proc per thread (Linux).</li>
 *   <li><b>Publish round trip</b>: a bridge with no robots in its own JVM; the client advertises
 *   and subscribes to {@code /bench} ({@code std_msgs/msg/String}) and publishes a 64-byte string,
 *   waiting for it to come back, one at a time; the baseline is a plain WebSocket echo of a
 *   64-byte text frame on the same server ({@code RosBridge.Builder.echo}), in the same JVMs,
 *   blocks of the two interleaved. Median and 99th percentile.</li>
 * </ul>
 *
 * Prints one {@code BENCH} line per figure ({@link BenchReport}). Usage:
 * {@code RosBridgeBenchmark [--smoke] [--cases odom,rtt]}; {@code RosBridgeBenchmark serve PORT}
 * is the round trip's server.
 */
public final class RosBridgeBenchmark {

    private static final ObjectMapper JSON = new ObjectMapper();
    private static final Path CHECKOUT = Path.of("..").toAbsolutePath().normalize();
    private static final int PAYLOAD = 64;

    private RosBridgeBenchmark() {
    }

    public static void main(String[] args) throws Exception {
        if (args.length == 2 && args[0].equals("serve")) {
            serve(Integer.parseInt(args[1]));
            return;
        }
        boolean smoke = Arrays.asList(args).contains("--smoke");
        String cases = "odom,rtt";
        for (int i = 0; i < args.length - 1; i++) {
            if (args[i].equals("--cases")) {
                cases = args[i + 1];
            }
        }
        if (cases.contains("odom")) {
            odometry(smoke ? 2 : 5, smoke ? 3 : 10);
        }
        if (cases.contains("rtt")) {
            roundTrip(smoke ? 2_000 : 10_000, smoke ? 2_000 : 10_000, smoke ? 1 : 3);
        }
    }

    // ---- odometry of 100 robots at 50 Hz to one client ----

    private static void odometry(int warmSeconds, int measureSeconds) throws Exception {
        int port = freePort();
        Process server = jvm("io.robomw.cli.Mw", "sim", CHECKOUT.resolve("examples/worlds/swarm-100.yaml").toString(), "--rosbridge", String.valueOf(port),
                "--rosbridge-odom-rate", "50");
        try {
            awaitLine(server, "rosbridge at ");
            long pid = server.pid();
            Thread.sleep(warmSeconds * 1000L); // the world alone, warming up
            long idle0 = ProcCpu.of(pid, "");
            long idleStart = System.nanoTime();
            Thread.sleep(measureSeconds * 1000L);
            double idleCpuPerSecond = (ProcCpu.of(pid, "") - idle0) / ((System.nanoTime() - idleStart) / 1e9);
            AtomicLong received = new AtomicLong();
            try (Client c = Client.connect(URI.create("ws://127.0.0.1:" + port + "/"), f -> {
                if (f.contains("\"op\":\"publish\"")) {
                    received.incrementAndGet();
                }
            })) {
                List<String> topics = odometryTopics(port);
                for (String t : topics) {
                    c.send("{\"op\":\"subscribe\",\"id\":\"s" + t + "\",\"topic\":\"" + t + "\",\"type\":\"nav_msgs/msg/Odometry\"}");
                }
                Thread.sleep(warmSeconds * 1000L);
                long n0 = received.get();
                long endpoint0 = ProcCpu.of(pid, "rosbridge");
                long all0 = ProcCpu.of(pid, "");
                long t0 = System.nanoTime();
                Thread.sleep(measureSeconds * 1000L);
                long n1 = received.get();
                long endpoint1 = ProcCpu.of(pid, "rosbridge");
                long all1 = ProcCpu.of(pid, "");
                double seconds = (System.nanoTime() - t0) / 1e9;
                long messages = n1 - n0;
                double rate = messages / seconds;
                double endpointUs = (endpoint1 - endpoint0) / 1e3 / messages;
                double marginalUs = ((all1 - all0) - idleCpuPerSecond * seconds) / 1e3 / messages;
                System.out.printf(Locale.ROOT, "odometry: %d topics, %.0f messages/s (of %d), endpoint threads %.1f µs CPU per message "
                                + "(%.0f%% of a core), the server JVM %.1f µs per message over the world alone (%.0f%% of a core)%n", topics.size(), rate,
                        topics.size() * 50, endpointUs, (endpoint1 - endpoint0) / 1e7 / seconds, marginalUs, idleCpuPerSecond / 1e7);
                System.out.println(BenchReport.line("rosbridge.odom100x50.rate", rate, "msg/s"));
                System.out.println(BenchReport.line("rosbridge.odom100x50.endpoint-cpu-per-msg", endpointUs, "us"));
                System.out.println(BenchReport.line("rosbridge.odom100x50.jvm-cpu-per-msg", marginalUs, "us"));
                System.out.println(BenchReport.line("rosbridge.odom100x50.world-alone-cpu", idleCpuPerSecond / 1e7, "%core"));
            }
        } finally {
            server.destroy();
            if (!server.waitFor(15, TimeUnit.SECONDS)) {
                server.destroyForcibly();
            }
        }
    }

    /** The odometry topics rosapi lists. */
    private static List<String> odometryTopics(int port) throws Exception {
        BlockingQueue<String> answer = new LinkedBlockingQueue<>();
        try (Client c = Client.connect(URI.create("ws://127.0.0.1:" + port + "/"), answer::add)) {
            c.send("{\"op\":\"call_service\",\"id\":\"t\",\"service\":\"/rosapi/topics\"}");
            String a = answer.poll(30, TimeUnit.SECONDS);
            if (a == null) {
                throw new IOException("rosapi did not answer");
            }
            List<String> out = new ArrayList<>();
            for (JsonNode t : JSON.readTree(a).at("/values/topics")) {
                if (t.asText().endsWith("/odom")) {
                    out.add(t.asText());
                }
            }
            return out;
        }
    }

    // ---- 64-byte publish round trip against a plain echo on the same server ----

    private static void serve(int port) throws Exception {
        try (RosBridge bridge = RosBridge.builder().listen("127.0.0.1", port).echo("/echo").start()) {
            System.out.println("serving at " + bridge.address());
            System.out.flush();
            while (System.in.read() >= 0) {
                // until the harness closes our stdin
            }
        }
    }

    private static void roundTrip(int warm, int measured, int blocks) throws Exception {
        int port = freePort();
        Process server = jvm(RosBridgeBenchmark.class.getName(), "serve", String.valueOf(port));
        try {
            awaitLine(server, "serving at ");
            BlockingQueue<String> echoes = new LinkedBlockingQueue<>();
            BlockingQueue<String> publishes = new LinkedBlockingQueue<>();
            String payload = "x".repeat(PAYLOAD);
            try (Client echo = Client.connect(URI.create("ws://127.0.0.1:" + port + "/echo"), echoes::add);
                 Client bridge = Client.connect(URI.create("ws://127.0.0.1:" + port + "/"), publishes::add)) {
                bridge.send("{\"op\":\"advertise\",\"id\":\"a\",\"topic\":\"/bench\",\"type\":\"std_msgs/msg/String\"}");
                bridge.send("{\"op\":\"subscribe\",\"id\":\"s\",\"topic\":\"/bench\",\"type\":\"std_msgs/msg/String\"}");
                String publish = "{\"op\":\"publish\",\"topic\":\"/bench\",\"msg\":{\"data\":\"" + payload + "\"}}";
                times(echo, payload, echoes, warm);
                times(bridge, publish, publishes, warm);
                long[] e = new long[measured * blocks];
                long[] b = new long[measured * blocks];
                for (int k = 0; k < blocks; k++) {
                    System.arraycopy(times(echo, payload, echoes, measured), 0, e, k * measured, measured);
                    System.arraycopy(times(bridge, publish, publishes, measured), 0, b, k * measured, measured);
                }
                Arrays.sort(e);
                Arrays.sort(b);
                double e50 = e[e.length / 2] / 1e3;
                double e99 = e[(int) (e.length * 0.99)] / 1e3;
                double b50 = b[b.length / 2] / 1e3;
                double b99 = b[(int) (b.length * 0.99)] / 1e3;
                System.out.printf(Locale.ROOT, "round trip, 64 B: plain WebSocket echo p50 %.1f µs p99 %.1f µs; rosbridge publish p50 %.1f µs p99 %.1f µs (%.2fx)%n",
                        e50, e99, b50, b99, b50 / e50);
                System.out.println(BenchReport.line("rosbridge.rtt64.echo.p50", e50, "us"));
                System.out.println(BenchReport.line("rosbridge.rtt64.echo.p99", e99, "us"));
                System.out.println(BenchReport.line("rosbridge.rtt64.publish.p50", b50, "us"));
                System.out.println(BenchReport.line("rosbridge.rtt64.publish.p99", b99, "us"));
            }
        } finally {
            server.getOutputStream().close();
            if (!server.waitFor(15, TimeUnit.SECONDS)) {
                server.destroyForcibly();
            }
        }
    }

    private static long[] times(Client c, String frame, BlockingQueue<String> replies, int n) throws Exception {
        long[] t = new long[n];
        for (int i = 0; i < n; i++) {
            long start = System.nanoTime();
            c.send(frame);
            if (replies.poll(30, TimeUnit.SECONDS) == null) {
                throw new IOException("no reply within 30 s at round trip " + i);
            }
            t[i] = System.nanoTime() - start;
        }
        return t;
    }

    // ---- plumbing ----

    /** A JDK WebSocket client that hands every text frame to a consumer. */
    private static final class Client implements AutoCloseable {
        /** Held: an HttpClient no one references closes its connections when it is collected. */
        private final HttpClient http;
        private final WebSocket socket;

        private Client(HttpClient http, WebSocket socket) {
            this.http = http;
            this.socket = socket;
        }

        static Client connect(URI uri, Consumer<String> frames) throws Exception {
            HttpClient http = HttpClient.newHttpClient();
            WebSocket ws = http.newWebSocketBuilder().buildAsync(uri, new WebSocket.Listener() {
                private final StringBuilder text = new StringBuilder();

                @Override
                public CompletionStage<?> onText(WebSocket w, CharSequence data, boolean last) {
                    text.append(data);
                    if (last) {
                        frames.accept(text.toString());
                        text.setLength(0);
                    }
                    w.request(1);
                    return null;
                }

                @Override
                public CompletionStage<?> onClose(WebSocket w, int status, String reason) {
                    System.err.println("bench: " + uri + " closed: " + status + " " + reason);
                    return null;
                }

                @Override
                public void onError(WebSocket w, Throwable error) {
                    System.err.println("bench: " + uri + " failed: " + error);
                }
            }).get(30, TimeUnit.SECONDS);
            return new Client(http, ws);
        }

        void send(String text) throws Exception {
            socket.sendText(text, true).get(30, TimeUnit.SECONDS);
        }

        @Override
        public void close() {
            socket.abort();
        }
    }

    /** CPU time of a process's threads, from /proc (Linux), in nanoseconds. */
    private static final class ProcCpu {
        private static final long NANOS_PER_TICK = 10_000_000L; // USER_HZ is 100 on Linux

        static long of(long pid, String threadPrefix) throws IOException {
            long ticks = 0;
            try (var tasks = Files.list(Path.of("/proc", String.valueOf(pid), "task"))) {
                for (Path task : tasks.toList()) {
                    try {
                        String comm = Files.readString(task.resolve("comm")).strip();
                        if (!comm.startsWith(threadPrefix)) {
                            continue;
                        }
                        String stat = Files.readString(task.resolve("stat"));
                        String[] f = stat.substring(stat.lastIndexOf(')') + 2).split(" ");
                        ticks += Long.parseLong(f[11]) + Long.parseLong(f[12]); // utime, stime: fields 14 and 15
                    } catch (IOException e) {
                        // the thread ended meanwhile
                    }
                }
            }
            return ticks * NANOS_PER_TICK;
        }
    }

    private static Process jvm(String main, String... args) throws IOException {
        List<String> command = new ArrayList<>(List.of(Path.of(System.getProperty("java.home"), "bin", "java").toString(), "-Xmx2g",
                "-Dorg.slf4j.simpleLogger.defaultLogLevel=warn", "-Dmw.home=" + CHECKOUT, "-cp", System.getProperty("java.class.path"), main));
        command.addAll(List.of(args));
        Path log = Path.of("target", "bench-logs");
        Files.createDirectories(log);
        return new ProcessBuilder(command).directory(CHECKOUT.toFile()).redirectError(log.resolve("rosbridge-server.log").toFile()).start();
    }

    private static void awaitLine(Process p, String text) throws IOException {
        BufferedReader r = new BufferedReader(new InputStreamReader(p.getInputStream(), StandardCharsets.UTF_8));
        long deadline = System.nanoTime() + TimeUnit.SECONDS.toNanos(120);
        for (String line; (line = r.readLine()) != null; ) {
            if (line.contains(text)) {
                Thread drainer = new Thread(() -> {
                    try {
                        while (r.readLine() != null) {
                            // keep its pipe empty
                        }
                    } catch (IOException ignored) {
                        // it ended
                    }
                }, "bench-server-stdout");
                drainer.setDaemon(true);
                drainer.start();
                return;
            }
            if (System.nanoTime() > deadline) {
                break;
            }
        }
        throw new IOException("the server did not print '" + text + "' (log: target/bench-logs/rosbridge-server.log)");
    }

    private static int freePort() throws IOException {
        try (ServerSocket s = new ServerSocket()) {
            s.bind(new InetSocketAddress(InetAddress.getLoopbackAddress(), 0));
            return s.getLocalPort();
        }
    }
}
