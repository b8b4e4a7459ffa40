package io.robomw.bench;

import io.robomw.agents.host.AgentHost;
import io.robomw.agents.host.AgentHostBuilder;
import io.robomw.agents.host.code.StateCodec;
import io.robomw.api.Agent;
import io.robomw.api.AgentRef;
import io.robomw.bench.jade.JadeMoveBaseline;
import io.robomw.it.messaging.PeerProcess;

import javax.tools.JavaCompiler;
import javax.tools.ToolProvider;
import java.io.ByteArrayOutputStream;
import java.io.IOException;
import java.io.OutputStream;
import java.io.Serializable;
import java.net.URL;
import java.net.URLClassLoader;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.Arrays;
import java.util.Comparator;
import java.util.List;
import java.util.Locale;
import java.util.UUID;
import java.util.concurrent.TimeUnit;
import java.util.function.LongConsumer;
import java.util.jar.JarEntry;
import java.util.jar.JarOutputStream;
import java.util.stream.Stream;

/**
 * The mobile-agent benchmark (issue 5): host A in this JVM (the agents' home), host B in a JVM of
 * its own ({@link AgentBenchPeer}), both on 127.0.0.1, with JADE's {@code doMove} round trip
 * ({@link JadeMoveBaseline}) measured in the same run. Writes {@code target/benchmarks/agents.md}.
 *
 * <p>The agent's class ({@code io.robomw.benchagent.BenchAgent}, source below) is compiled at run
 * time into a jar that only this JVM has, and loaded through a {@link URLClassLoader}: host B gets
 * its code as an archive, so code shipping is real.
 *
 * <ul>
 *   <li><b>Warm round trip.</b> One agent goes A→B→A again and again: at each stop its
 *   {@code run()} clears its itinerary and adds the next stop (B at A, A at B), so its state
 *   (itinerary and history included) stays the same size; at A it passes {@code System.nanoTime()}
 *   to a sink of this JVM. A round trip is the time between two successive stops at A: two hops,
 *   each with its transfer, the receiving host's store, its acknowledgement, and the stop's work,
 *   and nothing else (no result, no message, no extra trip). Memory mode, then durable mode (both
 *   hosts with a journal in a temporary directory).</li>
 *   <li><b>Cold first dispatch.</b> An archive B has never seen (the same class in a jar with a
 *   unique resource entry, one jar per dispatch, each in a class loader of its own, the agent made
 *   before the clock starts): time until {@code startTrip} returns (B has stored the agent and
 *   acknowledged), and until its result is home (its stop at B ends the trip).</li>
 *   <li><b>Wire bytes per warm hop.</b> Bytes through both hosts' RMI server sockets (in + out:
 *   every byte of the A↔B connections once each way it is counted) around N warm round trips,
 *   divided by 2N hops, next to the agent's state as the host sends it ({@link StateCodec#writeCompact}).</li>
 * </ul>
 *
 * <p>Run: {@code bench/agents}. Not part of the normal test run.
 */
public final class AgentBenchmark {

    static final int[] PAYLOADS = {0, 10 * 1024, 1024 * 1024};
    static final int WARMUP = 200;
    static final int ITERATIONS = Integer.getInteger("agent.bench.iterations", 3000);
    /** Round trips measured at 1 MB ({@code -Dagent.bench.iterations1MB}); by default as many as the others. */
    static final int ITERATIONS_1MB = Integer.getInteger("agent.bench.iterations1MB", ITERATIONS);
    /**
     * Fresh JVMs are warmed (JIT) before anything is measured, RoboMW's and JADE's alike: passes
     * of {@value #WARMUP_PASS} round trips at 0 B, discarded, until a pass's p50 is within
     * {@value #STEADY_PERCENT} % of the one before (at least {@value #MIN_PASSES}, at most
     * {@value #MAX_PASSES} passes). JADE's author found one pass of 2000 enough for JADE; RoboMW's
     * hop path was still getting faster after ten (bench runs: p50 535, 285, 247, 187, 154, 146, 133, 111, 100, 103 µs).
     */
    static final int WARMUP_PASS = Integer.getInteger("agent.bench.pass", 2000);
    static final int MIN_PASSES = Integer.getInteger("agent.bench.minPasses", 12);
    static final int MAX_PASSES = 24;
    static final int STEADY_PERCENT = 5;

