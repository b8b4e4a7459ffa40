package io.robomw.bench;

import io.robomw.agents.messaging.MessagingNode;
import io.robomw.agents.messaging.MessagingSettings;
import io.robomw.it.messaging.PeerProcess;
import org.zeromq.SocketType;
import org.zeromq.ZContext;
import org.zeromq.ZMQ;

import java.io.DataInputStream;
import java.io.IOException;
import java.io.OutputStream;
import java.net.DatagramSocket;
import java.net.InetAddress;
import java.net.InetSocketAddress;
import java.net.NetworkInterface;
import java.net.Socket;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.ArrayList;
import java.util.Arrays;
import java.util.List;
import java.util.Locale;
import java.util.UUID;
import java.util.function.LongSupplier;

/**
 * Messaging benchmark between two JVMs on loopback (this one drives, a {@link BenchPeer} answers
 * or subscribes): 64-byte request/reply latency (p50, p99) and 64-byte publish/subscribe
 * throughput, per RoboMW transport, with a raw {@link Socket} ping-pong and JeroMQ REQ/REP and
 * PUB/SUB as baselines in the same run. Writes {@code target/benchmarks/messaging.md}.
 *
 * <p>Run: {@code mvn -B -Pbench verify -pl src-it -am -Dtest=none -Dsurefire.failIfNoSpecifiedTests=false}
 * (see docs/benchmarks.md). Not part of the normal test run.
 */
public final class MessagingBenchmark {

    static final int SIZE = 64;
    static final int LATENCY_WARMUP = Integer.getInteger("bench.rrWarmup", 20_000);
    static final int LATENCY_MEASURED = Integer.getInteger("bench.rrMeasured", 100_000);
    static final long PUBSUB_WARMUP = Long.getLong("bench.psWarmup", 300_000);
    /** Measured messages of the JeroMQ and TCP publish/subscribe cases ({@code -Dbench.psMessages}); the others take a fraction. */
    static final long PUBSUB_MESSAGES = Long.getLong("bench.psMessages", 2_000_000);
    static final int ROUNDS = 3;

    private final List<String> rows = new ArrayList<>();
    private final List<String> log = new ArrayList<>();

    /** One latency result, microseconds. @param name case @param p50 median @param p99 99th percentile @param mean mean */
    record Latency(String name, double p50, double p99, double mean) {
    }

    /** One throughput result. @param name case @param messages measured messages received @param sent measured messages sent @param perSecond received per second */
    record Throughput(String name, long messages, long sent, double perSecond) {
    }

    /**
     * @param args ignored
     * @throws Exception on failure
     */
    public static void main(String[] args) throws Exception {
        new MessagingBenchmark().run();
    }

    void run() throws Exception {
        List<Latency> latencies = new ArrayList<>();
        latency(latencies, "rr-raw", this::rawPingPong);
        latency(latencies, "rr-zmq", this::zmqReqRep);
        latency(latencies, "rr-tcp", () -> mwReqRep("tcp", "tcp://127.0.0.1:0"));
        latency(latencies, "rr-tcp-nospin", () -> mwReqRep("tcp", "tcp://127.0.0.1:0", Duration.ZERO));
        latency(latencies, "rr-rmi", () -> mwReqRep("rmi", "rmi://127.0.0.1:0/bench"));
        latency(latencies, "rr-udp", () -> mwReqRep("udp", "udp://127.0.0.1:0"));
        latency(latencies, "rr-multicast", () -> mwReqRep("multicast", group()));
        List<Throughput> throughputs = new ArrayList<>();
        throughput(throughputs, "ps-zmq", () -> zmqPubSub(PUBSUB_MESSAGES));
        throughput(throughputs, "ps-tcp", () -> mwPubSub("tcp", "tcp://127.0.0.1:0", PUBSUB_MESSAGES));
        throughput(throughputs, "ps-rmi", () -> mwPubSub("rmi", "rmi://127.0.0.1:0/bench", PUBSUB_MESSAGES / 2));
        throughput(throughputs, "ps-udp", () -> mwPubSub("udp", "udp://127.0.0.1:0", PUBSUB_MESSAGES / 4));
        throughput(throughputs, "ps-multicast", () -> mwPubSub("multicast", group(), PUBSUB_MESSAGES / 4));
        write(latencies, throughputs);
    }

