package io.robomw.bench;

import io.robomw.agents.messaging.MessagingNode;
import io.robomw.agents.messaging.MessagingSettings;
import org.zeromq.SocketType;
import org.zeromq.ZContext;
import org.zeromq.ZMQ;

import java.io.DataInputStream;
import java.io.DataOutputStream;
import java.io.IOException;
import java.io.PrintStream;
import java.net.InetAddress;
import java.net.ServerSocket;
import java.net.Socket;
import java.nio.charset.StandardCharsets;
import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicInteger;
import java.util.concurrent.atomic.AtomicLong;
import java.util.concurrent.locks.LockSupport;
import java.util.function.Consumer;

/**
 * One side of {@link SensorBenchmark}, in a JVM of its own: a publisher of large payloads, or K
 * subscribers, over RoboMW tcp ({@code tcp}: large publications through shared memory, the default;
 * {@code tcp-noshm}: with shared memory off, every byte on the connections), JeroMQ PUB/SUB ({@code zmq}) or plain sockets
 * ({@code raw}: the publisher writes each payload, length first, to each subscriber's connection
 * in turn; the ceiling of a publisher thread's fan-out on this machine).
 *
 * <ul>
 *   <li>{@code pub SYSTEM SIZE K COUNT}: binds on 127.0.0.1, prints {@code BOUND address}; sends a
 *   hello (first byte 'H') every millisecond until {@code GO}, then COUNT payloads of SIZE bytes
 *   (first byte 'D') back to back; prints {@code CPU ...}.</li>
 *   <li>{@code sub SYSTEM SIZE K WARMUP MEASURED ADDRESS}: K subscribers; {@code SYNC} once each has
 *   had a hello; counts data payloads across all K, and times from the moment the K × WARMUP-th
 *   arrived to the last one (at K × (WARMUP + MEASURED), or 2 s after the last if some never come:
 *   JeroMQ drops above its high-water mark); prints {@code CPU ...} and {@code RESULT messages nanos}.</li>
 * </ul>
 * Ends when stdin closes or says {@code exit} (the driver's close): through {@code System.exit}, so a
 * shared-memory segment's file is removed as the JVM ends rather than left for the next one.
 */
public final class SensorPeer {

    /** Frames up to 2 MiB: the default 1 MiB leaves no room for a 1 MiB payload's header. */
    static final MessagingSettings SETTINGS = MessagingSettings.defaults().withMaxFrameSize(2 << 20);
    /** The same with shared memory off: every payload on the subscribers' TCP connections. */
    static final MessagingSettings SETTINGS_NO_SHM = SETTINGS.withSharedMemory(false);
    /** JeroMQ's high-water mark: none (0), as in the 64-byte case: a PUB socket drops what is above it, so a bounded one would measure the drops. */
    static final int ZMQ_HWM = 0;

    private SensorPeer() {
    }

    /**
     * @param args see the class comment
     * @throws Exception on failure
     */
    public static void main(String[] args) throws Exception {
        PrintStream out = new PrintStream(System.out, true, StandardCharsets.UTF_8);
        CountDownLatch go = new CountDownLatch(1);
        Thread watcher = new Thread(() -> {
            try {
                java.io.BufferedReader commands = new java.io.BufferedReader(new java.io.InputStreamReader(System.in, StandardCharsets.UTF_8));
                for (String line; (line = commands.readLine()) != null && !line.equals("exit"); ) {
                    if (line.equals("GO")) {
                        go.countDown();
                    }
                }
            } catch (IOException ignored) {
                // driver gone
            }
            System.exit(0);
        }, "sensor-stdin");
        watcher.setDaemon(true);
        watcher.start();
        String system = args[1];
        int size = Integer.parseInt(args[2]);
        int k = Integer.parseInt(args[3]);
        if (args[0].equals("pub")) {
            long count = Long.parseLong(args[4]);
            switch (system) {
                case "zmq" -> zmqPub(out, go, size, count);
                case "tcp" -> mwPub(out, go, size, count, SETTINGS);
                case "tcp-noshm" -> mwPub(out, go, size, count, SETTINGS_NO_SHM);
                case "raw" -> rawPub(out, go, size, k, count);
                default -> throw new IllegalArgumentException("unknown system " + system);
            }
        } else {
            sub(out, system, size, k, Long.parseLong(args[4]), Long.parseLong(args[5]), args[6]);
        }
        watcher.join();
    }

    // ---- publishers ----

    private static void zmqPub(PrintStream out, CountDownLatch go, int size, long count) throws InterruptedException {
        try (ZContext ctx = new ZContext()) {
            ZMQ.Socket pub = ctx.createSocket(SocketType.PUB);
            pub.setSndHWM(ZMQ_HWM);
            out.println("BOUND tcp://127.0.0.1:" + pub.bindToRandomPort("tcp://127.0.0.1"));
            publish(out, go, size, count, pub::send);
        }
    }

    private static void mwPub(PrintStream out, CountDownLatch go, int size, long count, MessagingSettings settings) throws InterruptedException {
        try (MessagingNode node = MessagingNode.builder("sensor-pub").settings(settings).bind("tcp://127.0.0.1:0").build()) {
            out.println("BOUND " + node.boundAddresses().get(0));
            publish(out, go, size, count, data -> node.publishMessage("scan", data, "data", null));
        }
    }