    /** One warm-up pass: its p50 in µs. */
    @FunctionalInterface
    interface Pass {
        double p50() throws Exception;
    }

    /** Runs warm-up passes until the p50 is steady; returns the p50 of each pass. */
    static List<Double> warmUp(Pass pass) throws Exception {
        List<Double> p50s = new ArrayList<>();
        while (p50s.size() < MAX_PASSES) {
            p50s.add(pass.p50());
            int n = p50s.size();
            if (n >= MIN_PASSES && Math.abs(p50s.get(n - 1) - p50s.get(n - 2)) <= p50s.get(n - 2) * STEADY_PERCENT / 100.0) {
                break;
            }
        }
        return p50s;
    }

    static final int COLD = 20;
    static final int WIRE_ROUNDS = 200;
    static final String TICKS = "robomw.bench.ticks";

    /** The benchmark agent; compiled at run time so that only this JVM has its class. */
    static final String AGENT_SOURCE = """
            package io.robomw.benchagent;

            import io.robomw.api.Agent;
            import io.robomw.api.AgentContext;
            import io.robomw.api.Itinerary;
            import java.util.function.LongConsumer;

            /** Goes A->B->A until its rounds are done, or (rounds 0) ends its trip at B with a result. */
            public class BenchAgent extends Agent {
                private static final long serialVersionUID = 1L;
                private final byte[] payload;
                private final String far;
                private int rounds;

                public BenchAgent(byte[] payload, String far, int rounds) {
                    this.payload = payload;
                    this.far = far;
                    this.rounds = rounds;
                }

                @Override
                public void run() {
                    AgentContext c = context();
                    Itinerary it = itinerary();
                    it.clear();
                    if (!c.hostAddress().equals(c.homeAddress())) {
                        if (rounds > 0) {
                            it.addStop(c.homeAddress());
                        } else {
                            c.setResult(c.hostName() + " " + payload.length);
                        }
                        return;
                    }
                    if (System.getProperties().get("%s") instanceof LongConsumer sink) {
                        sink.accept(System.nanoTime());
                    }
                    if (--rounds > 0) {
                        it.addStop(far);
                    }
                }
            }
            """.formatted(TICKS);
    static final String AGENT_CLASS = "io.robomw.benchagent.BenchAgent";

    /** Round trips of one warm measurement, nanoseconds. */
    record RoundTrips(long[] nanos) {
        double p50() {
            return percentile(0.50);
        }

        double p99() {
            return percentile(0.99);
        }

        double percentile(double q) {
            long[] s = nanos.clone();
            Arrays.sort(s);
            return s[Math.min(s.length - 1, (int) (s.length * q))] / 1000.0;
        }
    }

    /** Cold dispatches: to B's acknowledgement and to the result home, nanoseconds each. */
    record Cold(long[] ack, long[] result) {
    }

    /** Wire bytes of one payload. */
    record Wire(int payload, int state, double perHop) {
    }

    /** One mode's figures. */
    record Mode(String name, List<RoundTrips> warm, Cold cold, List<Wire> wire) {
    }

    private final Path work;
    private final byte[] agentJarBase;
    private final List<String> notes = new ArrayList<>();
    private final java.util.Map<String, List<Double>> warmups = new java.util.LinkedHashMap<>();
    private List<Double> jadeWarmup = List.of();

    AgentBenchmark(Path work, byte[] agentJarBase) {
        this.work = work;
        this.agentJarBase = agentJarBase;
    }

