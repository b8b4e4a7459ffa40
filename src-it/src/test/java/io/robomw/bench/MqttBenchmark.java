package io.robomw.bench;

import com.hivemq.client.mqtt.MqttClient;
import com.hivemq.client.mqtt.MqttGlobalPublishFilter;
import com.hivemq.client.mqtt.datatypes.MqttQos;
import com.hivemq.client.mqtt.mqtt5.Mqtt5AsyncClient;
import com.hivemq.client.mqtt.mqtt5.message.publish.Mqtt5Publish;
import io.robomw.agents.messaging.MessagingNode;
import io.robomw.agents.messaging.mqtt.BrokerCredentials;
import io.robomw.it.mqtt.Broker;

import java.nio.ByteBuffer;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.Arrays;
import java.util.List;
import java.util.Locale;
import java.util.UUID;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.ConcurrentHashMap;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.Semaphore;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicLong;

/**
 * RoboMW through an MQTT 5 broker against the bare HiveMQ MQTT client through the same broker,
 * in the same run: 64-byte request/reply latency (QoS 1, MQTT 5 response topic and correlation
 * data) and 64-byte publish/subscribe throughput (QoS 1), over the embedded broker
 * ({@code mw broker}) and over Mosquitto, each broker in its own process on loopback, both
 * clients of a case in this JVM. Each case runs {@code -Dbench.rounds} times (default 5),
 * alternating bare and RoboMW; the report gives median, min and max, and RoboMW's overhead as the
 * ratio of the medians. Writes {@code target/benchmarks/mqtt.md}.
 *
 * <p>Run: {@code bench/mqtt} (see docs/benchmarks.md). Not part of the normal test run.
 */
public final class MqttBenchmark {

    static final int SIZE = 64;
    static final int RR_WARMUP = 2_000;
    static final int RR_MEASURED = 5_000;
    static final int PS_MESSAGES = 50_000;
    static final int PS_IN_FLIGHT = 10_000;
    static final Duration WAIT = Duration.ofSeconds(120);

    private final StringBuilder report = new StringBuilder();

    /**
     * @param args ignored
     * @throws Exception on failure
     */
    public static void main(String[] args) throws Exception {
        new MqttBenchmark().run();
    }

    void run() throws Exception {
        int rounds = Integer.getInteger("bench.rounds", 5);
        report.append("# MQTT messaging benchmark\n\n")
                .append(String.format(Locale.ROOT, "%s, %s %s, %d processors; %d rounds per case; 64-byte payloads, QoS 1.%n%n",
                        java.time.Instant.now(), System.getProperty("java.vm.name"), System.getProperty("java.version"),
                        Runtime.getRuntime().availableProcessors(), rounds))
                .append("| broker | case | bare HiveMQ client: median (min-max) | RoboMW: median (min-max) | RoboMW's overhead |\n")
                .append("|---|---|---|---|---|\n");
        for (Broker.Kind kind : kinds()) {
            try (Broker broker = Broker.start(kind, "bench-" + kind.name().toLowerCase(Locale.ROOT))) {
                double[][] rr = new double[2][rounds];
                double[][] ps = new double[2][rounds];
                for (int r = 0; r < rounds; r++) {
                    rr[0][r] = bareRequestReply(broker.address());
                    rr[1][r] = roboRequestReply(broker.address());
                    ps[0][r] = barePubSub(broker.address());
                    ps[1][r] = roboPubSub(broker.address());
                    System.out.printf(Locale.ROOT, "%s round %d: rr p50 bare %.0f us, robomw %.0f us; pub/sub bare %.0f msg/s, robomw %.0f msg/s%n",
                            kind, r + 1, rr[0][r], rr[1][r], ps[0][r], ps[1][r]);
                    String id = "mqtt." + kind.name().toLowerCase(Locale.ROOT);
                    System.out.println(BenchReport.line(id + ".rr-bare", rr[0][r], "µs"));
                    System.out.println(BenchReport.line(id + ".rr-robomw", rr[1][r], "µs"));
                    System.out.println(BenchReport.line(id + ".ps-bare", ps[0][r], "msg/s"));
                    System.out.println(BenchReport.line(id + ".ps-robomw", ps[1][r], "msg/s"));
                }
                row(kind, "request/reply p50 latency (us)", rr, false);
                row(kind, "publish/subscribe (messages/s)", ps, true);
            }
        }
        Path out = Path.of("target", "benchmarks", "mqtt.md");
        Files.createDirectories(out.getParent());
        Files.writeString(out, report.toString());
        System.out.println(report);
    }

