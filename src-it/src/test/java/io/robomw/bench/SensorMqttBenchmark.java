package io.robomw.bench;

import com.hivemq.client.mqtt.MqttClient;
import com.hivemq.client.mqtt.MqttGlobalPublishFilter;
import com.hivemq.client.mqtt.datatypes.MqttQos;
import com.hivemq.client.mqtt.mqtt5.Mqtt5AsyncClient;
import com.hivemq.client.mqtt.mqtt5.message.publish.Mqtt5Publish;
import io.robomw.agents.messaging.MessagingNode;
import io.robomw.agents.messaging.mqtt.BrokerCredentials;
import io.robomw.it.mqtt.Broker;

import java.util.ArrayList;
import java.util.List;
import java.util.Locale;
import java.util.Random;
import java.util.UUID;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.Semaphore;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicLong;

/**
 * Sensor-sized messages through an MQTT 5 broker (issue 36): RoboMW ({@code mqtt://}) against the
 * bare HiveMQ MQTT client through the same broker (in a process of its own on loopback), QoS 1,
 * one publisher and K subscribers in this JVM. Each sample sets up both (a publisher and K
 * subscribers each), warms both (bare, then RoboMW), then measures both twice, in the order bare,
 * RoboMW, RoboMW, bare (so that a drift over the sample weighs on both alike), each side's figure
 * the same payloads over its two windows' time: MB/s
 * (10^6 bytes) of payload all K subscribers received, from the first measured publication to the
 * last delivery. Arguments: {@code BROKER SIZE K WARMUP MEASURED} (BROKER embedded or mosquitto).
 * Prints {@code BENCH sensor.mqtt-BROKER.bare|robomw.SIZE.Ksub}, and on the line before them each
 * side's processor time per MB ({@link Sample}).
 *
 * <p>Like with like (since 2026-11-28; before, the bare callback only counted arrivals and never
 * read a payload, and the bare client was measured in a fresh JVM before RoboMW had warmed
 * anything, RoboMW in a JVM the bare run had warmed):
 * <ul>
 * <li>each subscriber, bare or RoboMW, takes every payload as a {@code byte[]} of its own and
 *     checks its length, as {@link SensorPeer}'s subscribers do (JeroMQ's {@code recv}, the plain
 *     sockets' {@code readFully}): a RoboMW listener is handed that array, the bare client's
 *     callback asks for it ({@code getPayloadAsBytes()}, the client's way to an array);</li>
 * <li>both are warmed before either is measured;</li>
 * <li>both publishers have at most the broker's receive maximum unacknowledged (Mosquitto: 20);
 *     beyond it the bare publisher waits when {@value #IN_FLIGHT_DEFAULT} wait in its client, RoboMW
 *     when its {@code max-in-flight} (64 by default) do (until 2026-11-29: when its {@code max-queued}, 10,000,
 *     or {@code max-queued-bytes}, 64 MiB, did: hundreds of 100 KB payloads piled up in its client, at a fifth of
 *     its throughput).</li>
 * <li>RoboMW's publications here carry no password, so their payloads travel apart from their
 *     frames (docs/messaging.md): a subscriber node is handed the client's array, the bare callback
 *     copies it ({@code getPayloadAsBytes()}, the only way to an array its public API has).</li>
 * </ul>
 */
public final class SensorMqttBenchmark {

    /** The bare publisher's bound on publications not yet acknowledged, unless {@code -Dsensor.mqtt.inFlight} says otherwise. */
    static final int IN_FLIGHT_DEFAULT = 64;
    /** Bare client's publications not yet acknowledged at once, in its client and at the broker (RoboMW's own queue bounds its own). */
    static final int IN_FLIGHT = Integer.getInteger("sensor.mqtt.inFlight", IN_FLIGHT_DEFAULT);
    static final long WAIT_SECONDS = 180;

    private SensorMqttBenchmark() {
    }

