package io.robomw.cli;

import io.robomw.agents.host.AgentHost;
import io.robomw.api.Agent;
import io.robomw.api.AgentRef;
import picocli.CommandLine.Command;
import picocli.CommandLine.Mixin;
import picocli.CommandLine.Model.CommandSpec;
import picocli.CommandLine.Option;
import picocli.CommandLine.Parameters;
import picocli.CommandLine.Spec;

import java.io.PrintWriter;
import java.io.Serializable;
import java.net.URL;
import java.net.URLClassLoader;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.Callable;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.TimeoutException;

/**
 * {@code mw dispatch}: sends an agent class from a jar to agent hosts (a clone per host, or one
 * agent visiting them in turn), prints its reports and results as they come, and exits when all
 * results are home: 0 if every agent completed, 1 if one failed, 3 on time-out.
 */
@Command(name = "dispatch", mixinStandardHelpOptions = true,
        description = {"Sends an agent from a jar to agent hosts and prints its results as they come.",
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

    @Option(names = "--timeout", defaultValue = "PT2M", description = "how long to wait for results: 30s, 2m, ISO-8601... (default ${DEFAULT-VALUE})")
    Duration timeout;

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
            err.println("mw dispatch: no jar at " + jar);
            return 2;
        }
        try (URLClassLoader code = new URLClassLoader(new URL[] {jar.toUri().toURL()}, Agent.class.getClassLoader());
             AgentHost home = AgentHost.builder("dispatch-" + ProcessHandle.current().pid()).bind(bind).clusterKey(cluster.key())
                     .tls(cluster.tls()).start()) {
            Agent agent = instantiate(code);
            List<AgentRef> refs;
            if (clone) {
                refs = home.dispatchClones(agent, hosts.toArray(String[]::new));
            } else {
                hosts.forEach(h -> agent.itinerary().addStop(h));
                refs = List.of(home.startTrip(agent));
            }
            List<CompletableFuture<Boolean>> done = new ArrayList<>();
            for (int i = 0; i < refs.size(); i++) {
                AgentRef ref = refs.get(i);
                String label = clone ? hosts.get(i) : "agent " + ref.id().toString().substring(0, 8);
                synchronized (out) {
                    out.printf("sent %s %s to %s%n", agentClass, ref.id(), clone ? hosts.get(i) : String.join(" -> ", hosts));
                    out.flush();
                }
                ref.addReportListener(v -> {
                    synchronized (out) {
                        out.printf("[%s] %s%n", label, v);
                        out.flush();
                    }
                });
                done.add(ref.result().handle((Serializable result, Throwable failure) -> {
                    synchronized (out) {
                        if (failure != null) {
                            out.printf("[%s] FAILED: %s%n", label, failure.getCause() != null ? failure.getCause().getMessage() : failure.getMessage());
                        } else {
                            out.printf("[%s] result from %s:%n%s%n", label, ref.location(), ResultText.format(result, "  "));
                        }
                        out.flush();
                    }
                    return failure == null;
                }));
            }
            try {
                CompletableFuture.allOf(done.toArray(CompletableFuture[]::new)).get(timeout.toMillis(), TimeUnit.MILLISECONDS);
            } catch (TimeoutException e) {
                err.println("mw dispatch: not every result came home within " + timeout);
                return 3;
            }
            return done.stream().allMatch(CompletableFuture::join) ? 0 : 1;
        } catch (io.robomw.api.AgentException | IllegalArgumentException | java.io.IOException e) {
            err.println("mw dispatch: " + e.getMessage());
            return 2;
        }
    }

    private Agent instantiate(ClassLoader code) throws ReflectiveOperationException {
        Class<?> type;
        try {
            type = Class.forName(agentClass, true, code);
        } catch (ClassNotFoundException e) {
            throw new IllegalArgumentException("class " + agentClass + " is not in " + jar);
        }
        if (!Agent.class.isAssignableFrom(type)) {
            throw new IllegalArgumentException(agentClass + " does not extend " + Agent.class.getName());
        }
        Object o = arg == null ? type.getConstructor().newInstance() : type.getConstructor(String.class).newInstance(arg);
        return (Agent) o;
    }
}