    /**
     * @param args ignored
     * @throws Exception on failure
     */
    public static void main(String[] args) throws Exception {
        Path work = Files.createTempDirectory("robomw-agent-bench");
        try {
            new AgentBenchmark(work, compileAgent(work)).run();
        } finally {
            System.getProperties().remove(TICKS);
            deleteTree(work);
        }
    }

    /**
     * @return the systems this run measures, {@code -Dagent.bench.modes} (a comma-separated subset
     *         of memory, durable, jade; default all three): {@code bench/all} measures each in JVMs
     *         of its own, and then no table is written, only the {@code BENCH} lines
     */
    private static List<String> modes() {
        return Arrays.asList(System.getProperty("agent.bench.modes", "memory,durable,jade").trim().split("\\s*,\\s*"));
    }

    /** @return the round trips measured at a payload */
    private static int iterations(int payload) {
        return payload >= 1 << 20 ? ITERATIONS_1MB : ITERATIONS;
    }

    void run() throws Exception {
        String loadBefore = loadAverage();
        List<String> modes = modes();
        if (!modes.containsAll(List.of("memory", "durable", "jade"))) {
            if (modes.contains("memory")) {
                mode("memory", false);
            }
            if (modes.contains("durable")) {
                mode("durable", true);
            }
            if (modes.contains("jade")) {
                jade();
            }
            say("partial run (-Dagent.bench.modes=" + String.join(",", modes) + "): BENCH lines only, no table");
            return;
        }
        Mode memory = mode("memory", false);
        Mode durable = mode("durable", true);
        List<JadeMoveBaseline.RoundTrips> jade = new ArrayList<>();
        if (!Boolean.parseBoolean(System.getProperty("agent.bench.jade", "true"))) {
            say("JADE baseline skipped (-Dagent.bench.jade=false): no ratios in this run");
            write(memory, durable, jade, loadBefore, loadAverage());
            return;
        }
        jade.addAll(jade());
        String loadAfter = loadAverage();
        write(memory, durable, jade, loadBefore, loadAfter);
    }

    /** JADE's two containers in fresh JVMs: warmed as RoboMW is, then each payload. */
    private List<JadeMoveBaseline.RoundTrips> jade() throws Exception {
        List<JadeMoveBaseline.RoundTrips> jade = new ArrayList<>();
        try (JadeMoveBaseline j = JadeMoveBaseline.start()) {
            List<Double> w = warmUp(() -> j.measure(0, 0, WARMUP_PASS).p50Micros());
            jadeWarmup = w;
            say("JADE JVM warm-up passes (p50 µs, discarded): " + format(w));
            for (int p : PAYLOADS) {
                JadeMoveBaseline.RoundTrips r = j.measure(p, WARMUP, iterations(p));
                jade.add(r);
                say(String.format(Locale.ROOT, "JADE doMove A->B->A %8d B  p50 %8.1f µs  p99 %8.1f µs", p, r.p50Micros(), r.p99Micros()));
                System.out.println(BenchReport.line("agents.jade." + payloadId(p), r.p50Micros(), "µs"));
            }
        }
        return jade;
    }

    /** @return 0B, 10KB or 1MB: a payload as the BENCH lines name it */
    private static String payloadId(int bytes) {
        return bytes >= 1 << 20 ? bytes / (1 << 20) + "MB" : bytes >= 1024 ? bytes / 1024 + "KB" : bytes + "B";
    }

    // ---- one mode: host A here, host B in its own JVM ----