    private static void rawPub(PrintStream out, CountDownLatch go, int size, int k, long count) throws Exception {
        try (ServerSocket server = new ServerSocket(0, k, InetAddress.getLoopbackAddress())) {
            out.println("BOUND " + server.getLocalPort());
            server.setSoTimeout(60_000);
            List<DataOutputStream> subs = new ArrayList<>();
            List<Socket> sockets = new ArrayList<>();
            for (int i = 0; i < k; i++) {
                Socket s = server.accept();
                sockets.add(s);
                subs.add(new DataOutputStream(s.getOutputStream()));
            }
            publish(out, go, size, count, data -> {
                try {
                    for (DataOutputStream o : subs) {
                        o.writeInt(data.length);
                        o.write(data);
                    }
                } catch (IOException e) {
                    throw new java.io.UncheckedIOException(e);
                }
            });
            for (Socket s : sockets) {
                s.close();
            }
        }
    }

    /** A hello every millisecond until GO, then {@code count} payloads back to back; CPU; then waits for the end. */
    private static void publish(PrintStream out, CountDownLatch go, int size, long count, Consumer<byte[]> send) throws InterruptedException {
        byte[] hello = new byte[size];
        hello[0] = 'H';
        do {
            send.accept(hello);
        } while (!go.await(1, TimeUnit.MILLISECONDS));
        out.println("GOING");
        ThreadCpu cpu = ThreadCpu.now();
        byte[] data = new byte[size];
        new java.util.Random(7).nextBytes(data);
        data[0] = 'D';
        for (long i = 0; i < count; i++) {
            send.accept(data);
        }
        out.println("CPU " + cpu.since());
        new CountDownLatch(1).await();
    }

    // ---- subscribers ----

    private static void sub(PrintStream out, String system, int size, int k, long warmup, long measured, String address) throws Exception {
        Timer timer = new Timer((long) k * warmup, (long) k * measured);
        AtomicInteger synced = new AtomicInteger();
        boolean[] hello = new boolean[k];
        List<AutoCloseable> open = new ArrayList<>();
        for (int i = 0; i < k; i++) {
            int me = i;
            Consumer<byte[]> onMessage = p -> {
                if (p[0] == 'H') {
                    synchronized (hello) {
                        if (!hello[me]) {
                            hello[me] = true;
                            if (synced.incrementAndGet() == k) {
                                out.println("SYNC");
                            }
                        }
                    }
                } else if (p.length != size) {
                    throw new IllegalStateException("subscriber " + me + " got " + p.length + " bytes, expected " + size);
                } else {
                    timer.tick();
                }
            };
            switch (system) {
                case "tcp", "tcp-noshm" -> {
                    MessagingNode node = MessagingNode.builder("sensor-sub-" + i).settings(system.equals("tcp") ? SETTINGS : SETTINGS_NO_SHM)
                            .connect(address).build();
                    node.addMessageListener("scan", null, m -> onMessage.accept((byte[]) m.payload()));
                    node.subscribeMessage("scan", null);
                    open.add(node);
                }
                case "zmq" -> {
                    ZContext ctx = new ZContext();
                    ZMQ.Socket sub = ctx.createSocket(SocketType.SUB);
                    sub.setRcvHWM(ZMQ_HWM);
                    sub.connect(address);
                    sub.subscribe(new byte[0]);
                    reader("sensor-zmq-sub-" + i, () -> {
                        while (true) {
                            byte[] m = sub.recv();
                            if (m == null) {
                                return;
                            }
                            onMessage.accept(m);
                        }
                    });
                    open.add(ctx);
                }
                case "raw" -> {
                    Socket s = new Socket(InetAddress.getLoopbackAddress(), Integer.parseInt(address));
                    DataInputStream in = new DataInputStream(new java.io.BufferedInputStream(s.getInputStream(), 1 << 16));
                    reader("sensor-raw-sub-" + i, () -> {
                        while (true) {
                            byte[] m = new byte[in.readInt()];
                            in.readFully(m);
                            onMessage.accept(m);
                        }
                    });
                    open.add(s);
                }
                default -> throw new IllegalArgumentException("unknown system " + system);
            }
        }
        ThreadCpu cpu = ThreadCpu.now();
        long idleSince = System.nanoTime();
        long lastCount = -1;
        while (!timer.done()) {
            LockSupport.parkNanos(1_000_000);
            long c = timer.count();
            if (c != lastCount) {
                lastCount = c;
                idleSince = System.nanoTime();
            } else if (c > 0 && System.nanoTime() - idleSince > 2_000_000_000L) {
                break;
            }
        }
        out.println("CPU " + cpu.since());
        out.println(timer.result());
        for (AutoCloseable c : open) {
            try {
                c.close();
            } catch (Exception ignored) {
                // ending anyway
            }
        }
    }

    /** A loop that may throw on a closed connection: its reader thread just ends. */
    @FunctionalInterface
    interface Loop {
        void run() throws Exception;
    }

    private static void reader(String name, Loop loop) {
        Thread t = new Thread(() -> {
            try {
                loop.run();
            } catch (Exception e) {
                // closed: done
            }
        }, name);
        t.setDaemon(true);
        t.start();
    }

    /** Counts data payloads of all subscribers and times the measured ones. */
    private static final class Timer {
        private final long warmup;
        private final long total;
        private final AtomicLong count = new AtomicLong();
        private volatile long start;
        private volatile long last;

        Timer(long warmup, long measured) {
            this.warmup = warmup;
            this.total = warmup + measured;
        }

        void tick() {
            long n = count.incrementAndGet();
            long now = System.nanoTime();
            if (n == warmup) {
                start = now;
            }
            if (n > warmup) {
                last = now;
            }
        }

        long count() {
            return count.get();
        }

        boolean done() {
            return count.get() >= total;
        }

        String result() {
            long measuredCount = Math.max(0, count.get() - warmup);
            return "RESULT " + measuredCount + " " + (measuredCount == 0 ? 0 : last - start);
        }
    }
}
