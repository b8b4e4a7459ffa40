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

/**
 * {@code mw agents HOST}: lists the agents at an agent host; {@code mw agents --cluster BROKER}:
 * every host announced at an MQTT broker and its agents.
 */
@Command(name = "agents", mixinStandardHelpOptions = true, description = {"Lists the agents at an agent host,",
        "or with --cluster mqtt://BROKER every host announced there (mw host --announce or --serve mqtt://...) and its agents."})
final class AgentsCommand implements Callable<Integer> {

    @Parameters(paramLabel = "HOST", arity = "0..1", description = "the host's address, rmi://host:port/name")
    String host;

    @picocli.CommandLine.Option(names = "--cluster", paramLabel = "BROKER", description = "list every host announced at this broker, mqtt://host:port[/prefix]")
    String broker;

    @picocli.CommandLine.Option(names = "--wait", defaultValue = "3s", description = "how long to wait for the broker's answer with --cluster (default ${DEFAULT-VALUE})")
    java.time.Duration wait;

    @Mixin
    ClusterOptions cluster;

    @Spec
    CommandSpec spec;

    @Override
    public Integer call() throws Exception {
        PrintWriter out = spec.commandLine().getOut();
        if (broker != null) {
            return listCluster(out);
        }
        if (host == null) {
            spec.commandLine().getErr().println("mw agents: give a HOST (rmi://host:port/name) or --cluster mqtt://BROKER");
            return 2;
        }
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

    private int listCluster(PrintWriter out) {
        List<io.robomw.agents.messaging.PresenceRecord> all;
        try {
            all = io.robomw.agents.messaging.mqtt.BrokerDirectory.read(broker, wait);
        } catch (java.io.IOException | IllegalArgumentException e) {
            spec.commandLine().getErr().println("mw agents: " + e.getMessage());
            return 2;
        }
        List<io.robomw.agents.messaging.PresenceRecord> hosts = all.stream().filter(p -> p.host() != null).toList();
        out.printf("%d agent host%s at %s%n", hosts.size(), hosts.size() == 1 ? "" : "s", broker);
        for (io.robomw.agents.messaging.PresenceRecord p : hosts) {
            out.printf("%s  %s  %s  robot %s  since %s%n", p.host(), p.online() ? "online" : "offline", p.hostAddress(),
                    p.robots().isEmpty() ? "none" : String.join(",", p.robots()), p.time());
            for (String a : p.agents()) {
                out.printf("    %s%n", a);
            }
        }
        List<io.robomw.agents.messaging.PresenceRecord> others = all.stream().filter(p -> p.host() == null && p.online()).toList();
        if (!others.isEmpty()) {
            out.printf("%d other node%s online:%n", others.size(), others.size() == 1 ? "" : "s");
            for (io.robomw.agents.messaging.PresenceRecord p : others) {
                out.printf("    %s%s%n", p.node(), p.robots().isEmpty() ? "" : "  robots " + String.join(",", p.robots()));
            }
        }
        out.flush();
        return 0;
    }
}
