package io.robomw.cli;

import io.robomw.agents.host.AgentHost;
import io.robomw.api.Agent;
import io.robomw.api.AgentException;
import io.robomw.api.AgentRef;
import io.robomw.api.PartialDispatchException;
import picocli.CommandLine.Command;
import picocli.CommandLine.Mixin;
import picocli.CommandLine.Model.CommandSpec;
import picocli.CommandLine.Option;
import picocli.CommandLine.Parameters;
import picocli.CommandLine.Spec;

import java.io.PrintWriter;
import java.io.Serializable;
import java.lang.reflect.Constructor;
import java.lang.reflect.InvocationTargetException;
import java.lang.reflect.Modifier;
import java.net.URL;
import java.net.URLClassLoader;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.ArrayList;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Map;
import java.util.concurrent.Callable;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.TimeoutException;

/**
 * {@code mw dispatch}: sends an agent class from a jar to agent hosts (a clone per host, or one
 * agent visiting them in turn), prints its reports and results as they come, waits for every
 * agent that was sent (also when some hosts could not be reached), and ends with a summary of
 * every stop. It exits after the results it printed have been acknowledged to their hosts (its
 * home closes only once the calls that brought them have replied), so no host keeps owing them.
 *
 * <p>Exit status: 0 every agent that was sent completed; 1 one failed; 2 a usage error, or no
 * agent could be sent; 3 not every result came home in time (the summary says where each agent
 * was last seen); 4 with {@code --strict}, a stop was skipped (its host could not be reached, its
 * clone could not be sent, or its host stopped while it ran).
 */
@Command(name = "dispatch", mixinStandardHelpOptions = true,
        description = {"Sends an agent from a jar to agent hosts, prints its results as they come, and ends with a summary of every stop.",
                "Exit status: 0 all completed, 1 one failed, 2 usage error or nothing sent, 3 time-out, 4 --strict and a stop was skipped.",
                "Example: mw dispatch --jar my-agents.jar --agent org.example.Survey --clone rmi://127.0.0.1:1099/nxt rmi://127.0.0.1:1100/ft"})
final class DispatchCommand implements Callable<Integer> {

    @Option(names = "--jar", required = true, paramLabel = "JAR", description = "the jar with the agent's classes (it travels to the hosts)")
    Path jar;

    @Option(names = "--agent", required = true, paramLabel = "CLASS", description = "the agent class (a public no-argument constructor, or one taking a String with --arg)")
    String agentClass;

    @Option(names = "--arg", description = "text given to the agent's String constructor")
    String arg;

    @Option(names = "--clone", description = "send one clone to each host, in parallel (default: one agent visits the hosts in turn)")
    boolean clone;

    @Option(names = "--strict", description = "exit with status 4 when a stop was skipped: its host could not be reached, its clone not sent, or its host stopped while it ran")
    boolean strict;

    @Option(names = "--timeout", defaultValue = "PT2M", description = "how long to wait for results: 30s, 2m, ISO-8601... (default ${DEFAULT-VALUE})")
    Duration timeout;

    @Option(names = "--wait-hosts", defaultValue = "30s", paramLabel = "DURATION",
            description = "how long to wait for a host that does not answer yet (it may be starting: mw host ... & just before) before sending to it (default ${DEFAULT-VALUE}; 0: not at all)")
    Duration waitHosts;

    @Option(names = "--bind", defaultValue = "127.0.0.1", description = "address of this command's own home host, where results arrive (default ${DEFAULT-VALUE})")
    String bind;

    @Parameters(arity = "1..*", paramLabel = "HOST", description = "agent host addresses, rmi://host:port/name")
    List<String> hosts;

    @Mixin
    ClusterOptions cluster;

    @Spec
    CommandSpec spec;

