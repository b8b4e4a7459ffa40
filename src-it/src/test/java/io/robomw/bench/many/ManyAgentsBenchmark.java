package io.robomw.bench.many;

import io.robomw.bench.AgentBenchmark;
import io.robomw.it.messaging.PeerProcess;
import io.robomw.testkit.Await;

import java.io.IOException;
import java.io.OutputStream;
import java.net.InetAddress;
import java.net.ServerSocket;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.ArrayList;
import java.util.Comparator;
import java.util.List;
import java.util.Locale;
import java.util.jar.JarEntry;
import java.util.jar.JarOutputStream;
import java.util.stream.Stream;

/**
 * Many agents at once (issue 36): N agents (1,000 by default) hop concurrently among H hosts (4),
 * each host a JVM of its own on 127.0.0.1 ({@link ManyAgentsPeer}), RoboMW agent hosts or JADE
 * containers with agent mobility; this JVM only drives them. One sample of one system:
 *
 * <ol>
 *   <li>The home host (the first) starts N agents; each goes to a host picked at random among the
 *   others, and so on (0-byte payload: its state is the host list, a random state and its
 *   departure time). RoboMW's agent class is compiled here into a jar only the home host gets, so
 *   its code travels as an archive; JADE's agent is on every container's class path (JADE ships no code).</li>
 *   <li>After a warm-up of W s, every host records each hop's latency (from just before the agent
 *   leaves its last stop to the start of its work at this one: transfer, store, acknowledgement,
 *   scheduling) for S s: hops per second (every host's hops / S), p50 and p99, and the processor
 *   time of all H JVMs (user + system, from /proc) per hop. Each host counts the hops that end
 *   there between its own start and end of recording; hops per second is the sum over the hosts of
 *   each one's hops over its own window.</li>
 *   <li>Then every agent is told to go home: each must end its trip at home within 2 minutes
 *   (lost = N − home; RoboMW's sample fails if one is lost, JADE's reports it). Latencies of 10 s
 *   and more fall in the histogram's last bucket: a p99 of 10,020,000 µs means "10 s or more".</li>
 *   <li>Parked agents, first, on the fresh JVMs: N / 20 agents (at least 10) sent to the second host
 *   to wait there (RoboMW: the stop's work blocks on a latch; JADE: a cyclic behaviour blocked for a
 *   message) load the classes and open the sessions; then the second host's live heap after two
 *   full collections, N more agents, the live heap again: the difference / the agents that arrived
 *   (RoboMW's sample fails if one does not arrive; JADE, which loses one on the way in some runs,
 *   reports them as {@code park-lost}, see {@link #park}). Then RoboMW's are let
 *   go (their trips end there); JADE's stay, idle, through the hop phase (killing them one by one
 *   took minutes on a loaded machine; an idle JADE agent takes no processor time).</li>
 *   <li>Paced, after the saturated window and before the agents go home (unless {@code --paced 0}):
 *   every agent waits at each stop so that the offered load is a share (50 % by default) of the
 *   saturated rate just measured, as wrk2 does to avoid coordinated omission: at saturation the
 *   hop latency is mostly the queue's (Little's law: N agents / the rate). Hops per second, p50 and
 *   p99 again, over S s after a settling time (see {@link #paced}).</li>
 * </ol>
 *
 * <p>Prints {@code BENCH many.<system>.<figure>} lines for bench/all's report ({@code paced.*}
 * for the paced phase). Arguments:
 * {@code --system robomw|jade --agents N --hosts H --warmup W --seconds S --paced SHARE}.
 */
public final class ManyAgentsBenchmark {

    private static final Duration START = Duration.ofSeconds(90);
    private static final Duration HOME = Duration.ofMinutes(2);
    /** How long JADE's parking may make no progress before its missing agents count as lost (see {@link #park}). */
    private static final Duration PARK_STALL = Duration.ofSeconds(15);
    /** The most of JADE's parking agents that may be lost before its sample fails instead. */
    private static final int PARK_LOSS_ALLOWED = 5;