    private Mode mode(String name, boolean durable) throws Exception {
        Path dirA = work.resolve(name + "-a");
        Path dirB = work.resolve(name + "-b");
        List<String> peerArgs = durable ? List.of("durable", dirB.toString()) : List.of("memory");
        List<String> peerJvm = new ArrayList<>(List.of("-Xmx2g", "-Dorg.slf4j.simpleLogger.defaultLogLevel=warn"));
        for (String spinProperty : AgentBenchPeer.PROPERTIES) {
            String spin = System.getProperty(spinProperty);
            if (spin != null) {
                peerJvm.add("-D" + spinProperty + "=" + spin);
            }
        }
        String extra = System.getProperty("agent.bench.peerJvmArgs", "").trim();
        if (!extra.isEmpty()) {
            peerJvm.addAll(Arrays.asList(extra.split("\\s+")));
        }
        try (PeerProcess b = PeerProcess.start("agent-bench-b-" + name, AgentBenchPeer.class.getName(), peerJvm, peerArgs)) {
            String far = b.expect("ADDRESS", PeerProcess.COMMAND).substring("ADDRESS ".length());
            AgentHostBuilder builder = AgentBenchPeer.spin(AgentHost.builder("bench-a").bind("127.0.0.1").clusterKey(AgentBenchPeer.KEY));
            if (durable) {
                builder.store(dirA);
            }
            try (AgentHost a = builder.start(); URLClassLoader code = loader(jar("warm"))) {
                Class<?> agentClass = code.loadClass(AGENT_CLASS);
                List<Double> w = warmUp(() -> warm(a, far, agentClass, 0, 0, WARMUP_PASS).p50());
                warmups.put(name, w);
                say("RoboMW " + name + " JVM warm-up passes (p50 µs, discarded): " + format(w));
                List<RoundTrips> warm = new ArrayList<>();
                long peerPid = b.process().pid();
                for (int p : PAYLOADS) {
                    long cpu0 = cpuNanos(ProcessHandle.current().pid()) + cpuNanos(peerPid);
                    RoundTrips r = warm(a, far, agentClass, p, WARMUP, iterations(p));
                    long cpu = cpuNanos(ProcessHandle.current().pid()) + cpuNanos(peerPid) - cpu0;
                    warm.add(r);
                    double cpuPerTrip = cpu / 1e3 / (WARMUP + iterations(p) + 1);
                    say(String.format(Locale.ROOT, "RoboMW %-7s A->B->A %8d B  p50 %8.1f µs  p99 %8.1f µs  CPU (both JVMs) %8.1f µs per round trip",
                            name, p, r.p50(), r.p99(), cpuPerTrip));
                    System.out.println(BenchReport.line("agents." + name + "." + payloadId(p), r.p50(), "µs"));
                    System.out.println(BenchReport.line("agents." + name + "." + payloadId(p) + ".cpu", cpuPerTrip, "µs"));
                }
                if (!Boolean.parseBoolean(System.getProperty("agent.bench.extras", "true"))) {
                    return new Mode(name, warm, null, List.of());
                }
                List<Wire> wire = new ArrayList<>();
                for (int p : PAYLOADS) {
                    wire.add(wire(a, b, far, agentClass, p));
                }
                Cold cold = cold(a, far);
                return new Mode(name, warm, cold, wire);
            }
        }
    }

    /**
     * @param pid a process of this machine
     * @return its processor time so far (user and system, all threads, GC included), ns, from /proc; 0 where there is none
     */
    static long cpuNanos(long pid) {
        try {
            String stat = java.nio.file.Files.readString(java.nio.file.Path.of("/proc/" + pid + "/stat"));
            String[] f = stat.substring(stat.lastIndexOf(')') + 2).split(" ");
            // fields 14 and 15 of proc(5) (utime, stime), here at 11 and 12 after the name; clock ticks of 10 ms
            return (Long.parseLong(f[11]) + Long.parseLong(f[12])) * 10_000_000L;
        } catch (IOException | RuntimeException e) {
            return 0;
        }
    }