    /** A latency case. */
    @FunctionalInterface
    interface LatencyCase {
        Latency run() throws Exception;
    }

    /** Runs a latency case unless {@code -Dbench.cases} leaves it out. */
    private static void latency(List<Latency> into, String key, LatencyCase c) throws Exception {
        if (selected(key)) {
            Latency l = c.run();
            System.out.println(BenchReport.line("msg." + key, l.p50(), "µs"));
            into.add(l);
        }
    }

    private void throughput(List<Throughput> into, String key, Case c) throws Exception {
        if (selected(key)) {
            into.add(median(key, c));
        }
    }

    /**
     * @param key a case: rr-raw, rr-zmq, rr-tcp, rr-tcp-nospin, rr-rmi, rr-udp, rr-multicast,
     *            ps-zmq, ps-tcp, ps-rmi, ps-udp, ps-multicast
     * @return whether {@code -Dbench.cases} (a comma-separated list; default all) names it
     */
    private static boolean selected(String key) {
        String cases = System.getProperty("bench.cases", "").trim();
        return cases.isEmpty() || Arrays.asList(cases.split("\\s*,\\s*")).contains(key);
    }

    /** @return the runs per throughput case: {@code -Dbench.rounds}, default {@value #ROUNDS} */
    private static int rounds() {
        return Integer.getInteger("bench.rounds", ROUNDS);
    }

    /** A throughput case, run in fresh processes. */
    @FunctionalInterface
    interface Case {
        Throughput run() throws Exception;
    }

    /** Runs a throughput case {@value #ROUNDS} times (throughput on a shared 2-core machine varies) and keeps the median. */
    private Throughput median(String key, Case c) throws Exception {
        List<Throughput> runs = new ArrayList<>();
        int rounds = rounds();
        for (int i = 0; i < rounds; i++) {
            Throughput t = c.run();
            System.out.println(BenchReport.line("msg." + key, t.perSecond(), "msg/s"));
            runs.add(t);
        }
        say(runs.get(0).name() + " runs (msg/s): " + runs.stream().map(t -> String.format(Locale.ROOT, "%,.0f", t.perSecond())).toList());
        runs.sort(java.util.Comparator.comparingDouble(Throughput::perSecond));
        Throughput m = runs.get(rounds / 2);
        say(String.format(Locale.ROOT, "%-48s median of %d: %,12.0f msg/s", m.name(), rounds, m.perSecond()));
        return m;
    }

    // ---- request/reply ----

    private Latency rawPingPong() throws Exception {
        try (PeerProcess peer = bench("bench-raw-echo", "raw-echo")) {
            int port = Integer.parseInt(peer.expect("PORT", PeerProcess.COMMAND).substring(5));
            try (Socket s = new Socket(InetAddress.getLoopbackAddress(), port)) {
                s.setTcpNoDelay(true);
                DataInputStream in = new DataInputStream(s.getInputStream());
                OutputStream out = s.getOutputStream();
                byte[] msg = new byte[SIZE];
                return latency("raw java.net.Socket ping-pong", () -> {
                    try {
                        long t0 = System.nanoTime();
                        out.write(msg);
                        in.readFully(msg);
                        return System.nanoTime() - t0;
                    } catch (IOException e) {
                        throw new java.io.UncheckedIOException(e);
                    }
                });
            }
        }
    }

