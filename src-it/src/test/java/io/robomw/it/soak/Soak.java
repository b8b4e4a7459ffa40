package io.robomw.it.soak;

import io.robomw.agents.host.AgentHost;
import io.robomw.agents.host.ClusterKey;
import io.robomw.api.AgentRef;
import io.robomw.api.Itinerary;
import io.robomw.it.AtOnce;
import io.robomw.it.agents.HostProcess;

import java.io.IOException;
import java.io.Serializable;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.ArrayList;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Map;
import java.util.Set;
import java.util.concurrent.ConcurrentHashMap;
import java.util.concurrent.ExecutorService;
import java.util.concurrent.Executors;
import java.util.concurrent.Future;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicInteger;

/**
 * One soak run: host JVMs started with {@code mw host} (agents' code travels to them), agents of
 * {@link SoakAgent} going round them from a home in this JVM until a deadline, optionally one
 * durable host killed with -9 and restarted at an interval; then every agent's reports and result
 * are checked and each host's threads, files and heap are measured before and after.
 *
 * <p>Lost, duplicated and twice-run are counted from the agents' own reports (see
 * {@link SoakAgent}); an agent is lost when its result is not home within the drain time after
 * the deadline.
 */
final class Soak implements AutoCloseable {

    /** What a run is. */
    record Plan(String name, int hosts, int agents, Duration duration, int workMillis, Duration killEvery, Duration drain) {
    }

    /** One host's figures before and after. */
    record HostRow(String host, HostFigures before, HostFigures after, int restarts) {
    }

    /**
     * What a run found.
     *
     * @param plan             the run
     * @param sent             agents sent
     * @param home             agents whose result came home
     * @param stopsRun         stops whose work ran (distinct stop keys reported)
     * @param stopsRunTwice    stops whose work ran twice (one key, two nonces)
     * @param reportsLost      stops in an agent's result never reported home
     * @param reportsDuplicate reports delivered to the home twice (one key and nonce, twice)
     * @param interrupted      stops recorded INTERRUPTED (their host was killed while they ran)
     * @param unreachable      stops recorded UNREACHABLE
     * @param kills            kill -9s of the durable host
     * @param seconds          how long the run took, start to last result
     * @param rows             each host's figures
     */
    record Figures(Plan plan, int sent, int home, long stopsRun, long stopsRunTwice, long reportsLost, long reportsDuplicate, long interrupted,
                   long unreachable, int kills, double seconds, List<HostRow> rows) {
        int lost() {
            return sent - home;
        }
    }

    private static final String PASSPHRASE = "soak cluster";
    /** The most threads a host may have after a run beyond those it had before. */
    static final int THREAD_BOUND = 16;
    /** The most open files a host may have after a run beyond those it had before. */
    static final int FILE_BOUND = 16;
    /** The most heap (after a full GC, KiB) a host may hold after a run beyond what it held before. */
    static final long HEAP_BOUND_KIB = 32 * 1024;
    /**
     * A directory: when set ({@code -Dsoak.heapDumps=DIR}), every host's heap is dumped there before
     * and after the run, {@code <host>-before.hprof} and {@code <host>-after.hprof}, for finding
     * what holds what the figures show (docs/reliability.md).
     */
    static final String HEAP_DUMPS = "soak.heapDumps";

    private final Plan plan;
    private final Path dir;
    private final List<HostProcess> hosts = new ArrayList<>();
    private final Map<HostProcess, Integer> restarts = new LinkedHashMap<>();
    private AgentHost home;

    Soak(Plan plan, Path dir) {
        this.plan = plan;
        this.dir = dir;
    }

    /** Starts the hosts (the first one durable: the one killed), the home, and runs a few agents once round to warm up. */
    void start() throws Exception {
        Path key = Files.writeString(dir.resolve("cluster.key"), PASSPHRASE + "\n");
        // The host JVMs start at once (none needs another); every one that started is kept, to be closed, before a failure is thrown.
        List<AtOnce.Step<HostProcess>> starts = new ArrayList<>();
        for (int i = 0; i < plan.hosts(); i++) {
            String name = plan.name() + "-h" + (i + 1);
            List<String> args = new ArrayList<>(List.of("--key-file", key.toString(), "--no-messaging"));
            if (i == 0) {
                args.addAll(List.of("--store", dir.resolve(name).toString()));
            }
            starts.add(new AtOnce.Step<>("starting soak host " + name, () -> HostProcess.start(name, args.toArray(String[]::new))));
        }
        AtOnce.all(starts, Duration.ofMinutes(2), h -> {
            hosts.add(h);
            restarts.put(h, 0);
        });
        home = AgentHost.builder(plan.name() + "-home").clusterKey(ClusterKey.fromPassphrase(PASSPHRASE)).noMessaging().start();
        // Warm-up: the agent's code reaches every host, the links are made, the JITs have seen the hop path.
        List<AgentRef> warm = new ArrayList<>();
        for (int i = 0; i < 4; i++) {
            warm.add(home.agency().startTrip(agent(System.currentTimeMillis(), i)));
        }
        for (AgentRef r : warm) {
            r.result().get(2, TimeUnit.MINUTES);
        }
    }