    /** One agent, {@code warmup + iterations} timed round trips, the last {@code iterations} kept. */
    RoundTrips warm(AgentHost a, String far, Class<?> agentClass, int payload, int warmup, int iterations) throws Exception {
        int rounds = warmup + iterations + 1;
        Ticks ticks = new Ticks(rounds);
        System.getProperties().put(TICKS, ticks);
        try {
            AgentRef ref = a.agency().startTrip(agent(agentClass, payload, far, rounds));
            ref.result().get(60 + rounds / 10, TimeUnit.SECONDS);
        } finally {
            System.getProperties().remove(TICKS);
        }
        long[] t = ticks.times();
        if (t.length != rounds) {
            throw new IllegalStateException(t.length + " stops at A, expected " + rounds);
        }
        long[] rt = new long[iterations];
        for (int i = 0; i < iterations; i++) {
            int k = warmup + 1 + i;
            rt[i] = t[k] - t[k - 1];
        }
        return new RoundTrips(rt);
    }

    /** Bytes on the A↔B connections per warm hop, and the agent's state as it leaves A. */
    private Wire wire(AgentHost a, PeerProcess b, String far, Class<?> agentClass, int payload) throws Exception {
        int rounds = payload >= 1 << 20 ? WIRE_ROUNDS / 4 : WIRE_ROUNDS;
        // One round trip first, so that whatever the trip before left in flight is done.
        a.agency().startTrip(agent(agentClass, payload, far, 1)).result().get(60, TimeUnit.SECONDS);
        long before = a.wireBytesIn() + a.wireBytesOut() + wireOf(b);
        a.agency().startTrip(agent(agentClass, payload, far, rounds)).result().get(120, TimeUnit.SECONDS);
        long after = a.wireBytesIn() + a.wireBytesOut() + wireOf(b);
        // The state as it leaves A on every round but the first: itinerary [B], history [A done], at stop 0.
        Agent replica = agent(agentClass, payload, far, rounds);
        replica.itinerary().record(a.address(), io.robomw.api.Itinerary.Outcome.DONE, "");
        replica.itinerary().goToNext();
        // in the form the host sends it in (compact unless told to serve older hosts)
        java.io.ByteArrayOutputStream compact = new java.io.ByteArrayOutputStream();
        new StateCodec(java.util.List.of(), Long.MAX_VALUE).writeCompact(replica, compact);
        int state = compact.size();
        Wire w = new Wire(payload, state, (after - before) / (2.0 * rounds));
        say(String.format(Locale.ROOT, "RoboMW wire per warm hop %8d B payload: %10.1f bytes, state %8d bytes, overhead %6.1f bytes (%d round trips)",
                payload, w.perHop(), state, w.perHop() - state, rounds));
        return w;
    }

    private static long wireOf(PeerProcess b) {
        String[] r = b.ask("WIRE", "WIRE").split(" ");
        return Long.parseLong(r[1]) + Long.parseLong(r[2]);
    }

    /** {@value #COLD} dispatches, each of a jar B has never seen. */
    private Cold cold(AgentHost a, String far) throws Exception {
        long[] ack = new long[COLD];
        long[] result = new long[COLD];
        for (int i = 0; i < COLD; i++) {
            try (URLClassLoader code = loader(jar("cold-" + UUID.randomUUID()))) {
                Agent agent = agent(code.loadClass(AGENT_CLASS), 0, far, 0);
                long t0 = System.nanoTime();
                AgentRef ref = a.agency().startTrip(agent);
                long t1 = System.nanoTime();
                Serializable r = ref.result().get(30, TimeUnit.SECONDS);
                long t2 = System.nanoTime();
                if (!"bench-b 0".equals(r)) {
                    throw new IllegalStateException("cold dispatch answered " + r);
                }
                ack[i] = t1 - t0;
                result[i] = t2 - t0;
            }
        }
        Cold c = new Cold(ack, result);
        say(String.format(Locale.ROOT, "RoboMW cold first dispatch: to B's ack median %.2f ms (max %.2f), to result median %.2f ms (max %.2f)",
                median(ack) / 1e6, max(ack) / 1e6, median(result) / 1e6, max(result) / 1e6));
        return c;
    }

