package io.robomw.it.messaging;

import io.robomw.agents.messaging.frame.Frame;
import io.robomw.agents.messaging.frame.FrameCodec;
import io.robomw.agents.messaging.frame.FrameKind;
import io.robomw.agents.messaging.io.FrameStreamReader;
import io.robomw.testkit.Await;
import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.Test;

import java.io.BufferedOutputStream;
import java.io.IOException;
import java.io.InputStream;
import java.io.OutputStream;
import java.net.InetAddress;
import java.net.Socket;
import java.net.SocketException;
import java.nio.ByteBuffer;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.nio.file.StandardOpenOption;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.Locale;
import java.util.UUID;
import java.util.concurrent.ExecutorService;
import java.util.concurrent.Executors;
import java.util.concurrent.Future;
import java.util.regex.Matcher;
import java.util.regex.Pattern;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * A messaging node in its own JVM under the attacks that found its leaks (issue 15): what any TCP
 * peer can make it hold, measured as the heap kept after full collections, its live threads and
 * its resident set, before, during and after. Each figure is also written to
 * {@code target/it-logs/node-under-attack.txt}.
 */
class NodeUnderAttackIT {

    private static final int MIB = 1 << 20;
    private static final Duration WAIT = Duration.ofSeconds(60);
    private static final Pattern RESOURCES = Pattern.compile("RESOURCES heap=(\\d+) threads=(\\d+) rss=(-?\\d+)");

    private final List<AutoCloseable> open = new ArrayList<>();

    /** What the node's JVM holds. */
    record Resources(long heap, int threads, long rss) {
        static Resources of(PeerProcess p) {
            Matcher m = RESOURCES.matcher(p.ask("resources", "RESOURCES"));
            assertTrue(m.matches());
            return new Resources(Long.parseLong(m.group(1)), Integer.parseInt(m.group(2)), Long.parseLong(m.group(3)));
        }

        String minus(Resources base) {
            return String.format(Locale.ROOT, "heap %+.1f MB, threads %+d, RSS %+.1f MB (heap %.1f MB, %d threads, RSS %.1f MB)",
                    (heap - base.heap) / 1e6, threads - base.threads, (rss - base.rss) / 1e6, heap / 1e6, threads, rss / 1e6);
        }
    }

    @AfterEach
    void closeAll() throws Exception {
        for (int i = open.size() - 1; i >= 0; i--) {
            open.get(i).close();
        }
    }

    private PeerProcess node(String name, String... jvmArgs) {
        try {
            PeerProcess p = PeerProcess.peer(name, List.of(jvmArgs));
            open.add(p);
            return p;
        } catch (IOException e) {
            throw new AssertionError("cannot start " + name, e);
        }
    }

    private static int bind(PeerProcess p) {
        String bound = p.ask("bind tcp://127.0.0.1:0", "BOUND").substring("BOUND ".length());
        return Integer.parseInt(bound.substring(bound.lastIndexOf(':') + 1));
    }

    private static long dropped(PeerProcess p, String reason) {
        Matcher m = Pattern.compile(" " + reason + "=(\\d+)").matcher(p.ask("stats", "STATS"));
        assertTrue(m.find(), "no " + reason + " in the stats");
        return Long.parseLong(m.group(1));
    }

    private static void record(String test, String figures) throws IOException {
        String line = test + ": " + figures + System.lineSeparator();
        System.out.print(line);
        Path file = Path.of("target", "it-logs", "node-under-attack.txt");
        Files.createDirectories(file.getParent());
        Files.writeString(file, line, StandardOpenOption.CREATE, StandardOpenOption.APPEND);
    }

    private static byte[] subscribe(String topic) {
        Frame f = new Frame(FrameKind.SUBSCRIBE, 0, 99, 1, new UUID(99, 1), System.currentTimeMillis() * 1000, "attacker", "", topic, "",
                0, new byte[0], false);
        return FrameCodec.encode(f, false);
    }

    private static String topic(int i, int bytes) {
        String n = "t" + i + "-";
        return n + "x".repeat(bytes - n.length());
    }

    private static Frame readFrame(InputStream in) throws Exception {
        FrameStreamReader r = new FrameStreamReader(in, MIB);
        int length = r.next();
        return length < 0 ? null : FrameCodec.decode(r.buffer(), r.offset(), length, MIB);
    }

    /** Reads until the node closes the connection (a reset counts). */
    private static void awaitClosedByNode(Socket s) throws IOException {
        s.setSoTimeout((int) WAIT.toMillis());
        byte[] buf = new byte[512];
        try {
            while (s.getInputStream().read(buf) >= 0) {
                // keep-alives
            }
        } catch (SocketException reset) {
            // closed too
        }
    }

    @Test
    void aPeerSubscribingToThousandsOfTopicsIsBoundedAndLeavesNothingBehind() throws IOException {
        PeerProcess node = node("attack-subscriptions");
        int port = bind(node);
        Resources base = Resources.of(node);
        Resources during;
        try (Socket s = new Socket(InetAddress.getLoopbackAddress(), port)) {
            OutputStream out = new BufferedOutputStream(s.getOutputStream(), 1 << 16);
            // the attack: 20,000 distinct topics of 10 KB (above the 1 KiB topic limit)
            for (int i = 0; i < 20_000; i++) {
                out.write(subscribe(topic(i, 10_000)));
            }
            // and 20,000 distinct topics just under the limit: the per-peer maximum (1,024) holds
            for (int i = 0; i < 20_000; i++) {
                out.write(subscribe(topic(i, 1000)));
            }
            out.flush();
            Await.until("every subscription above the limits refused", WAIT, () -> dropped(node, "LIMIT") == 20_000 + 20_000 - 1024);
            during = Resources.of(node);
        }
        Await.until("the peer's subscriptions released", WAIT, () -> Resources.of(node).heap() - base.heap() < 4_000_000,
                () -> Resources.of(node).minus(base));
        Resources after = Resources.of(node);
        record("40,000 subscriptions from one connection", "during " + during.minus(base) + "; after it closed " + after.minus(base));
        assertTrue(during.heap() - base.heap() < 16_000_000, "held while open: " + during.minus(base));
    }

