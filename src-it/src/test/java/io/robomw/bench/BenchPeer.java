package io.robomw.bench;

import io.robomw.agents.messaging.MessagingNode;
import org.zeromq.SocketType;
import org.zeromq.ZContext;
import org.zeromq.ZMQ;

import java.io.DataInputStream;
import java.io.OutputStream;
import java.io.PrintStream;
import java.net.InetAddress;
import java.net.ServerSocket;
import java.net.Socket;
import java.nio.charset.StandardCharsets;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicLong;
import java.util.concurrent.locks.LockSupport;

/**
 * One side of a benchmark, in a JVM of its own: an echo server (raw socket, JeroMQ REP, RoboMW),
 * a publisher (JeroMQ PUB, RoboMW) or a subscriber that times the data messages (JeroMQ SUB,
 * RoboMW). Prints {@code PORT}, {@code BOUND}, {@code SYNC}, {@code GOING}, {@code CPU} and
 * {@code RESULT} lines on stdout; takes {@code GO} on stdin; ends when stdin closes.
 *
 * <p>Pub/sub protocol: the publisher sends hello messages (first byte 'H') every millisecond until
 * the driver says {@code GO} (once the subscriber has printed {@code SYNC}), then
 * {@code warmup + measured} data messages (first byte 'D') back to back. The subscriber reports
 * how many data messages it got and the nanoseconds from the last warm-up message to the last
 * one. Both print the CPU time of their busy threads.
 */
public final class BenchPeer {

    private BenchPeer() {
    }

    /**
     * @param args mode and its arguments
     * @throws Exception on failure
     */
    public static void main(String[] args) throws Exception {
        PrintStream out = new PrintStream(System.out, true, StandardCharsets.UTF_8);
        CountDownLatch go = new CountDownLatch(1);
        Thread watcher = new Thread(() -> {
            try {
                java.io.BufferedReader commands = new java.io.BufferedReader(new java.io.InputStreamReader(System.in, StandardCharsets.UTF_8));
                for (String line; (line = commands.readLine()) != null; ) {
                    if (line.equals("GO")) {
                        go.countDown();
                    }
                }
            } catch (java.io.IOException ignored) {
                // driver gone
            }
            System.exit(0);
        }, "bench-stdin");
        watcher.setDaemon(true);
        watcher.start();
        switch (args[0]) {
            case "raw-echo" -> rawEcho(out);
            case "zmq-rep" -> zmqRep(out);
            case "zmq-pub" -> zmqPub(out, go, Long.parseLong(args[1]));
            case "mw-pub" -> mwPub(out, go, args[1], Long.parseLong(args[2]));
            case "zmq-sub" -> zmqSub(out, args[1], Long.parseLong(args[2]), Long.parseLong(args[3]));
            case "mw-echo" -> mwEcho(out, args[1]);
            case "mw-sub" -> mwSub(out, args[1], Long.parseLong(args[2]), Long.parseLong(args[3]));
            default -> throw new IllegalArgumentException("unknown mode " + args[0]);
        }
        watcher.join();
    }

    private static void rawEcho(PrintStream out) throws Exception {
        try (ServerSocket server = new ServerSocket(0, 1, InetAddress.getLoopbackAddress())) {
            out.println("PORT " + server.getLocalPort());
            try (Socket s = server.accept()) {
                s.setTcpNoDelay(true);
                DataInputStream in = new DataInputStream(s.getInputStream());
                OutputStream o = s.getOutputStream();
                byte[] buf = new byte[64];
                while (true) {
                    in.readFully(buf);
                    o.write(buf);
                }
            } catch (java.io.EOFException e) {
                // driver done
            }
        }
    }

    private static void zmqRep(PrintStream out) {
        try (ZContext ctx = new ZContext()) {
            ZMQ.Socket rep = ctx.createSocket(SocketType.REP);
            int port = rep.bindToRandomPort("tcp://127.0.0.1");
            out.println("PORT " + port);
            while (!Thread.currentThread().isInterrupted()) {
                byte[] m = rep.recv();
                if (m == null) {
                    break;
                }
                rep.send(m);
            }
        }
    }