    /**
     * @param args BROKER SIZE K WARMUP MEASURED
     * @throws Exception on failure
     */
    public static void main(String[] args) throws Exception {
        Broker.Kind kind = Broker.Kind.valueOf(args[0].toUpperCase(Locale.ROOT));
        int size = Integer.parseInt(args[1]);
        int k = Integer.parseInt(args[2]);
        int warmup = Integer.parseInt(args[3]);
        int measured = Integer.parseInt(args[4]);
        String id = "sensor.mqtt-" + args[0].toLowerCase(Locale.ROOT) + ".";
        String tail = "." + SensorBenchmark.sizeId(size) + "." + k + "sub";
        byte[] payload = new byte[size];
        new Random(7).nextBytes(payload);
        try (Broker broker = Broker.start(kind, "sensor-" + args[0].toLowerCase(Locale.ROOT));
             Side bare = new Bare(broker.address(), k, size);
             Side robo = new RoboMw(broker.address(), k, size)) {
            bare.run(payload, warmup, "bare warm-up");
            robo.run(payload, warmup, "RoboMW warm-up");
            // bare, RoboMW, RoboMW, bare: whatever drifts over the sample (the broker's memory, the
            // collector's state, the machine) weighs on both alike
            Sample b1 = bare.run(payload, measured, "bare");
            Sample r1 = robo.run(payload, measured, "RoboMW");
            Sample r2 = robo.run(payload, measured, "RoboMW");
            Sample b2 = bare.run(payload, measured, "bare");
            Sample b = b1.and(b2);
            Sample r = r1.and(r2);
            System.out.printf(Locale.ROOT, "MQTT %s, %d bytes to %d subscriber(s): bare HiveMQ client %.0f MB/s (%.2f ms of this JVM's processor"
                    + " time per MB), RoboMW %.0f MB/s (%.2f ms per MB)%n", kind, size, k, b.megabytesPerSecond(), b.cpuMillisPerMegabyte(),
                    r.megabytesPerSecond(), r.cpuMillisPerMegabyte());
            System.out.println(BenchReport.line(id + "bare" + tail, b.megabytesPerSecond(), "MB/s"));
            System.out.println(BenchReport.line(id + "robomw" + tail, r.megabytesPerSecond(), "MB/s"));
        }
        System.exit(0);
    }

    /**
     * One side's figures over its measured window.
     *
     * @param megabytesPerSecond   payload delivered to all subscribers together, 10^6 bytes a second
     * @param cpuMillisPerMegabyte this JVM's processor time (every thread: clients, collector, compiler; not the broker's)
     *                             per 10^6 bytes delivered: the client's cost, which a loaded machine changes less than the rate
     */
    record Sample(double megabytesPerSecond, double cpuMillisPerMegabyte) {

        /** @return the two windows, of the same payloads, as one: their rates' harmonic mean (the same bytes over both windows' time) */
        Sample and(Sample other) {
            return new Sample(2 / (1 / megabytesPerSecond + 1 / other.megabytesPerSecond), (cpuMillisPerMegabyte + other.cpuMillisPerMegabyte) / 2);
        }
    }

    /** One system under test: a publisher and K subscribers, connected and subscribed; each delivery calls {@link #delivered}. */
    private abstract static class Side implements AutoCloseable {

        private final int k;
        private final int size;
        private final AtomicLong last = new AtomicLong();
        private volatile CountDownLatch phase = new CountDownLatch(0);

        Side(int k, int size) {
            this.k = k;
            this.size = size;
        }

        /** Publishes the payload n times. */
        abstract void publish(byte[] payload, int n) throws Exception;

        /** A subscriber's check of what it got: the whole payload (a wrong one fails the sample: its phase then waits in vain). */
        final void delivered(byte[] got) {
            if (got.length != size) {
                throw new IllegalStateException("a subscriber got " + got.length + " bytes, expected " + size);
            }
            last.set(System.nanoTime());
            phase.countDown();
        }