    private Latency zmqReqRep() throws Exception {
        try (PeerProcess peer = bench("bench-zmq-rep", "zmq-rep"); ZContext ctx = new ZContext()) {
            int port = Integer.parseInt(peer.expect("PORT", PeerProcess.COMMAND).substring(5));
            ZMQ.Socket req = ctx.createSocket(SocketType.REQ);
            req.connect("tcp://127.0.0.1:" + port);
            byte[] msg = new byte[SIZE];
            return latency("JeroMQ REQ/REP", () -> {
                long t0 = System.nanoTime();
                req.send(msg);
                req.recv();
                return System.nanoTime() - t0;
            });
        }
    }

    private Latency mwReqRep(String scheme, String bind) throws Exception {
        return mwReqRep(scheme, bind, MessagingSettings.defaults().replySpin());
    }

    private Latency mwReqRep(String scheme, String bind, Duration spin) throws Exception {
        try (PeerProcess peer = bench("bench-mw-echo-" + scheme, "mw-echo", bind);
             MessagingNode node = MessagingNode.builder("bench-client").settings(MessagingSettings.defaults().withReplySpin(spin)).build()) {
            String host = peer.expect("BOUND", PeerProcess.COMMAND).substring(6);
            if (scheme.equals("multicast")) {
                host = bind;
            }
            String target = host;
            byte[] msg = new byte[SIZE];
            Duration timeout = Duration.ofSeconds(10);
            String name = "RoboMW " + scheme + " sendMessage + waitForReply" + (spin.isZero() ? " (no spin)" : "");
            return latency(name, () -> {
                long t0 = System.nanoTime();
                UUID id = node.sendMessage("bench-echo", target, null, "bench", msg, "ping");
                node.waitForReply(id, timeout);
                return System.nanoTime() - t0;
            });
        }
    }

    private Latency latency(String name, LongSupplier roundTrip) {
        for (int i = 0; i < LATENCY_WARMUP; i++) {
            roundTrip.getAsLong();
        }
        long[] t = new long[LATENCY_MEASURED];
        for (int i = 0; i < t.length; i++) {
            t[i] = roundTrip.getAsLong();
        }
        Arrays.sort(t);
        double mean = Arrays.stream(t).average().orElse(0) / 1000;
        Latency l = new Latency(name, t[t.length / 2] / 1000.0, t[(int) (t.length * 0.99)] / 1000.0, mean);
        say(String.format(Locale.ROOT, "%-48s p50 %8.1f µs  p99 %8.1f µs  mean %8.1f µs", name, l.p50(), l.p99(), l.mean()));
        return l;
    }

    // ---- publish/subscribe ----

    private Throughput zmqPubSub(long measured) throws Exception {
        try (PeerProcess pub = bench("bench-zmq-pub", "zmq-pub", String.valueOf(PUBSUB_WARMUP + measured))) {
            String endpoint = "tcp://127.0.0.1:" + pub.expect("PORT", PeerProcess.COMMAND).substring(5);
            try (PeerProcess sub = bench("bench-zmq-sub", "zmq-sub", endpoint, String.valueOf(PUBSUB_WARMUP), String.valueOf(measured))) {
                return pubSub("JeroMQ PUB/SUB", pub, sub, measured);
            }
        }
    }

    private Throughput mwPubSub(String scheme, String bind, long measured) throws Exception {
        try (PeerProcess pub = bench("bench-mw-pub-" + scheme, "mw-pub", bind, String.valueOf(PUBSUB_WARMUP + measured))) {
            String address = pub.expect("BOUND", PeerProcess.COMMAND).substring(6);
            try (PeerProcess sub = bench("bench-mw-sub-" + scheme, "mw-sub", address, String.valueOf(PUBSUB_WARMUP), String.valueOf(measured))) {
                return pubSub("RoboMW " + scheme + " publishMessage", pub, sub, measured);
            }
        }
    }

