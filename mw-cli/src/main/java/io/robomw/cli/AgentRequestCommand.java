package io.robomw.cli;

import io.robomw.agents.host.ops.HostClient;
import picocli.CommandLine.Mixin;
import picocli.CommandLine.Model.CommandSpec;
import picocli.CommandLine.Parameters;
import picocli.CommandLine.Spec;

import java.io.IOException;
import java.io.PrintWriter;
import java.util.ArrayList;
import java.util.List;
import java.util.UUID;
import java.util.concurrent.Callable;

/**
 * What {@code mw retract} and {@code mw dispose} share: find an agent from the hosts given (each
 * request follows it from a host it left to where it went) and ask it. Exit status 0 once a host
 * took the request, 1 when none of the hosts knew the agent.
 */
abstract class AgentRequestCommand implements Callable<Integer> {

    @Parameters(index = "0", paramLabel = "ID", description = "the agent's id (mw dispatch and mw agents print it)")
    UUID id;

    @Parameters(index = "1..*", arity = "1..*", paramLabel = "HOST", description = "hosts where the agent is or was, rmi://host:port/name; each is asked in turn")
    List<String> hosts;

    @Mixin
    ClusterOptions cluster;

    @Spec
    CommandSpec spec;

    /** Asks the agent through the host where it is now. */
    abstract HostClient.Taken ask(HostClient client, String host) throws IOException;

    /** @return what the request does, after "agent ID ... at HOST" */
    abstract String effect();

    @Override
    public Integer call() throws Exception {
        PrintWriter out = spec.commandLine().getOut();
        PrintWriter err = spec.commandLine().getErr();
        List<String> misses = new ArrayList<>();
        try (HostClient client = new HostClient(cluster.keyOrTlsOnly(), cluster.tls() != null, 10_000)) {
            for (String host : hosts) {
                try {
                    HostClient.Taken taken = ask(client, host);
                    out.printf("agent %s %s at %s%s%n", id, effect(), taken.host(), taken.hops() > 0 ? " (followed from " + host + ")" : "");
                    out.flush();
                    return 0;
                } catch (IOException | IllegalArgumentException e) {
                    misses.add(host + ": " + Mw.oneLine(e));
                }
            }
        }
        err.printf("%s: no host given knows agent %s%n", spec.qualifiedName(), id);
        misses.forEach(m -> err.println("  " + m));
        err.flush();
        return 1;
    }
}