    private SoakAgent agent(long endAt, int first) {
        SoakAgent a = new SoakAgent(endAt, plan.workMillis());
        for (int k = 0; k < hosts.size(); k++) {
            int at = (first + k) % hosts.size();
            a.itinerary().addStop(hosts.get(at).address());
            if (at == 0) {
                a.itinerary().addStop(hosts.get(at).address()); // a hop to the same host, the durable one in the kill runs
            }
        }
        a.itinerary().repeat(1_000_000).onUnreachable(Itinerary.UnreachablePolicy.RETRY).retry(240, Duration.ofMillis(250));
        return a;
    }

    /** Runs the plan and checks what came home. */
    Figures run() throws Exception {
        Map<HostProcess, HostFigures> before = figuresOfEachHost();
        for (HostProcess h : hosts) {
            heapDump(h, "before");
        }
        long started = System.nanoTime();
        long endAt = System.currentTimeMillis() + plan.duration().toMillis();
        Map<AgentRef, Map<String, Set<String>>> reports = new ConcurrentHashMap<>();
        AtomicInteger duplicates = new AtomicInteger();
        List<AgentRef> refs = java.util.Collections.synchronizedList(new ArrayList<>());
        ExecutorService launchers = Executors.newFixedThreadPool(8, r -> new Thread(r, "soak-launcher"));
        List<Future<?>> launches = new ArrayList<>();
        for (int i = 0; i < plan.agents(); i++) {
            int first = i;
            launches.add(launchers.submit(() -> {
                AgentRef ref = home.agency().startTrip(agent(endAt, first));
                Map<String, Set<String>> byKey = new ConcurrentHashMap<>();
                reports.put(ref, byKey);
                ref.addReportListener(v -> {
                    String[] keyNonce = ((String) v).split("/");
                    if (!byKey.computeIfAbsent(keyNonce[0], k -> ConcurrentHashMap.newKeySet()).add(keyNonce[1])) {
                        duplicates.incrementAndGet();
                    }
                });
                refs.add(ref);
                return null;
            }));
        }
        for (Future<?> f : launches) {
            f.get();
        }
        launchers.shutdown();

        int kills = 0;
        if (plan.killEvery() != null) {
            HostProcess victim = hosts.get(0);
            long next = System.nanoTime() + plan.killEvery().toNanos();
            // Every kill the plan has room for happens, late if it must: on a loaded machine a restart can outlast the
            // interval (a 12 s run with a kill every 5 s once got 1 kill, its restart taking 9 s).
            long planned = plan.duration().toNanos() / plan.killEvery().toNanos();
            while (System.currentTimeMillis() < endAt || kills < planned) {
                long wait = next - System.nanoTime();
                if (wait > 0 && System.currentTimeMillis() >= endAt) {
                    wait = 0;
                }
                if (wait > 0) {
                    // The kill schedule: a wait for time itself, not for a condition.
                    TimeUnit.NANOSECONDS.sleep(Math.min(wait, TimeUnit.MILLISECONDS.toNanos(Math.max(1, endAt - System.currentTimeMillis()))));
                    continue;
                }
                victim.kill();
                kills++;
                victim.restart();
                restarts.merge(victim, 1, Integer::sum);
                next += plan.killEvery().toNanos();
            }
        }

        long drainUntil = System.nanoTime() + plan.duration().toNanos() + plan.drain().toNanos();
        int home = 0;
        for (AgentRef r : refs) {
            try {
                r.result().get(Math.max(1, drainUntil - System.nanoTime()), TimeUnit.NANOSECONDS);
                home++;
            } catch (java.util.concurrent.TimeoutException e) {
                // lost (counted below)
            }
        }
        double seconds = (System.nanoTime() - started) / 1e9;

        long stopsRun = 0;
        long twice = 0;
        long lost = 0;
        long interrupted = 0;
        long unreachable = 0;
        for (AgentRef r : refs) {
            Map<String, Set<String>> byKey = reports.get(r);
            stopsRun += byKey.size();
            twice += byKey.values().stream().filter(nonces -> nonces.size() > 1).count();
            if (r.result().isDone() && !r.result().isCompletedExceptionally()) {
                @SuppressWarnings("unchecked")
                List<String> keys = (List<String>) (Serializable) r.result().join();
                lost += keys.stream().filter(k -> !byKey.containsKey(k)).count();
            }
            interrupted += r.history().stream().filter(v -> v.outcome() == Itinerary.Outcome.INTERRUPTED).count();
            unreachable += r.history().stream().filter(v -> v.outcome() == Itinerary.Outcome.UNREACHABLE).count();
        }

        settle(before);
        Map<HostProcess, HostFigures> after = figuresOfEachHost();
        List<HostRow> rows = new ArrayList<>();
        for (HostProcess h : hosts) {
            rows.add(new HostRow(h.address(), before.get(h), after.get(h), restarts.get(h)));
            heapDump(h, "after");
        }
        return new Figures(plan, refs.size(), home, stopsRun, twice, lost, duplicates.get(), interrupted, unreachable, kills, seconds, rows);
    }