        /** Publishes n times and waits until each of the K subscribers has all n. */
        final Sample run(byte[] payload, int n, String what) throws Exception {
            CountDownLatch p = new CountDownLatch(k * n);
            phase = p;
            long cpu0 = processCpuNanos();
            long t0 = System.nanoTime();
            publish(payload, n);
            if (!p.await(WAIT_SECONDS, TimeUnit.SECONDS)) {
                throw new AssertionError(what + ": " + p.getCount() + " deliveries missing after " + WAIT_SECONDS + " s");
            }
            double megabytes = (double) k * n * size / 1e6;
            return new Sample(megabytes / ((last.get() - t0) / 1e9), (processCpuNanos() - cpu0) / 1e6 / megabytes);
        }
    }

    private static long processCpuNanos() {
        return ((com.sun.management.OperatingSystemMXBean) java.lang.management.ManagementFactory.getOperatingSystemMXBean()).getProcessCpuTime();
    }

    /** The bare HiveMQ client: one client publishing, K clients subscribed (QoS 1). */
    private static final class Bare extends Side {

        private final List<Mqtt5AsyncClient> clients = new ArrayList<>();
        private final Mqtt5AsyncClient pub;
        private final String topic = "sensor/" + UUID.randomUUID();
        private final Semaphore inFlight = new Semaphore(IN_FLIGHT);

        Bare(String address, int k, int size) throws Exception {
            super(k, size);
            int port = Integer.parseInt(address.substring(address.lastIndexOf(':') + 1));
            pub = client("sensor-pub-" + UUID.randomUUID(), port);
            for (int i = 0; i < k; i++) {
                Mqtt5AsyncClient sub = client("sensor-sub-" + i + "-" + UUID.randomUUID(), port);
                sub.publishes(MqttGlobalPublishFilter.SUBSCRIBED, p -> delivered(p.getPayloadAsBytes()));
                sub.subscribeWith().topicFilter(topic).qos(MqttQos.AT_LEAST_ONCE).send().get(10, TimeUnit.SECONDS);
            }
        }

        private Mqtt5AsyncClient client(String id, int port) throws Exception {
            var b = MqttClient.builder().useMqttVersion5().identifier(id).serverHost("127.0.0.1").serverPort(port);
            // mw broker lets in only its user: the bare client gives the credentials it generated for this machine, as RoboMW does
            BrokerCredentials user = BrokerCredentials.load(null, System.getenv(), "127.0.0.1");
            if (user.username() != null) {
                b = b.simpleAuth().username(user.username()).password(user.password()).applySimpleAuth();
            }
            Mqtt5AsyncClient c = b.buildAsync();
            clients.add(c);
            c.connectWith().cleanStart(true).send().get(10, TimeUnit.SECONDS);
            return c;
        }

        @Override
        void publish(byte[] payload, int n) throws InterruptedException {
            for (int i = 0; i < n; i++) {
                inFlight.acquire();
                pub.publish(Mqtt5Publish.builder().topic(topic).qos(MqttQos.AT_LEAST_ONCE).payload(payload).build())
                        .whenComplete((r, e) -> inFlight.release());
            }
        }

        @Override
        public void close() throws Exception {
            for (Mqtt5AsyncClient c : clients) {
                c.disconnect().get(5, TimeUnit.SECONDS);
            }
        }
    }

    /** RoboMW: one node publishing, K nodes subscribed, each its own session at the broker. */
    private static final class RoboMw extends Side {

        private final List<MessagingNode> nodes = new ArrayList<>();
        private final MessagingNode pub;
        private final String topic = "scan-" + UUID.randomUUID();

        RoboMw(String address, int k, int size) {
            super(k, size);
            pub = node("sensor-pub", address);
            for (int i = 0; i < k; i++) {
                MessagingNode sub = node("sensor-sub-" + i, address);
                sub.addMessageListener(topic, null, m -> delivered((byte[]) m.payload()));
                sub.subscribeMessage(topic, null);
            }
        }

        private MessagingNode node(String name, String address) {
            MessagingNode n = MessagingNode.builder(name).settings(SensorPeer.SETTINGS).bind(address).build();
            nodes.add(n);
            return n;
        }

        @Override
        void publish(byte[] payload, int n) {
            for (int i = 0; i < n; i++) {
                pub.publishMessage(topic, payload, "data", null);
            }
        }

        @Override
        public void close() {
            for (MessagingNode n : nodes) {
                n.close();
            }
        }
    }
}
