package io.robomw.cli;

import io.robomw.agents.host.AgentHost;
import io.robomw.agents.host.AgentInfo;
import picocli.CommandLine.Command;
import picocli.CommandLine.Mixin;
import picocli.CommandLine.Model.CommandSpec;
import picocli.CommandLine.Parameters;
import picocli.CommandLine.Spec;

import java.io.PrintWriter;
import java.util.List;
import java.util.concurrent.Callable;

/** {@code mw agents HOST}: lists the agents at an agent host. */
@Command(name = "agents", mixinStandardHelpOptions = true, description = "Lists the agents at an agent host.")
final class AgentsCommand implements Callable<Integer> {

    @Parameters(paramLabel = "HOST", description = "the host's address, rmi://host:port/name")
    String host;

    @Mixin
    ClusterOptions cluster;

    @Spec
    CommandSpec spec;

    @Override
    public Integer call() throws Exception {
        PrintWriter out = spec.commandLine().getOut();
        List<AgentInfo> agents;
        try {
            agents = AgentHost.list(host, cluster.key() == null ? io.robomw.agents.host.ClusterKey.tlsOnly() : cluster.key(), cluster.tls() != null);
        } catch (java.io.IOException | IllegalArgumentException e) {
            spec.commandLine().getErr().println("mw agents: " + e.getMessage());
            return 2;
        }
        out.printf("%d agent%s at %s%n", agents.size(), agents.size() == 1 ? "" : "s", host);
        if (!agents.isEmpty()) {
            out.printf("%-36s  %-10s  %4s  %-40s  %s%n", "ID", "STATUS", "HOP", "CLASS", "HOME");
            for (AgentInfo a : agents) {
                out.printf("%-36s  %-10s  %4d  %-40s  %s%n", a.id(), a.status(), a.hop(), a.className(), a.home());
            }
        }
        out.flush();
        return 0;
    }
}