    /** The agent; compiled at run time so that only the home host has its class. */
    static final String AGENT_SOURCE = """
            package io.robomw.benchagent;

            import io.robomw.api.Agent;
            import io.robomw.api.AgentContext;
            import io.robomw.api.Itinerary;
            import java.util.concurrent.CountDownLatch;
            import java.util.concurrent.TimeUnit;
            import java.util.concurrent.atomic.AtomicInteger;
            import java.util.concurrent.atomic.AtomicLong;
            import java.util.function.LongPredicate;

            /** Hops at random among its hosts while its host's log says so, then goes home; or (park) waits at its one host. */
            public class HopAgent extends Agent {
                private static final long serialVersionUID = 1L;
                private final String[] hosts;
                private final boolean park;
                private long seed;
                private long departed;

                public HopAgent(String[] hosts, long seed, boolean park) {
                    this.hosts = hosts;
                    this.seed = seed | 1;
                    this.park = park;
                }

                @Override
                public void run() {
                    long now = System.nanoTime();
                    AgentContext c = context();
                    Itinerary it = itinerary();
                    it.clear();
                    if (park) {
                        ((AtomicInteger) System.getProperties().get("%s")).incrementAndGet();
                        try {
                            ((CountDownLatch) System.getProperties().get("%s")).await(10, TimeUnit.MINUTES);
                        } catch (InterruptedException e) {
                            Thread.currentThread().interrupt();
                        }
                        c.setResult("parked");
                        return;
                    }
                    String here = c.hostAddress();
                    if (((LongPredicate) System.getProperties().get("%s")).test(departed == 0 ? -1 : now - departed)) {
                        long mean = ((AtomicLong) System.getProperties().get("%s")).get();
                        if (mean > 0) {
                            // paced: waits at this stop (on its runner thread) before it leaves
                            try {
                                TimeUnit.NANOSECONDS.sleep(mean / 2 + Math.floorMod(seed >>> 1, mean));
                            } catch (InterruptedException e) {
                                Thread.currentThread().interrupt();
                            }
                        }
                        String next;
                        do {
                            seed ^= seed << 13;
                            seed ^= seed >>> 7;
                            seed ^= seed << 17;
                            next = hosts[(int) Math.floorMod(seed, (long) hosts.length)];
                        } while (next.equals(here));
                        it.addStop(next);
                        departed = System.nanoTime();
                    } else if (!here.equals(c.homeAddress())) {
                        departed = 0;
                        it.addStop(c.homeAddress());
                    } else {
                        c.setResult("home");
                    }
                }
            }
            """.formatted(HopLog.PARKED, HopLog.GATE, HopLog.HOP, HopLog.PACE);

    private final String system;
    private final int agents;
    private final int hosts;
    private final int warmup;
    private final int seconds;
    private final double share;
    private final Path work;
    private final List<PeerProcess> peers = new ArrayList<>();
    private final List<String> names = new ArrayList<>();

    private ManyAgentsBenchmark(String system, int agents, int hosts, int warmup, int seconds, double share, Path work) {
        this.share = share;
        this.system = system;
        this.agents = agents;
        this.hosts = hosts;
        this.warmup = warmup;
        this.seconds = seconds;
        this.work = work;
    }

    /**
     * @param args see the class comment
     * @throws Exception on failure
     */
    public static void main(String[] args) throws Exception {
        String system = "robomw";
        int agents = 1000;
        int hosts = 4;
        int warmup = 10;
        int seconds = 30;
        double share = 0.5;
        for (int i = 0; i < args.length; i += 2) {
            switch (args[i]) {
                case "--system" -> system = args[i + 1];
                case "--agents" -> agents = Integer.parseInt(args[i + 1]);
                case "--hosts" -> hosts = Integer.parseInt(args[i + 1]);
                case "--warmup" -> warmup = Integer.parseInt(args[i + 1]);
                case "--seconds" -> seconds = Integer.parseInt(args[i + 1]);
                case "--paced" -> share = Double.parseDouble(args[i + 1]);
                default -> throw new IllegalArgumentException("unknown argument " + args[i] + " (--system robomw|jade --agents N --hosts H --warmup W --seconds S --paced SHARE)");
            }
        }
        if (!system.equals("robomw") && !system.equals("jade")) {
            throw new IllegalArgumentException("--system is robomw or jade, not " + system);
        }
        Path work = Files.createTempDirectory("robomw-many-agents");
        ManyAgentsBenchmark b = new ManyAgentsBenchmark(system, agents, hosts, warmup, seconds, share, work);
        try {
            b.run();
        } finally {
            b.close();
            deleteTree(work);
        }
        System.exit(0);
    }