    /**
     * The slow-joiner handshake (the publisher says hello every millisecond until the subscriber
     * got one), then the run; both sides in fresh JVMs, so no case inherits another's heap, JIT
     * or threads.
     */
    private Throughput pubSub(String name, PeerProcess pub, PeerProcess sub, long measured) {
        sub.expect("SYNC", PeerProcess.COMMAND);
        pub.ask("GO", "GOING");
        String subscriberCpu = sub.expect("CPU", Duration.ofMinutes(5));
        String[] r = sub.expect("RESULT", Duration.ofMinutes(5)).split(" ");
        String publisherCpu = pub.expect("CPU", Duration.ofMinutes(5));
        say("    publisher " + publisherCpu + "; subscriber " + subscriberCpu);
        long count = Long.parseLong(r[1]);
        long nanos = Long.parseLong(r[2]);
        Throughput t = new Throughput(name, count, measured, nanos == 0 ? 0 : count * 1e9 / nanos);
        say(String.format(Locale.ROOT, "%-48s %,12.0f msg/s  (%,d of %,d measured messages received)", name, t.perSecond(), count, measured));
        return t;
    }


    // ---- set-up and report ----

    private static String group() throws IOException {
        String loopback = NetworkInterface.getByInetAddress(InetAddress.getLoopbackAddress()).getName();
        try (DatagramSocket s = new DatagramSocket(new InetSocketAddress(InetAddress.getLoopbackAddress(), 0))) {
            return "multicast://239.255.99." + (1 + new java.util.Random().nextInt(254)) + ":" + s.getLocalPort() + "?interface=" + loopback + "&ttl=0";
        }
    }

    private static PeerProcess bench(String name, String... args) throws IOException {
        List<String> jvm = new ArrayList<>(List.of("-Xmx1g", "-Dorg.slf4j.simpleLogger.defaultLogLevel=warn"));
        String extra = System.getProperty("bench.peerJvmArgs." + args[0], "");
        if (!extra.isBlank()) {
            jvm.addAll(Arrays.asList(extra.trim().split("\\s+")));
        }
        return PeerProcess.start(name, BenchPeer.class.getName(), jvm, List.of(args));
    }

    private void say(String line) {
        System.out.println(line);
        log.add(line);
    }

    private static <T> double baseline(List<T> results, String name, java.util.function.ToDoubleFunction<T> value) {
        return results.stream().filter(r -> r.toString().contains("name=" + name + ",")).mapToDouble(value).findFirst().orElse(Double.NaN);
    }

    private void write(List<Latency> latencies, List<Throughput> throughputs) throws IOException {
        // ratios to the baselines when they ran (-Dbench.cases may leave them out: NaN then)
        double raw = baseline(latencies, "raw java.net.Socket ping-pong", Latency::p50);
        double zmqLatency = baseline(latencies, "JeroMQ REQ/REP", Latency::p50);
        double zmq = baseline(throughputs, "JeroMQ PUB/SUB", Throughput::perSecond);
        StringBuilder md = new StringBuilder();
        md.append("| request/reply, 64 bytes | p50 µs | p99 µs | mean µs | p50 / raw socket | p50 / JeroMQ |\n|---|---:|---:|---:|---:|---:|\n");
        for (Latency l : latencies) {
            md.append(String.format(Locale.ROOT, "| %s | %.1f | %.1f | %.1f | %.2f× | %.2f× |%n", l.name(), l.p50(), l.p99(), l.mean(), l.p50() / raw, l.p50() / zmqLatency));
        }
        md.append("\n| publish/subscribe, 64 bytes (median of " + rounds() + " runs) | msg/s | received / sent (measured) | × JeroMQ |\n|---|---:|---:|---:|\n");
        for (Throughput t : throughputs) {
            md.append(String.format(Locale.ROOT, "| %s | %,.0f | %,d / %,d | %.2f× |%n", t.name(), t.perSecond(), t.messages(), t.sent(), t.perSecond() / zmq));
        }
        Path out = Path.of("target", "benchmarks", "messaging.md");
        Files.createDirectories(out.getParent());
        Files.writeString(out, md.toString());
        System.out.println();
        System.out.println(md);
        System.out.println("written to " + out.toAbsolutePath());
    }
}