    /** Takes every host's figures at once (each a jcmd JVM against its host): the hosts' order kept. */
    private Map<HostProcess, HostFigures> figuresOfEachHost() throws IOException {
        List<AtOnce.Step<HostFigures>> taking = new ArrayList<>();
        for (HostProcess h : hosts) {
            taking.add(new AtOnce.Step<>("taking the figures of " + h.address(), () -> HostFigures.of(h.pid())));
        }
        List<HostFigures> taken = AtOnce.all(taking, Duration.ofMinutes(3), f -> { });
        Map<HostProcess, HostFigures> figures = new LinkedHashMap<>();
        for (int i = 0; i < hosts.size(); i++) {
            figures.put(hosts.get(i), taken.get(i));
        }
        return figures;
    }

    /**
     * Waits (up to 90 s) until every host is back within the thread and file bounds of where it
     * started: a host's connections from its peers close 15 s after their last call (RMI's client
     * connection time-out), its connection threads 10 s after that, its pool and delivery threads
     * 10 s after their last work. What is measured after is what is left then.
     */
    private void settle(Map<HostProcess, HostFigures> before) throws IOException {
        long deadline = System.nanoTime() + TimeUnit.SECONDS.toNanos(90);
        for (HostProcess h : hosts) {
            HostFigures b = before.get(h);
            while (System.nanoTime() < deadline
                    && (HostFigures.threadsOf(h.pid()) > b.threads() + THREAD_BOUND || HostFigures.filesOf(h.pid()) > b.files() + FILE_BOUND)) {
                java.util.concurrent.locks.LockSupport.parkNanos(TimeUnit.MILLISECONDS.toNanos(200));
            }
        }
    }

    private static void heapDump(HostProcess h, String when) throws IOException {
        String dir = System.getProperty(HEAP_DUMPS);
        if (dir != null && !dir.isBlank()) {
            String host = h.address().substring(h.address().lastIndexOf('/') + 1);
            HostFigures.heapDump(h.pid(), Path.of(dir, host + "-" + when + "-" + h.pid() + ".hprof"));
        }
    }

    @Override
    public void close() {
        if (home != null) {
            home.close();
        }
        hosts.forEach(HostProcess::close);
    }

    /** @return where a host's log is */
    static Path logOf(String host) {
        return Path.of("target", "it-logs", host + ".log");
    }

    static String describe(Figures f) throws IOException {
        StringBuilder b = new StringBuilder();
        b.append(String.format("%s: %d agents, %d s%s, %d host JVMs: %d sent, %d home, %d lost; %d stops run, %d run twice; %d reports lost, %d duplicated;"
                        + " %d interrupted by kills, %d unreachable tries; %d kills; %.1f s%n",
                f.plan().name(), f.plan().agents(), f.plan().duration().toSeconds(), f.plan().killEvery() == null ? "" : ", kill -9 every "
                        + f.plan().killEvery().toSeconds() + " s", f.plan().hosts(), f.sent(), f.home(), f.lost(), f.stopsRun(), f.stopsRunTwice(),
                f.reportsLost(), f.reportsDuplicate(), f.interrupted(), f.unreachable(), f.kills(), f.seconds()));
        for (HostRow r : f.rows()) {
            b.append(String.format("  %s%s: before %s; after %s%n", r.host(), r.restarts() > 0 ? " (restarted " + r.restarts() + " times)" : "",
                    r.before(), r.after().detailed()));
        }
        return b.toString();
    }
}
