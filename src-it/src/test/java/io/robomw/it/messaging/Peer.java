package io.robomw.it.messaging;

import io.robomw.agents.messaging.DropReason;
import io.robomw.agents.messaging.MessagingNode;
import io.robomw.agents.messaging.MessagingSettings;
import io.robomw.agents.messaging.MessagingStats;
import io.robomw.agents.messaging.PeerLimits;
import io.robomw.agents.messaging.robot.RobotProtocol;
import io.robomw.agents.messaging.robot.RobotServer;
import io.robomw.agents.messaging.security.TlsSettings;
import io.robomw.api.Message;
import io.robomw.api.Robot;
import io.robomw.api.Robots;

import java.io.BufferedReader;
import java.io.InputStreamReader;
import java.io.PrintStream;
import java.nio.charset.StandardCharsets;
import java.nio.file.Path;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.Map;
import java.util.UUID;
import java.util.concurrent.ConcurrentHashMap;
import java.util.concurrent.CopyOnWriteArrayList;
import java.util.concurrent.locks.LockSupport;

/**
 * A messaging peer in its own JVM, driven by the integration tests through stdin: one command a
 * line, one answer a line on stdout ({@code OK}, {@code BOUND addr}, {@code COUNT ...},
 * {@code ERR why}). Arguments: {@code name [--tls keyStore trustStore password]}.
 */
public final class Peer {

    private final MessagingNode node;
    private final PrintStream out;
    private final Map<String, List<Object>> received = new ConcurrentHashMap<>();
    private final List<AutoCloseable> closeables = new ArrayList<>();

    private Peer(MessagingNode node, PrintStream out) {
        this.node = node;
        this.out = out;
    }

    /**
     * @param args name, then optional --tls keyStore trustStore password
     * @throws Exception on failure
     */
    public static void main(String[] args) throws Exception {
        PrintStream out = new PrintStream(System.out, true, StandardCharsets.UTF_8);
        MessagingSettings settings = RobotProtocol.forServer(MessagingSettings.defaults());
        settings = settings.withLimits(limitsFromProperties(settings.limits()));
        if (args.length >= 5 && args[1].equals("--tls")) {
            settings = settings.withTls(new TlsSettings(Path.of(args[2]), args[4], Path.of(args[3]), args[4]));
        }
        try (MessagingNode node = MessagingNode.builder(args[0]).settings(settings).build()) {
            Peer peer = new Peer(node, out);
            BufferedReader in = new BufferedReader(new InputStreamReader(System.in, StandardCharsets.UTF_8));
            out.println("READY");
            String line;
            while ((line = in.readLine()) != null) {
                if (line.equals("exit")) {
                    break;
                }
                try {
                    peer.run(line.trim().split(" "));
                } catch (RuntimeException e) {
                    out.println("ERR " + e.toString().replace('\n', ' '));
                }
            }
            for (AutoCloseable c : peer.closeables) {
                c.close();
            }
        }
        out.println("BYE");
    }

    /** {@code -Dpeer.maxConnections=N -Dpeer.firstFrameMillis=T -Dpeer.idleMillis=T}: the limits under test. */
    private static PeerLimits limitsFromProperties(PeerLimits limits) {
        PeerLimits l = limits;
        if (System.getProperty("peer.maxConnections") != null) {
            l = l.withMaxConnections(Integer.getInteger("peer.maxConnections"));
        }
        if (System.getProperty("peer.idleMillis") != null) {
            l = l.withTimeouts(Duration.ofMillis(Long.getLong("peer.firstFrameMillis", l.firstFrameTimeout().toMillis())),
                    Duration.ofMillis(Long.getLong("peer.idleMillis")));
        }
        return l;
    }

    /**
     * What this JVM holds, as the leak tests measure it: the heap used after full collections
     * (serial GC: {@code System.gc()} is a full collection), live threads, and the resident set.
     */
    static String resources() throws java.io.IOException {
        java.lang.management.MemoryMXBean memory = java.lang.management.ManagementFactory.getMemoryMXBean();
        long used = Long.MAX_VALUE;
        for (int i = 0; i < 3; i++) {
            System.gc();
            used = Math.min(used, memory.getHeapMemoryUsage().getUsed());
        }
        int threads = java.lang.management.ManagementFactory.getThreadMXBean().getThreadCount();
        long rssKb = -1;
        for (String line : java.nio.file.Files.readAllLines(Path.of("/proc/self/status"))) {
            if (line.startsWith("VmRSS:")) {
                rssKb = Long.parseLong(line.replaceAll("[^0-9]", ""));
            }
        }
        return "RESOURCES heap=" + used + " threads=" + threads + " rss=" + rssKb * 1024;
    }

