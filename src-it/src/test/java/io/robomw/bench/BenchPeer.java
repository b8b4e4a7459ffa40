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
import java.util.concurrent.atomic.AtomicLong;
import java.util.concurrent.locks.LockSupport;

/**
 * The far side of each benchmark, in its own JVM: an echo server (raw socket, JeroMQ REP, RoboMW)
 * or a subscriber that times the data messages (JeroMQ SUB, RoboMW). Prints {@code PORT},
 * {@code BOUND}, {@code SYNC} and {@code RESULT} lines on stdout; ends when stdin closes.
 *
 * <p>Pub/sub protocol: the publisher sends hello messages (first byte 'H') until the subscriber
 * prints {@code SYNC}, then {@code warmup + measured} data messages (first byte 'D'). The
 * subscriber reports how many data messages it got and the nanoseconds from the last warm-up
 * message to the last one.
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
        Thread watcher = new Thread(() -> {
            try {
                while (System.in.read() >= 0) {
                    // wait for the driver to close stdin
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

    private static void zmqSub(PrintStream out, String endpoint, long warmup, long measured) {
        try (ZContext ctx = new ZContext()) {
            ZMQ.Socket sub = ctx.createSocket(SocketType.SUB);
            sub.setRcvHWM(0);
            sub.connect(endpoint);
            sub.subscribe(new byte[0]);
            out.println("READY");
            Timer timer = new Timer(warmup, measured);
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