    private void run() throws Exception {
        String load0 = load();
        start();
        String jar = system.equals("robomw") ? jar().toString() : null;
        PeerProcess home = peers.get(0);
        // Parked agents first, on fresh JVMs (after the hop phase, idle runner threads ending made the live heap fall meanwhile):
        // a warm-up batch loads the classes and opens the sessions, then the live heap before and after N more.
        PeerProcess parking = peers.get(1);
        int warmParked = Math.max(10, agents / 20);
        int warmArrived = park(home, parking, jar, warmParked, 0);
        long before = Long.parseLong(parking.ask("HEAP", "HEAP", Duration.ofMinutes(1)).substring(5));
        int arrived = park(home, parking, jar, agents, warmArrived) - warmArrived;
        long after = Long.parseLong(parking.ask("HEAP", "HEAP", Duration.ofMinutes(1)).substring(5));
        double perParked = (after - before) / (double) arrived;
        parking.ask("RELEASE", "RELEASED");
        int parkLost = warmParked + agents - (warmArrived + arrived);
        say(String.format(Locale.ROOT, "%s: %d agents waiting at one host (after %d more to warm up; %d lost on the way): live heap %.1f → %.1f MiB, %.0f bytes per agent",
                system, arrived, warmArrived, parkLost, before / 1048576.0, after / 1048576.0, perParked));
        System.out.println(line("many." + system + ".park-lost", parkLost, "agents"));
        if (jar != null) {
            // RoboMW's released agents end their trips before the hops begin (JADE's stay, idle)
            int sent = warmParked + agents;
            int[] returned = {0};
            Await.until("every released agent's trip ended at " + names.get(0), HOME,
                    () -> (returned[0] = count(home, "RETURNED")) >= sent, () -> returned[0] + " of " + sent);
        }
        String launch = "LAUNCH " + agents + (jar == null ? "" : " " + jar) + " " + String.join(" ", names);
        home.ask(launch, "LAUNCHED", Duration.ofMinutes(2));
        say("%s: %d agents launched among %d hosts; warm-up %d s".formatted(system, agents, hosts, warmup));
        Thread.sleep(warmup * 1000L);
        for (PeerProcess p : peers) {
            p.ask("MEASURE", "MEASURING");
        }
        long cpu0 = cpu();
        long t0 = System.nanoTime();
        Thread.sleep(seconds * 1000L);
        long[] histogram = new long[HopLog.BUCKETS];
        double perSecond = snap(histogram);
        long t1 = System.nanoTime();
        long cpu1 = cpu();
        long hops = java.util.Arrays.stream(histogram).sum();
        double window = (t1 - t0) / 1e9;
        double p50 = percentile(histogram, hops, 0.50);
        double p99 = percentile(histogram, hops, 0.99);
        double cpuPerHop = hops == 0 ? Double.NaN : (cpu1 - cpu0) / 1e3 / hops;
        say(String.format(Locale.ROOT, "%s saturated: %,d hops in %.1f s: %,.0f hops/s, p50 %.0f µs, p99 %.0f µs",
                system, hops, window, perSecond, p50, p99));
        Paced paced = share > 0 && perSecond > 0 ? paced(perSecond) : null;
        for (PeerProcess p : peers) {
            p.ask("STOP", "STOPPING");
        }
        int[] home0 = homeCount(home);
        int lost = agents - home0[0];
        say(String.format(Locale.ROOT, "%s: %,d hops in %.1f s: %,.0f hops/s, p50 %.0f µs, p99 %.0f µs, CPU of the %d JVMs %.1f µs per hop; home %d of %d (%d trips failed), lost %d",
                system, hops, window, perSecond, p50, p99, hosts, cpuPerHop, home0[0], agents, home0[1], lost));
        say("%s: load average %s before, %s after".formatted(system, load0, load()));
        String id = "many." + system + ".";
        System.out.println(line(id + "hops-per-s", perSecond, "hops/s"));
        System.out.println(line(id + "p50", p50, "µs"));
        System.out.println(line(id + "p99", p99, "µs"));
        System.out.println(line(id + "cpu-per-hop", cpuPerHop, "µs"));
        System.out.println(line(id + "heap-per-parked", perParked, "bytes"));
        System.out.println(line(id + "lost", lost, "agents"));
        if (paced != null) {
            System.out.println(line(id + "paced.wait", paced.waitNanos / 1e3, "µs"));
            System.out.println(line(id + "paced.hops-per-s", paced.perSecond, "hops/s"));
            System.out.println(line(id + "paced.share", paced.perSecond / perSecond, "of saturated"));
            System.out.println(line(id + "paced.p50", paced.p50, "µs"));
            System.out.println(line(id + "paced.p99", paced.p99, "µs"));
        }
        // RoboMW must bring every agent home; what JADE loses is a figure of the baseline, not a failure of the harness.
        if (system.equals("robomw") && (lost != 0 || home0[1] != 0)) {
            throw new IllegalStateException(lost + " of " + agents + " agents not home within " + HOME + ", " + home0[1] + " trips failed");
        }
    }

    /** What the paced phase measured. */
    private record Paced(long waitNanos, double perSecond, double p50, double p99) {
    }