    @Test
    void connectionsOpenedAndDroppedInBatchesLeaveNothingBehind() throws Exception {
        PeerProcess node = node("attack-churn");
        int port = bind(node);
        Resources base = Resources.of(node);
        List<Resources> rounds = new ArrayList<>();
        ExecutorService peers = Executors.newFixedThreadPool(8);
        try {
            for (int round = 0; round < 3; round++) {
                List<Future<?>> batch = new ArrayList<>();
                for (int w = 0; w < 8; w++) {
                    batch.add(peers.submit(() -> {
                        for (int i = 0; i < 250; i++) {
                            try (Socket s = new Socket(InetAddress.getLoopbackAddress(), port)) {
                                // the keep-alive it hears first: the node has started this connection's threads
                                assertEquals(FrameKind.KEEPALIVE, readFrame(s.getInputStream()).kind());
                            }
                        }
                        return null;
                    }));
                }
                for (Future<?> f : batch) {
                    f.get();
                }
                Await.until("the node's connection threads ended", WAIT, () -> Resources.of(node).threads() <= base.threads() + 2,
                        () -> Resources.of(node).minus(base));
                rounds.add(Resources.of(node));
            }
        } finally {
            peers.shutdownNow();
        }
        StringBuilder figures = new StringBuilder();
        for (int i = 0; i < rounds.size(); i++) {
            figures.append(i == 0 ? "" : "; ").append("after round ").append(i + 1).append(": ").append(rounds.get(i).minus(base));
        }
        record("3 × 2,000 connections opened and dropped", figures.toString());
        Resources last = rounds.get(rounds.size() - 1);
        assertTrue(last.heap() - base.heap() < 4_000_000, "kept after 6,000 connections: " + last.minus(base));
        assertTrue(last.heap() - rounds.get(0).heap() < 2_000_000, "grew from round to round: " + figures);
    }

    @Test
    void peersAnnouncingLargeFramesAreBoundedByTheConnectionLimitAndTimedOut() throws Exception {
        PeerProcess node = node("attack-headers", "-Dpeer.maxConnections=100", "-Dpeer.firstFrameMillis=6000", "-Dpeer.idleMillis=6000");
        int port = bind(node);
        Resources base = Resources.of(node);
        byte[] header = ByteBuffer.allocate(FrameCodec.PREFIX_LENGTH).putShort((short) FrameCodec.MAGIC).put((byte) FrameCodec.VERSION)
                .put((byte) FrameKind.PUBLISH.code()).putInt(MIB).array();
        List<Socket> accepted = new ArrayList<>();
        int refused = 0;
        long start = System.nanoTime();
        for (int i = 0; i < 300; i++) {
            Socket s = new Socket(InetAddress.getLoopbackAddress(), port);
            open.add(s);
            s.getOutputStream().write(header);
            s.setSoTimeout((int) WAIT.toMillis());
            Frame first = readFrame(s.getInputStream());
            if (first.kind() == FrameKind.KEEPALIVE) {
                accepted.add(s);
            } else {
                assertEquals(FrameKind.ERROR, first.kind());
                String why = new String(first.payload(), StandardCharsets.UTF_8);
                assertTrue(why.contains("serves at most 100 connections (maxConnections)"), why);
                refused++;
            }
        }
        Resources during = Resources.of(node);
        boolean measuredInTime = System.nanoTime() - start < Duration.ofMillis(5500).toNanos();
        for (Socket s : accepted) {
            awaitClosedByNode(s);
        }
        Await.until("the node's connection threads ended", WAIT, () -> Resources.of(node).threads() <= base.threads() + 2,
                () -> Resources.of(node).minus(base));
        Resources after = Resources.of(node);
        record("300 peers announcing 1 MiB frames (limit 100 connections, timeouts 6 s)", accepted.size() + " accepted, " + refused
                + " refused; while held " + during.minus(base) + "; after the timeouts " + after.minus(base));
        if (measuredInTime) {
            assertEquals(100, accepted.size(), "accepted beyond the limit");
            assertEquals(200, refused);
        }
        assertTrue(during.heap() - base.heap() < 16_000_000, "heap while held: " + during.minus(base));
        assertTrue(during.rss() - base.rss() < 96_000_000, "RSS while held: " + during.minus(base));
        assertTrue(during.threads() - base.threads() <= 2 * 100 + 4, "threads while held: " + during.minus(base));
        assertTrue(dropped(node, "TIMED_OUT") >= accepted.size(), "each held connection timed out");
        try (Socket again = new Socket(InetAddress.getLoopbackAddress(), port)) {
            again.setSoTimeout((int) WAIT.toMillis());
            assertEquals(FrameKind.KEEPALIVE, readFrame(again.getInputStream()).kind(), "the node serves again once they are gone");
        }
    }
}