    private static void zmqPub(PrintStream out, CountDownLatch go, long messages) throws InterruptedException {
        try (ZContext ctx = new ZContext()) {
            ZMQ.Socket pub = ctx.createSocket(SocketType.PUB);
            pub.setSndHWM(0);
            out.println("PORT " + pub.bindToRandomPort("tcp://127.0.0.1"));
            publish(out, go, messages, pub::send);
        }
    }

    private static void mwPub(PrintStream out, CountDownLatch go, String bind, long messages) throws InterruptedException {
        try (MessagingNode node = MessagingNode.builder("bench-pub").bind(bind).build()) {
            out.println("BOUND " + (bind.startsWith("multicast:") ? bind : node.boundAddresses().get(0)));
            publish(out, go, messages, data -> node.publishMessage("bench", data, data[0] == 'H' ? "hello" : "data", null));
        }
    }

    /** Hello every millisecond until GO, then {@code messages} data messages back to back; CPU, then waits for the end. */
    private static void publish(PrintStream out, CountDownLatch go, long messages, java.util.function.Consumer<byte[]> send) throws InterruptedException {
        byte[] hello = new byte[MessagingBenchmark.SIZE];
        hello[0] = 'H';
        do {
            send.accept(hello);
        } while (!go.await(1, TimeUnit.MILLISECONDS));
        out.println("GOING");
        ThreadCpu cpu = ThreadCpu.now();
        byte[] data = new byte[MessagingBenchmark.SIZE];
        data[0] = 'D';
        for (long i = 0; i < messages; i++) {
            send.accept(data);
        }
        out.println("CPU " + cpu.since());
        new CountDownLatch(1).await();
    }

    private static void zmqSub(PrintStream out, String endpoint, long warmup, long measured) {
        try (ZContext ctx = new ZContext()) {
            ZMQ.Socket sub = ctx.createSocket(SocketType.SUB);
            sub.setRcvHWM(0);
            sub.connect(endpoint);
            sub.subscribe(new byte[0]);
            out.println("READY");
            Timer timer = new Timer(warmup, measured);
            ThreadCpu cpu = ThreadCpu.now();
            boolean synced = false;
            while (!timer.done()) {
                byte[] m = sub.recv();
                if (m[0] == 'H') {
                    if (!synced) {
                        synced = true;
                        out.println("SYNC");
                    }
                } else {
                    timer.tick();
                }
            }
            out.println("CPU " + cpu.since());
            out.println(timer.result());
        }
    }

    private static void mwEcho(PrintStream out, String address) {
        MessagingNode node = MessagingNode.builder("bench-echo").bind(address).build();
        node.addMessageListener("bench", null, m -> node.replyMessage(m, m.payload(), "echo"));
        out.println("BOUND " + node.boundAddresses().get(0));
    }

    private static void mwSub(PrintStream out, String address, long warmup, long measured) {
        boolean group = address.startsWith("multicast:");
        MessagingNode.Builder b = MessagingNode.builder("bench-sub");
        if (group) {
            b.bind(address);
        } else {
            b.connect(address);
        }
        MessagingNode node = b.build();
        Timer timer = new Timer(warmup, measured);
        AtomicLong hello = new AtomicLong();
        node.addMessageListener("bench", null, m -> {
            byte[] p = (byte[]) m.payload();
            if (p[0] == 'H') {
                if (hello.getAndIncrement() == 0) {
                    out.println("SYNC");
                }
            } else {
                timer.tick();
            }
        });
        node.subscribeMessage("bench", null);
        ThreadCpu cpu = ThreadCpu.now();
        out.println("READY");
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
    }

    /** Counts data messages and times the measured ones (the last warm-up message to the last one). */
    private static final class Timer {
        private final long warmup;
        private final long total;
        private volatile long count;
        private long start;
        private volatile long last;

        Timer(long warmup, long measured) {
            this.warmup = warmup;
            this.total = warmup + measured;
        }

        void tick() {
            long n = count + 1;
            long now = System.nanoTime();
            if (n == warmup) {
                start = now;
            }
            last = now;
            count = n;
        }

        long count() {
            return count;
        }

        boolean done() {
            return count >= total;
        }

        String result() {
            long measuredCount = Math.max(0, count - warmup);
            return "RESULT " + measuredCount + " " + (measuredCount == 0 ? 0 : last - start);
        }
    }
}
