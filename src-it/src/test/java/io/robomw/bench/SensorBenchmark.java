package io.robomw.bench;

import io.robomw.it.messaging.PeerProcess;

import java.io.IOException;
import java.time.Duration;
import java.util.ArrayList;
import java.util.Arrays;
import java.util.List;
import java.util.Locale;

/**
 * Sensor-sized messages (issue 36): publish/subscribe of large payloads (a laser scan of 100 KB,
 * a camera frame of 1 MiB) from one publisher JVM to K subscribers in a second JVM, both
 * {@link SensorPeer}s on 127.0.0.1, in MB/s (10^6 bytes) delivered: the payload bytes all K
 * subscribers received over the measured window. One sample of one system per run:
 * {@code SYSTEM SIZE K WARMUP MEASURED}, SYSTEM one of {@code tcp} (RoboMW: large publications through
 * shared memory, the default), {@code tcp-noshm} (RoboMW with shared memory off), {@code zmq}
 * (JeroMQ PUB/SUB, the baseline) or {@code raw} (plain sockets, the ceiling: one thread writes
 * each payload to each connection). Prints {@code BENCH sensor.SYSTEM.SIZE.Ksub value MB/s}.
 */
public final class SensorBenchmark {

    private SensorBenchmark() {
    }

    /**
     * @param args SYSTEM SIZE K WARMUP MEASURED (warm-up and measured payloads per subscriber)
     * @throws Exception on failure
     */
    public static void main(String[] args) throws Exception {
        String system = args[0];
        int size = Integer.parseInt(args[1]);
        int k = Integer.parseInt(args[2]);
        long warmup = Long.parseLong(args[3]);
        long measured = Long.parseLong(args[4]);
        String id = "sensor." + system + "." + sizeId(size) + "." + k + "sub";
        try (PeerProcess pub = peer("sensor-pub-" + system, "pub", system, String.valueOf(size), String.valueOf(k), String.valueOf(warmup + measured))) {
            String address = pub.expect("BOUND", PeerProcess.COMMAND).substring(6);
            try (PeerProcess sub = peer("sensor-sub-" + system, "sub", system, String.valueOf(size), String.valueOf(k), String.valueOf(warmup),
                    String.valueOf(measured), address)) {
                sub.expect("SYNC", Duration.ofSeconds(60));
                pub.ask("GO", "GOING");
                String subscriberCpu = sub.expect("CPU", Duration.ofMinutes(5));
                String[] r = sub.expect("RESULT", Duration.ofMinutes(5)).split(" ");
                String publisherCpu = pub.expect("CPU", Duration.ofMinutes(5));
                long count = Long.parseLong(r[1]);
                long nanos = Long.parseLong(r[2]);
                double mbs = nanos == 0 ? 0 : count * (double) size / 1e6 / (nanos / 1e9);
                System.out.printf(Locale.ROOT, "%s: %d of %d measured payloads of %d bytes to %d subscriber(s) in %.2f s: %.0f MB/s%n", id, count, k * measured,
                        size, k, nanos / 1e9, mbs);
                System.out.println("    publisher " + publisherCpu + "; subscribers " + subscriberCpu);
                System.out.println(BenchReport.line(id, mbs, "MB/s"));
                System.out.println(BenchReport.line(id + ".delivered", 100.0 * count / (k * measured), "%"));
            }
        }
        System.exit(0);
    }

    /** @return 100KB or 1MiB: a payload as the BENCH lines name it */
    static String sizeId(int bytes) {
        return bytes % (1 << 20) == 0 ? bytes / (1 << 20) + "MiB" : bytes % 1000 == 0 ? bytes / 1000 + "KB" : bytes + "B";
    }

    private static PeerProcess peer(String name, String... args) throws IOException {
        List<String> jvm = new ArrayList<>(List.of("-Xmx2g", "-Dorg.slf4j.simpleLogger.defaultLogLevel=warn"));
        String extra = System.getProperty("sensor.peerJvmArgs", "").trim();
        if (!extra.isEmpty()) {
            jvm.addAll(Arrays.asList(extra.split("\\s+")));
        }
        return PeerProcess.start(name, SensorPeer.class.getName(), jvm, List.of(args));
    }
}