    /**
     * The paced phase: every hopping agent waits at each stop for a time whose mean makes the
     * offered load {@code share} of the saturated rate measured just before (N agents each leaving
     * once per N / (share × rate) s; a little less in fact, the hop's own latency adds to each
     * cycle), so the latency is the hop's rather than the queue's at saturation (Little's law), as
     * wrk2 measures at a fixed rate to avoid coordinated omission. Settles for the warm-up / 2
     * (at least 5 s and two waits), then records for the same S s.
     */
    private Paced paced(double saturated) throws Exception {
        long wait = (long) (agents / (share * saturated) * 1e9);
        for (PeerProcess p : peers) {
            p.ask("PACE " + wait, "PACED");
        }
        Thread.sleep(Math.max(Math.max(5000L, warmup * 500L), 2 * wait / 1_000_000));
        for (PeerProcess p : peers) {
            p.ask("MEASURE", "MEASURING");
        }
        Thread.sleep(seconds * 1000L);
        long[] histogram = new long[HopLog.BUCKETS];
        double perSecond = snap(histogram);
        long hops = java.util.Arrays.stream(histogram).sum();
        Paced r = new Paced(wait, perSecond, percentile(histogram, hops, 0.50), percentile(histogram, hops, 0.99));
        say(String.format(Locale.ROOT, "%s paced at %.0f %% of %,.0f hops/s (mean wait %.1f ms at each stop): %,d hops, %,.0f hops/s (%.0f %%), p50 %.0f µs, p99 %.0f µs",
                system, share * 100, saturated, wait / 1e6, hops, perSecond, 100 * perSecond / saturated, r.p50, r.p99));
        return r;
    }

    /** Stops recording on every host and adds their histograms into {@code histogram}: @return the hops per second of all hosts */
    private double snap(long[] histogram) throws Exception {
        double perSecond = 0;
        for (PeerProcess p : peers) {
            String[] snap = p.ask("SNAP", "SNAP").split(" ");
            long hostHops = 0;
            String s = snap[2];
            if (!s.equals("-")) {
                for (String e : s.split(",")) {
                    int colon = e.indexOf(':');
                    long n = Long.parseLong(e.substring(colon + 1));
                    histogram[Integer.parseInt(e.substring(0, colon))] += n;
                    hostHops += n;
                }
            }
            perSecond += hostHops / (Long.parseLong(snap[1]) / 1e9);
        }
        return perSecond;
    }

    /**
     * Sends {@code n} agents to wait at the parking host and waits until {@code waiting + n} wait there.
     * RoboMW's sample fails if one does not arrive within {@link #HOME}; JADE's (the baseline, which
     * loses an agent on the way in some runs) goes on once none has arrived for {@link #PARK_STALL}
     * with every one of them but {@link #PARK_LOSS_ALLOWED} in, and reports the ones lost.
     *
     * @return how many wait there now
     */
    private int park(PeerProcess home, PeerProcess parking, String jar, int n, int waiting) {
        int total = waiting + n;
        home.ask("PARK " + n + (jar == null ? "" : " " + jar) + " " + names.get(1), "PARKING", Duration.ofMinutes(2));
        int[] parked = {0};
        long[] progress = {-1, System.nanoTime()};
        Await.until(total + " agents waiting at " + names.get(1), HOME, () -> {
            parked[0] = count(parking, "PARKED");
            long now = System.nanoTime();
            if (parked[0] != progress[0]) {
                progress[0] = parked[0];
                progress[1] = now;
            }
            boolean stalled = jar == null && now - progress[1] > PARK_STALL.toNanos() && total - parked[0] <= PARK_LOSS_ALLOWED;
            return parked[0] >= total || stalled;
        }, () -> "(" + parked[0] + " arrived)");
        return parked[0];
    }

    /** Asks a host for one of its counters ({@code PARKED}, {@code RETURNED}): its answer is the word and the count. */
    private static int count(PeerProcess peer, String counter) {
        return Integer.parseInt(peer.ask(counter, counter).substring(counter.length() + 1));
    }

    private static String line(String id, double value, String unit) {
        return String.format(Locale.ROOT, "BENCH %s %.6g %s", id, value, unit);
    }

    /** Waits until every agent is home or its trip failed (or the deadline): {home, failed} as last counted, partial at the deadline. */
    private int[] homeCount(PeerProcess home) {
        int[][] r = {{0, 0}};
        try {
            Await.until("every agent home at " + names.get(0), HOME, () -> {
                String[] f = home.ask("HOME", "HOME").split(" ");
                r[0] = new int[] {Integer.parseInt(f[1]), Integer.parseInt(f[2])};
                return r[0][0] + r[0][1] >= agents;
            });
        } catch (AssertionError notAll) {
            // the caller reports what is missing: JADE's lost agents are a figure of the baseline
        }
        return r[0];
    }