    private static String pw(String s) {
        return s.equals("-") ? null : s;
    }

    private void run(String[] c) throws Exception {
        switch (c[0]) {
            case "bind" -> out.println("BOUND " + node.bind(c[1]));
            case "connect" -> {
                node.connect(c[1]);
                out.println("OK");
            }
            case "subscribe" -> {
                record(c[1], pw(c[2]));
                node.subscribeMessage(c[1], pw(c[2]));
                out.println("OK");
            }
            case "listen" -> {
                record(c[1], pw(c[2]));
                out.println("OK");
            }
            case "echo" -> {
                node.addMessageListener(c[1], pw(c[2]), m -> node.replyMessage(m, m.payload(), "echo"));
                out.println("OK");
            }
            case "await" -> {
                long deadline = System.nanoTime() + Duration.ofSeconds(Long.parseLong(c[3])).toNanos();
                int n = Integer.parseInt(c[2]);
                while (list(c[1]).size() < n && System.nanoTime() < deadline) {
                    LockSupport.parkNanos(1_000_000);
                }
                out.println(count(c[1]));
            }
            case "count" -> out.println(count(c[1]));
            case "distinct" -> {
                List<Object> l = list(c[1]);
                out.println("DISTINCT " + c[1] + " " + new java.util.HashSet<>(l).size() + " of " + l.size());
            }
            case "presence-host" -> {
                node.presence().host(c[1], c[2]);
                out.println("OK");
            }
            case "waitsubs" -> {
                long deadline = System.nanoTime() + Duration.ofSeconds(Long.parseLong(c[3])).toNanos();
                while (node.subscriberCount(c[1]) < Integer.parseInt(c[2]) && System.nanoTime() < deadline) {
                    LockSupport.parkNanos(1_000_000);
                }
                out.println("SUBS " + node.subscriberCount(c[1]));
            }
            case "publish" -> {
                int from = Integer.parseInt(c[2]);
                int n = Integer.parseInt(c[3]);
                for (int i = from; i < from + n; i++) {
                    node.publishMessage(c[1], i, "count", pw(c[4]));
                }
                out.println("PUBLISHED " + n);
            }
            case "request" -> {
                UUID id = node.sendMessage(c[2], c[1], pw(c[5]), c[3], c[4], "ask");
                try {
                    Message reply = node.waitForReply(id, Duration.ofSeconds(5));
                    out.println("REPLY " + reply.payload());
                } catch (RuntimeException e) {
                    out.println("FAILED " + e.getMessage().replace('\n', ' '));
                }
            }
            case "stats" -> out.println(stats(node.stats()));
            case "resources" -> out.println(resources());
            case "robot" -> {
                Robot robot = Robots.open(Path.of(c[1]));
                closeables.add(RobotServer.serveInsecure(node, robot));
                closeables.add(robot);
                out.println("SERVING " + robot.name());
            }
            case "sim" -> {
                io.robomw.sim.Simulation sim = io.robomw.sim.Simulation.load(Path.of(c[1]));
                closeables.add(sim);
                sim.startRealTime(Double.parseDouble(c[3]));
                Robot robot = sim.robot(c[2]);
                closeables.add(0, RobotServer.serveInsecure(node, robot));
                out.println("SERVING " + robot.name());
            }
            default -> out.println("ERR unknown command " + c[0]);
        }
    }

    private List<Object> list(String topic) {
        return received.computeIfAbsent(topic, t -> new CopyOnWriteArrayList<>());
    }

    private void record(String topic, String password) {
        List<Object> l = list(topic);
        node.addMessageListener(topic, password, m -> l.add(m.payload()));
    }

    private String count(String topic) {
        List<Object> l = list(topic);
        boolean ordered = true;
        for (int i = 0; i < l.size(); i++) {
            if (!(l.get(i) instanceof Integer v) || v != i) {
                ordered = false;
                break;
            }
        }
        return "COUNT " + topic + " " + l.size() + " ordered=" + ordered;
    }

    static String stats(MessagingStats s) {
        StringBuilder b = new StringBuilder("STATS");
        for (DropReason r : DropReason.values()) {
            b.append(' ').append(r).append('=').append(s.dropped(r));
        }
        return b.append(" lost=").append(s.framesLost()).append(" in=").append(s.framesIn()).toString();
    }
}