    @Override
    public Integer call() throws Exception {
        PrintWriter out = spec.commandLine().getOut();
        PrintWriter err = spec.commandLine().getErr();
        if (!Files.isRegularFile(jar)) {
            err.println("mw dispatch: no jar at " + jar.toAbsolutePath());
            return 2;
        }
        try (URLClassLoader code = new URLClassLoader(new URL[] {jar.toUri().toURL()}, Agent.class.getClassLoader())) {
            Agent agent = instantiate(code);
            try (AgentHost home = AgentHost.builder("dispatch-" + ProcessHandle.current().pid()).bind(bind).clusterKey(cluster.key())
                    .tls(cluster.tls()).start()) {
                awaitHosts(clone ? hosts : hosts.subList(0, 1), err);
                return dispatch(home, agent, out, err);
            }
        } catch (AgentException | IllegalArgumentException | java.io.IOException e) {
            err.println("mw dispatch: " + Mw.oneLine(e));
            if (Mw.verbose(spec)) {
                e.printStackTrace(err);
            }
            return 2;
        }
    }

    /**
     * Waits (up to {@code --wait-hosts}) for the hosts the agents go to first to answer: a host
     * started in the background a moment before ({@code mw host ... &} pasted with this command)
     * refuses connections until it serves. A host that answers, refuses this peer, or still does not
     * answer at the deadline is sent to as it is (the summary then says what happened).
     */
    private void awaitHosts(List<String> first, PrintWriter err) throws java.io.IOException {
        if (waitHosts.isZero()) {
            return;
        }
        long deadline = System.nanoTime() + waitHosts.toNanos();
        try (io.robomw.agents.host.HostClient client = new io.robomw.agents.host.HostClient(cluster.keyOrTlsOnly(), cluster.tls() != null, 5_000)) {
            for (String host : first) {
                boolean said = false;
                while (true) {
                    try {
                        client.describe(host);
                        break;
                    } catch (java.io.IOException | RuntimeException e) {
                        String why = Mw.oneLine(e);
                        boolean notYet = why.contains("cannot connect to") || why.contains("timed out") || why.contains("Connection refused");
                        if (!notYet || System.nanoTime() - deadline > 0) {
                            break;
                        }
                        if (!said) {
                            err.println("mw dispatch: waiting up to " + Durations.format(waitHosts) + " for " + host + " to answer (" + why
                                    + "); a host started just before answers once it prints 'ready at'");
                            err.flush();
                            said = true;
                        }
                        java.util.concurrent.locks.LockSupport.parkNanos(200_000_000L); // the host starting: nothing to be woken by
                    }
                }
            }
        }
    }