    private static double percentile(long[] histogram, long total, double q) {
        if (total == 0) {
            return Double.NaN;
        }
        long rank = (long) Math.ceil(total * q);
        long seen = 0;
        for (int i = 0; i < histogram.length; i++) {
            seen += histogram[i];
            if (seen >= rank) {
                return HopLog.micros(i);
            }
        }
        return HopLog.micros(histogram.length - 1);
    }

    // ---- processes ----

    private void start() throws Exception {
        List<String> jvm = new ArrayList<>(List.of("-Xmx1g", "-Dorg.slf4j.simpleLogger.defaultLogLevel=warn"));
        for (String property : io.robomw.bench.AgentBenchPeer.PROPERTIES) {
            String value = System.getProperty(property);
            if (value != null) {
                jvm.add("-D" + property + "=" + value);
            }
        }
        String extra = System.getProperty("many.peerJvmArgs", "").trim();
        if (!extra.isEmpty()) {
            jvm.addAll(List.of(extra.split("\\s+")));
        }
        String main = ManyAgentsPeer.class.getName();
        if (system.equals("robomw")) {
            for (int i = 1; i <= hosts; i++) {
                peers.add(PeerProcess.start("many-robomw-h" + i, main, named(jvm, "h" + i), List.of("robomw", "many-h" + i)));
            }
        } else {
            int port = freePort();
            peers.add(PeerProcess.start("many-jade-C1", main, named(jvm, "C1"), List.of("jade", "main", "C1", String.valueOf(port))));
            peers.get(0).expect("READY", START);
            for (int i = 2; i <= hosts; i++) {
                peers.add(PeerProcess.start("many-jade-C" + i, main, named(jvm, "C" + i), List.of("jade", "peripheral", "C" + i, String.valueOf(port), String.valueOf(freePort()))));
            }
        }
        for (int i = 0; i < peers.size(); i++) {
            String ready = system.equals("jade") && i == 0 ? "READY C1" : peers.get(i).expect("READY", START);
            names.add(ready.substring(6));
        }
    }

    /** @return the JVM options with {@code {host}} (in {@code -Dmany.peerJvmArgs}, e.g. a JFR file name) replaced by the host's name */
    private static List<String> named(List<String> jvm, String host) {
        return jvm.stream().map(o -> o.replace("{host}", host)).toList();
    }

    private long cpu() {
        long sum = 0;
        for (PeerProcess p : peers) {
            sum += cpuNanos(p.process().pid());
        }
        return sum;
    }

    /** @return a process's processor time so far (user + system, every thread), ns, from /proc */
    static long cpuNanos(long pid) {
        try {
            String stat = Files.readString(Path.of("/proc/" + pid + "/stat"));
            String[] f = stat.substring(stat.lastIndexOf(')') + 2).split(" ");
            return (Long.parseLong(f[11]) + Long.parseLong(f[12])) * 10_000_000L;
        } catch (IOException | RuntimeException e) {
            throw new IllegalStateException("cannot read the processor time of process " + pid + " from /proc", e);
        }
    }

    private void close() {
        for (int i = peers.size() - 1; i >= 0; i--) {
            peers.get(i).close();
        }
    }

    private static int freePort() throws IOException {
        try (ServerSocket s = new ServerSocket(0, 1, InetAddress.getByName("127.0.0.1"))) {
            return s.getLocalPort();
        }
    }

    private static String load() {
        try {
            String[] f = Files.readString(Path.of("/proc/loadavg")).split(" ");
            return f[0] + " " + f[1] + " " + f[2];
        } catch (IOException e) {
            return "unknown";
        }
    }

    private static void say(String line) {
        System.out.println(line);
    }

    // ---- the agent's code ----

    private Path jar() throws IOException {
        byte[] agentClass = AgentBenchmark.compile(work, "HopAgent", AGENT_SOURCE);
        Path jar = work.resolve("hop-agent.jar");
        try (OutputStream f = Files.newOutputStream(jar); JarOutputStream j = new JarOutputStream(f)) {
            j.putNextEntry(new JarEntry("io/robomw/benchagent/HopAgent.class"));
            j.write(agentClass);
            j.closeEntry();
        }
        return jar;
    }

    private static void deleteTree(Path root) throws IOException {
        if (!Files.exists(root)) {
            return;
        }
        try (Stream<Path> walk = Files.walk(root)) {
            for (Path p : walk.sorted(Comparator.reverseOrder()).toList()) {
                Files.deleteIfExists(p);
            }
        }
    }
}