    /** A new agent whose first stop is B. */
    private static Agent agent(Class<?> agentClass, int payload, String far, int rounds) throws ReflectiveOperationException {
        Agent agent = (Agent) agentClass.getConstructor(byte[].class, String.class, int.class).newInstance(new byte[payload], far, rounds);
        agent.itinerary().addStop(far);
        return agent;
    }

    /** Collects the agent's stop times at A. */
    private static final class Ticks implements LongConsumer {
        private final long[] times;
        private int n;

        Ticks(int capacity) {
            times = new long[capacity];
        }

        @Override
        public synchronized void accept(long t) {
            if (n < times.length) {
                times[n++] = t;
            }
        }

        synchronized long[] times() {
            return Arrays.copyOf(times, n);
        }
    }

    // ---- the agent's code ----

    static byte[] compileAgent(Path work) throws IOException {
        return compile(work, "BenchAgent", AGENT_SOURCE);
    }

    /**
     * Compiles a benchmark's agent, kept off the class path so its code travels as an archive.
     *
     * @param work       a directory for the source and the classes
     * @param simpleName the class's name in package {@code io.robomw.benchagent}
     * @param source     its source
     * @return its class file
     */
    public static byte[] compile(Path work, String simpleName, String source) throws IOException {
        Path src = work.resolve("src/io/robomw/benchagent/" + simpleName + ".java");
        Path classes = work.resolve("classes");
        Files.createDirectories(src.getParent());
        Files.createDirectories(classes);
        Files.writeString(src, source);
        JavaCompiler javac = ToolProvider.getSystemJavaCompiler();
        if (javac == null) {
            throw new IllegalStateException("the benchmark needs a JDK (javax.tools) to compile its agent");
        }
        ByteArrayOutputStream err = new ByteArrayOutputStream();
        int rc = javac.run(null, null, err, "-d", classes.toString(), "-cp", System.getProperty("java.class.path"), "--release", "17", src.toString());
        if (rc != 0) {
            throw new IllegalStateException("the benchmark agent does not compile:\n" + err.toString(StandardCharsets.UTF_8));
        }
        return Files.readAllBytes(classes.resolve("io/robomw/benchagent/" + simpleName + ".class"));
    }

    /** A jar with the agent class and a resource entry of its own, so each tag gives an archive of its own. */
    Path jar(String tag) throws IOException {
        Path jar = work.resolve("agent-" + tag + ".jar");
        try (OutputStream f = Files.newOutputStream(jar); JarOutputStream j = new JarOutputStream(f)) {
            j.putNextEntry(new JarEntry("io/robomw/benchagent/BenchAgent.class"));
            j.write(agentJarBase);
            j.closeEntry();
            j.putNextEntry(new JarEntry("bench/" + tag + ".txt"));
            j.write(tag.getBytes(StandardCharsets.UTF_8));
            j.closeEntry();
        }
        return jar;
    }

    static URLClassLoader loader(Path jar) throws IOException {
        return new URLClassLoader("bench-agent", new URL[] {jar.toUri().toURL()}, AgentBenchmark.class.getClassLoader());
    }

    // ---- report ----