    private int dispatch(AgentHost home, Agent agent, PrintWriter out, PrintWriter err) throws InterruptedException {
        List<TripSummary.Sent> sent = new ArrayList<>();
        Map<String, String> unsent = new LinkedHashMap<>();
        if (clone) {
            List<AgentRef> refs;
            try {
                refs = home.agency().dispatchClones(agent, hosts.toArray(String[]::new));
            } catch (PartialDispatchException e) {
                refs = e.sent();
                unsent.putAll(e.unsent());
            }
            List<String> went = hosts.stream().filter(h -> !unsent.containsKey(h)).toList();
            for (int i = 0; i < refs.size(); i++) {
                sent.add(new TripSummary.Sent(went.get(i), refs.get(i)));
            }
            unsent.forEach((h, why) -> {
                synchronized (out) {
                    out.printf("[%s] not sent: %s%n", h, TripSummary.flat(why));
                }
            });
        } else {
            hosts.forEach(h -> agent.itinerary().addStop(h));
            AgentRef ref = home.agency().startTrip(agent);
            sent.add(new TripSummary.Sent("agent " + ref.id().toString().substring(0, 8), ref));
        }
        List<CompletableFuture<Boolean>> done = new ArrayList<>();
        for (TripSummary.Sent s : sent) {
            AgentRef ref = s.ref();
            synchronized (out) {
                out.printf("sent %s %s to %s%n", agentClass, ref.id(), clone ? s.label() : String.join(" -> ", hosts));
                out.flush();
            }
            // Each line says where the agent was when it sent it (a clone travels on from its first host).
            String who = sent.size() > 1 ? " " + ref.id().toString().substring(0, 8) : "";
            ref.onReport((at, v) -> {
                synchronized (out) {
                    out.printf("[%s%s] %s%n", at, who, v);
                    out.flush();
                }
            });
            done.add(ref.result().handle((Serializable result, Throwable failure) -> {
                synchronized (out) {
                    io.robomw.api.Agent back = ref.status() == io.robomw.api.AgentStatus.RETRACTED ? ref.whenRetracted().getNow(null) : null;
                    if (back != null) {
                        out.printf("[%s%s] RETRACTED: its state came home:%n%s%n", ref.location(), who, ResultText.state(back, "  "));
                    } else if (failure != null) {
                        out.printf("[%s%s] FAILED: %s%n", ref.location(), who, Mw.oneLine(failure.getCause() != null ? failure.getCause() : failure));
                    } else {
                        out.printf("[%s%s] result:%n%s%n", ref.location(), who, ResultText.format(result, "  "));
                    }
                    out.flush();
                }
                return failure == null || ref.status() == io.robomw.api.AgentStatus.RETRACTED;
            }));
        }
        // Ctrl-C while agents travel: say what keeps going and how to stop the hosts owing this home their results.
        Thread interrupted = new Thread(() -> {
            long travelling = sent.stream().filter(x -> !x.ref().result().isDone()).count();
            if (travelling > 0) {
                err.printf("mw dispatch: stopped with %d agent(s) still travelling; their hosts owe their results to %s until delivered or expired."
                        + " Drop them with: mw agents --drop-owed %s HOST...%n", travelling, home.address(), home.address());
                err.flush();
            }
        }, "mw-dispatch-interrupted");
        Runtime.getRuntime().addShutdownHook(interrupted);
        boolean timedOut = false;
        try {
            CompletableFuture.allOf(done.toArray(CompletableFuture[]::new)).get(timeout.toMillis(), TimeUnit.MILLISECONDS);
        } catch (TimeoutException e) {
            timedOut = true;
        } catch (java.util.concurrent.ExecutionException e) {
            throw new IllegalStateException(e); // the handlers above never fail
        }
        try {
            Runtime.getRuntime().removeShutdownHook(interrupted);
        } catch (IllegalStateException shuttingDown) {
            // the JVM is already stopping: the hook runs
        }
        TripSummary summary = new TripSummary(sent, unsent, Mw.verbose(spec));
        synchronized (out) {
            summary.print(out, timedOut ? timeout : null);
            out.flush();
        }
        if (timedOut) {
            err.println("mw dispatch: not every result came home within " + timeout + " (the summary says where each agent was last seen); their hosts"
                    + " owe the rest to " + home.address() + " until it expires: mw agents --drop-owed " + home.address() + " HOST... drops them");
            return 3;
        }
        if (!done.stream().allMatch(CompletableFuture::join)) {
            return 1;
        }
        if (strict && summary.skippedStops() > 0) {
            err.println("mw dispatch: " + summary.skippedStops() + " stop(s) skipped, and --strict was given");
            return 4;
        }
        return 0;
    }

    /** @return the agent, made from its class in the jar; a clear error in one line when it cannot be */
    private Agent instantiate(ClassLoader code) {
        Class<?> type;
        try {
            type = Class.forName(agentClass, true, code);
        } catch (ClassNotFoundException e) {
            throw new IllegalArgumentException("class " + agentClass + " is not in " + jar);
        } catch (LinkageError e) {
            throw new IllegalArgumentException("class " + agentClass + " in " + jar + " cannot be loaded: " + e);
        }
        if (!Agent.class.isAssignableFrom(type)) {
            throw new IllegalArgumentException(agentClass + " does not extend " + Agent.class.getName());
        }
        if (Modifier.isAbstract(type.getModifiers())) {
            throw new IllegalArgumentException(agentClass + " is abstract: give a concrete agent class");
        }
        Constructor<?> constructor;
        try {
            constructor = arg == null ? type.getConstructor() : type.getConstructor(String.class);
        } catch (NoSuchMethodException e) {
            throw new IllegalArgumentException(agentClass + (arg == null
                    ? " has no public no-argument constructor (give --arg TEXT if it has a public constructor taking a String)"
                    : " has no public constructor taking a String (--arg was given; leave it out if it has a public no-argument one)"));
        }
        try {
            return (Agent) constructor.newInstance(arg == null ? new Object[0] : new Object[] {arg});
        } catch (InvocationTargetException e) {
            throw new IllegalArgumentException("the constructor of " + agentClass + " threw " + e.getCause(), e.getCause());
        } catch (ReflectiveOperationException e) {
            throw new IllegalArgumentException(agentClass + " cannot be made: " + e, e);
        }
    }
}