    private static List<Broker.Kind> kinds() {
        String only = System.getProperty("bench.brokers", "");
        if (only.isBlank()) {
            return List.of(Broker.Kind.EMBEDDED, Broker.Kind.MOSQUITTO);
        }
        return Arrays.stream(only.split(",")).map(s -> Broker.Kind.valueOf(s.trim().toUpperCase(Locale.ROOT))).toList();
    }

    private void row(Broker.Kind kind, String what, double[][] v, boolean higherIsBetter) {
        double bare = median(v[0]);
        double robo = median(v[1]);
        // Overhead as a factor above 1 when RoboMW is slower: its latency over the bare client's, or the bare client's throughput over its.
        double ratio = higherIsBetter ? bare / robo : robo / bare;
        report.append(String.format(Locale.ROOT, "| %s | %s | %.0f (%.0f-%.0f) | %.0f (%.0f-%.0f) | %.2fx |%n", kind.name().toLowerCase(Locale.ROOT),
                what, bare, min(v[0]), max(v[0]), robo, min(v[1]), max(v[1]), ratio));
    }

    // ---- request/reply ----

    /** @return the median round trip in microseconds, bare client */
    static double bareRequestReply(String address) throws Exception {
        int port = Integer.parseInt(address.substring(address.lastIndexOf(':') + 1));
        Mqtt5AsyncClient responder = client("bench-responder-" + UUID.randomUUID(), port);
        Mqtt5AsyncClient requester = client("bench-requester-" + UUID.randomUUID(), port);
        try {
            responder.publishes(MqttGlobalPublishFilter.SUBSCRIBED, p -> responder.publishWith()
                    .topic(p.getResponseTopic().orElseThrow()).correlationData(p.getCorrelationData().orElseThrow())
                    .qos(MqttQos.AT_LEAST_ONCE).payload(p.getPayloadAsBytes()).send());
            responder.subscribeWith().topicFilter("bench/req").qos(MqttQos.AT_LEAST_ONCE).send().get(10, TimeUnit.SECONDS);
            ConcurrentHashMap<ByteBuffer, CompletableFuture<byte[]>> waiting = new ConcurrentHashMap<>();
            String replies = "bench/reply/" + UUID.randomUUID();
            requester.publishes(MqttGlobalPublishFilter.SUBSCRIBED, p -> {
                CompletableFuture<byte[]> f = waiting.remove(p.getCorrelationData().orElseThrow());
                if (f != null) {
                    f.complete(p.getPayloadAsBytes());
                }
            });
            requester.subscribeWith().topicFilter(replies).qos(MqttQos.AT_LEAST_ONCE).send().get(10, TimeUnit.SECONDS);
            byte[] payload = new byte[SIZE];
            long[] rtt = new long[RR_MEASURED];
            for (int i = 0; i < RR_WARMUP + RR_MEASURED; i++) {
                ByteBuffer corr = ByteBuffer.allocate(8).putLong(0, i);
                CompletableFuture<byte[]> f = new CompletableFuture<>();
                waiting.put(corr, f);
                long t0 = System.nanoTime();
                requester.publishWith().topic("bench/req").qos(MqttQos.AT_LEAST_ONCE).responseTopic(replies).correlationData(corr).payload(payload).send();
                f.get(WAIT.toSeconds(), TimeUnit.SECONDS);
                if (i >= RR_WARMUP) {
                    rtt[i - RR_WARMUP] = System.nanoTime() - t0;
                }
            }
            return p50(rtt);
        } finally {
            requester.disconnect().get(5, TimeUnit.SECONDS);
            responder.disconnect().get(5, TimeUnit.SECONDS);
        }
    }

    /** @return the median round trip in microseconds, RoboMW ({@code sendMessage} then {@code waitForReply}) */
    static double roboRequestReply(String address) throws Exception {
        try (MessagingNode server = MessagingNode.builder("bench-server").bind(address).build();
             MessagingNode client = MessagingNode.builder("bench-client").bind(address).build()) {
            server.addMessageListener("echo", null, m -> server.replyMessage(m, m.payload(), "echo"));
            byte[] payload = new byte[SIZE];
            long[] rtt = new long[RR_MEASURED];
            for (int i = 0; i < RR_WARMUP + RR_MEASURED; i++) {
                long t0 = System.nanoTime();
                UUID id = client.sendMessage("bench-server", address, null, "echo", payload, "ask");
                client.waitForReply(id, WAIT);
                if (i >= RR_WARMUP) {
                    rtt[i - RR_WARMUP] = System.nanoTime() - t0;
                }
            }
            return p50(rtt);
        }
    }

