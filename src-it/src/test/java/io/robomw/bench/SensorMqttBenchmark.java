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
import java.util.UUID;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.Semaphore;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicLong;

/**
 * Sensor-sized messages through an MQTT 5 broker (issue 36): RoboMW ({@code mqtt://}) against the
 * bare HiveMQ MQTT client through the same broker (in a process of its own on loopback), QoS 1,
 * one publisher and K subscribers in this JVM. Each sample runs both, bare first, each after a
 * warm-up of its own: MB/s (10^6 bytes) of payload all K subscribers received, from the first
 * measured publication to the last delivery. Arguments: {@code BROKER SIZE K WARMUP MEASURED}
 * (BROKER embedded or mosquitto). Prints {@code BENCH sensor.mqtt-BROKER.bare|robomw.SIZE.Ksub}.
 */
public final class SensorMqttBenchmark {

    /** Bare client's publications in flight at once (RoboMW's own queue bounds its own). */
    static final int IN_FLIGHT = Integer.getInteger("sensor.mqtt.inFlight", 64);
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
        try (Broker broker = Broker.start(kind, "sensor-" + args[0].toLowerCase(Locale.ROOT))) {
            double bare = bare(broker.address(), size, k, warmup, measured);
            double robo = robomw(broker.address(), size, k, warmup, measured);
            System.out.printf(Locale.ROOT, "MQTT %s, %d bytes to %d subscriber(s): bare HiveMQ client %.0f MB/s, RoboMW %.0f MB/s%n", kind, size, k, bare, robo);
            System.out.println(BenchReport.line(id + "bare" + tail, bare, "MB/s"));
            System.out.println(BenchReport.line(id + "robomw" + tail, robo, "MB/s"));
        }
        System.exit(0);
    }

    private static double bare(String address, int size, int k, int warmup, int measured) throws Exception {
        int port = Integer.parseInt(address.substring(address.lastIndexOf(':') + 1));
        List<Mqtt5AsyncClient> subs = new ArrayList<>();
        Mqtt5AsyncClient pub = client("sensor-pub-" + UUID.randomUUID(), port);
        try {
            String topic = "sensor/" + UUID.randomUUID();
            CountDownLatch[] phase = {new CountDownLatch(k * warmup)};
            AtomicLong last = new AtomicLong();
            for (int i = 0; i < k; i++) {
                Mqtt5AsyncClient sub = client("sensor-sub-" + i + "-" + UUID.randomUUID(), port);
                subs.add(sub);
                sub.publishes(MqttGlobalPublishFilter.SUBSCRIBED, p -> {
                    last.set(System.nanoTime());
                    phase[0].countDown();
                });
                sub.subscribeWith().topicFilter(topic).qos(MqttQos.AT_LEAST_ONCE).send().get(10, TimeUnit.SECONDS);
            }
            byte[] payload = new byte[size];
            new java.util.Random(7).nextBytes(payload);
            Semaphore inFlight = new Semaphore(IN_FLIGHT);
            publishBare(pub, topic, payload, warmup, inFlight);
            await(phase[0], "bare warm-up");
            phase[0] = new CountDownLatch(k * measured);
            long t0 = System.nanoTime();
            publishBare(pub, topic, payload, measured, inFlight);
            await(phase[0], "bare");
            return (double) k * measured * size / 1e6 / ((last.get() - t0) / 1e9);
        } finally {
            pub.disconnect().get(5, TimeUnit.SECONDS);
            for (Mqtt5AsyncClient s : subs) {
                s.disconnect().get(5, TimeUnit.SECONDS);
            }
        }
    }

    private static void publishBare(Mqtt5AsyncClient pub, String topic, byte[] payload, int n, Semaphore inFlight) throws InterruptedException {
        for (int i = 0; i < n; i++) {
            inFlight.acquire();
            pub.publish(Mqtt5Publish.builder().topic(topic).qos(MqttQos.AT_LEAST_ONCE).payload(payload).build()).whenComplete((r, e) -> inFlight.release());
        }
    }

    private static double robomw(String address, int size, int k, int warmup, int measured) throws Exception {
        List<MessagingNode> subs = new ArrayList<>();
        try (MessagingNode pub = MessagingNode.builder("sensor-pub").settings(SensorPeer.SETTINGS).bind(address).build()) {
            String topic = "scan-" + UUID.randomUUID();
            CountDownLatch[] phase = {new CountDownLatch(k * warmup)};
            AtomicLong last = new AtomicLong();
            for (int i = 0; i < k; i++) {
                MessagingNode sub = MessagingNode.builder("sensor-sub-" + i).settings(SensorPeer.SETTINGS).bind(address).build();
                subs.add(sub);
                sub.addMessageListener(topic, null, m -> {
                    last.set(System.nanoTime());
                    phase[0].countDown();
                });
                sub.subscribeMessage(topic, null);
            }
            byte[] payload = new byte[size];
            new java.util.Random(7).nextBytes(payload);
            for (int i = 0; i < warmup; i++) {
                pub.publishMessage(topic, payload, "data", null);
            }
            await(phase[0], "RoboMW warm-up");
            phase[0] = new CountDownLatch(k * measured);
            long t0 = System.nanoTime();
            for (int i = 0; i < measured; i++) {
                pub.publishMessage(topic, payload, "data", null);
            }
            await(phase[0], "RoboMW");
            return (double) k * measured * size / 1e6 / ((last.get() - t0) / 1e9);
        } finally {
            for (MessagingNode s : subs) {
                s.close();
            }
        }
    }

    private static void await(CountDownLatch latch, String what) throws InterruptedException {
        if (!latch.await(WAIT_SECONDS, TimeUnit.SECONDS)) {
            throw new AssertionError(what + ": " + latch.getCount() + " deliveries missing after " + WAIT_SECONDS + " s");
        }
    }

    private static Mqtt5AsyncClient client(String id, int port) throws Exception {
        var b = MqttClient.builder().useMqttVersion5().identifier(id).serverHost("127.0.0.1").serverPort(port);
        // mw broker lets in only its user: the bare client gives the credentials it generated for this machine, as RoboMW does
        BrokerCredentials user = BrokerCredentials.load(null, System.getenv(), "127.0.0.1");
        if (user.username() != null) {
            b = b.simpleAuth().username(user.username()).password(user.password()).applySimpleAuth();
        }
        Mqtt5AsyncClient c = b.buildAsync();
        c.connectWith().cleanStart(true).send().get(10, TimeUnit.SECONDS);
        return c;
    }
}