    private void write(Mode memory, Mode durable, List<JadeMoveBaseline.RoundTrips> jade, String loadBefore, String loadAfter) throws IOException {
        StringBuilder md = new StringBuilder();
        md.append("Load average (1, 5, 15 min) before the run: ").append(loadBefore).append("; after: ").append(loadAfter).append("\n\n");
        md.append("| warm round trip A→B→A (2 hops), " + ITERATIONS + " after " + WARMUP + " warm-up | RoboMW memory p50 / p99 µs | RoboMW durable p50 / p99 µs | JADE 4.3 doMove p50 / p99 µs | JADE p50 / RoboMW memory p50 | JADE p50 / RoboMW durable p50 |\n");
        md.append("|---|---:|---:|---:|---:|---:|\n");
        for (int i = 0; i < PAYLOADS.length; i++) {
            RoundTrips m = memory.warm().get(i);
            RoundTrips d = durable.warm().get(i);
            if (jade.isEmpty()) {
                md.append(String.format(Locale.ROOT, "| %s | %.1f / %.1f | %.1f / %.1f | not run | | |%n", label(PAYLOADS[i]), m.p50(), m.p99(), d.p50(), d.p99()));
                continue;
            }
            JadeMoveBaseline.RoundTrips j = jade.get(i);
            md.append(String.format(Locale.ROOT, "| %s | %.1f / %.1f | %.1f / %.1f | %.1f / %.1f | %.1f× | %.1f× |%n", label(PAYLOADS[i]), m.p50(), m.p99(), d.p50(), d.p99(),
                    j.p50Micros(), j.p99Micros(), j.p50Micros() / m.p50(), j.p50Micros() / d.p50()));
        }
        md.append("\n| cold first dispatch (an archive B has never seen), " + COLD + " dispatches | to B's ack: median ms | max ms | to the result home: median ms | max ms |\n|---|---:|---:|---:|---:|\n");
        for (Mode m : List.of(memory, durable)) {
            md.append(String.format(Locale.ROOT, "| %s mode | %.2f | %.2f | %.2f | %.2f |%n", m.name(), median(m.cold().ack()) / 1e6, max(m.cold().ack()) / 1e6,
                    median(m.cold().result()) / 1e6, max(m.cold().result()) / 1e6));
        }
        md.append("\n| wire bytes per warm hop (both directions, all A↔B connections) | state bytes | wire bytes per hop | overhead (wire − state) |\n|---|---:|---:|---:|\n");
        for (Mode m : List.of(memory, durable)) {
            for (Wire w : m.wire()) {
                md.append(String.format(Locale.ROOT, "| %s mode, %s | %,d | %,.1f | %.1f |%n", m.name(), label(w.payload()), w.state(), w.perHop(), w.perHop() - w.state()));
            }
        }
        md.append("\nJVM warm-up passes (" + WARMUP_PASS + " round trips at 0 B each, discarded; p50 µs): ");
        warmups.forEach((mode, p) -> md.append("RoboMW ").append(mode).append(": ").append(format(p)).append("; "));
        md.append("JADE: ").append(jadeWarmup.isEmpty() ? "not run" : format(jadeWarmup)).append('\n');
        if (!notes.isEmpty()) {
            md.append('\n');
            notes.forEach(n -> md.append(n).append('\n'));
        }
        Path out = Path.of("target", "benchmarks", "agents.md");
        Files.createDirectories(out.getParent());
        Files.writeString(out, md.toString());
        System.out.println();
        System.out.println(md);
        System.out.println("written to " + out.toAbsolutePath());
    }

    private static String format(List<Double> values) {
        return values.stream().map(v -> String.format(Locale.ROOT, "%.0f", v)).collect(java.util.stream.Collectors.joining(", "));
    }

    private static String label(int bytes) {
        if (bytes >= 1024 * 1024) {
            return bytes / (1024 * 1024) + " MB payload";
        }
        return bytes >= 1024 ? bytes / 1024 + " KB payload" : bytes + " B payload";
    }

    private static double median(long[] v) {
        long[] s = v.clone();
        Arrays.sort(s);
        return s.length % 2 == 1 ? s[s.length / 2] : (s[s.length / 2 - 1] + s[s.length / 2]) / 2.0;
    }

    private static long max(long[] v) {
        return Arrays.stream(v).max().orElse(0);
    }

    private static String loadAverage() {
        try {
            String[] f = Files.readString(Path.of("/proc/loadavg")).split(" ");
            return f[0] + ", " + f[1] + ", " + f[2];
        } catch (IOException | RuntimeException e) {
            return "unknown";
        }
    }

    private void say(String line) {
        System.out.println(line);
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