    // ---- publish/subscribe ----

    /** @return messages per second from the first publication to the last one received, bare client */
    static double barePubSub(String address) throws Exception {
        int port = Integer.parseInt(address.substring(address.lastIndexOf(':') + 1));
        Mqtt5AsyncClient sub = client("bench-sub-" + UUID.randomUUID(), port);
        Mqtt5AsyncClient pub = client("bench-pub-" + UUID.randomUUID(), port);
        try {
            CountDownLatch all = new CountDownLatch(PS_MESSAGES);
            AtomicLong last = new AtomicLong();
            sub.publishes(MqttGlobalPublishFilter.SUBSCRIBED, p -> {
                all.countDown();
                last.set(System.nanoTime());
            });
            String topic = "bench/ps/" + UUID.randomUUID();
            sub.subscribeWith().topicFilter(topic).qos(MqttQos.AT_LEAST_ONCE).send().get(10, TimeUnit.SECONDS);
            Semaphore inFlight = new Semaphore(PS_IN_FLIGHT);
            byte[] payload = new byte[SIZE];
            long t0 = System.nanoTime();
            for (int i = 0; i < PS_MESSAGES; i++) {
                inFlight.acquire();
                pub.publish(Mqtt5Publish.builder().topic(topic).qos(MqttQos.AT_LEAST_ONCE).payload(payload).build())
                        .whenComplete((r, e) -> inFlight.release());
            }
            if (!all.await(WAIT.toSeconds(), TimeUnit.SECONDS)) {
                throw new AssertionError("bare pub/sub: " + all.getCount() + " of " + PS_MESSAGES + " not received");
            }
            return PS_MESSAGES / ((last.get() - t0) / 1e9);
        } finally {
            pub.disconnect().get(5, TimeUnit.SECONDS);
            sub.disconnect().get(5, TimeUnit.SECONDS);
        }
    }

    /** @return messages per second from the first publication to the last one received, RoboMW */
    static double roboPubSub(String address) throws Exception {
        try (MessagingNode sub = MessagingNode.builder("bench-sub").bind(address).build();
             MessagingNode pub = MessagingNode.builder("bench-pub").bind(address).build()) {
            CountDownLatch all = new CountDownLatch(PS_MESSAGES);
            AtomicLong last = new AtomicLong();
            String topic = "ps-" + UUID.randomUUID();
            sub.addMessageListener(topic, null, m -> {
                all.countDown();
                last.set(System.nanoTime());
            });
            sub.subscribeMessage(topic, null);
            byte[] payload = new byte[SIZE];
            long t0 = System.nanoTime();
            for (int i = 0; i < PS_MESSAGES; i++) {
                pub.publishMessage(topic, payload, "data", null);
            }
            if (!all.await(WAIT.toSeconds(), TimeUnit.SECONDS)) {
                throw new AssertionError("RoboMW pub/sub: " + all.getCount() + " of " + PS_MESSAGES + " not received");
            }
            return PS_MESSAGES / ((last.get() - t0) / 1e9);
        }
    }

    private static Mqtt5AsyncClient client(String id, int port) throws Exception {
        var b = MqttClient.builder().useMqttVersion5().identifier(id).serverHost("127.0.0.1").serverPort(port);
        // mw broker lets in only its user (NOT_AUTHORIZED otherwise): the bare client gives the credentials
        // it generated for this machine, as RoboMW's transport does; Mosquitto ignores them
        BrokerCredentials user = BrokerCredentials.load(null, System.getenv(), "127.0.0.1");
        if (user.username() != null) {
            b = b.simpleAuth().username(user.username()).password(user.password()).applySimpleAuth();
        }
        Mqtt5AsyncClient c = b.buildAsync();
        c.connectWith().cleanStart(true).send().get(10, TimeUnit.SECONDS);
        return c;
    }

    private static double p50(long[] nanos) {
        long[] s = nanos.clone();
        Arrays.sort(s);
        return s[s.length / 2] / 1000.0;
    }

    private static double median(double[] v) {
        double[] s = v.clone();
        Arrays.sort(s);
        return s.length % 2 == 1 ? s[s.length / 2] : (s[s.length / 2 - 1] + s[s.length / 2]) / 2;
    }

    private static double min(double[] v) {
        return Arrays.stream(v).min().orElse(Double.NaN);
    }

    private static double max(double[] v) {
        return Arrays.stream(v).max().orElse(Double.NaN);
    }

}
