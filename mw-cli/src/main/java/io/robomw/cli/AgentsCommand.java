package io.robomw.cli;

import io.robomw.agents.host.AgentInfo;
import io.robomw.agents.host.HostClient;
import io.robomw.agents.host.OwedDelivery;
import io.robomw.agents.host.OwedSelector;
import picocli.CommandLine.Command;
import picocli.CommandLine.Mixin;
import picocli.CommandLine.Model.CommandSpec;
import picocli.CommandLine.Option;
import picocli.CommandLine.Parameters;
import picocli.CommandLine.Spec;

import java.io.IOException;
import java.io.PrintWriter;
import java.time.Duration;
import java.time.Instant;
import java.util.List;
import java.util.UUID;
import java.util.concurrent.Callable;

/**
 * {@code mw agents HOST...}: lists the agents at agent hosts and what each owes agents' homes
 * (reports and results not delivered yet, with their age); {@code --drop-owed} drops those.
 * Exit status 0 when every host answered, 1 when one could not be reached. {@code mw agents
 * --cluster BROKER}: every host announced at an MQTT broker and its agents.
 */
@Command(name = "agents", mixinStandardHelpOptions = true,
        description = {"Lists the agents at agent hosts and the deliveries each owes agents' homes,",
                "or with --cluster mqtt://BROKER every host announced there (mw host --announce or --serve mqtt://...) and its agents.",
                "Example: mw agents rmi://127.0.0.1:1099/nxt rmi://127.0.0.1:1100/ft",
                "         mw agents --drop-owed rmi://127.0.0.1:41234/dispatch-4711 rmi://127.0.0.1:1099/nxt"})
final class AgentsCommand implements Callable<Integer> {

    @Parameters(arity = "0..*", paramLabel = "HOST", description = "the hosts' addresses, rmi://host:port/name")
    List<String> hosts = new java.util.ArrayList<>();

    @Option(names = "--cluster", paramLabel = "BROKER", description = "list every host announced at this broker, mqtt://host:port[/prefix]")
    String broker;

    @Option(names = "--wait", defaultValue = "3", description = "seconds to wait for the broker's answer with --cluster (default ${DEFAULT-VALUE})")
    double waitSeconds;

    @Option(names = "--drop-owed", paramLabel = "all|AGENT-ID|HOME", description = "drop the deliveries these hosts owe: all of them, those of one"
            + " agent, or those owed to one home (rmi://...); for a home that is gone for good, rather than wait for their expiry")
    String dropOwed;

    @Mixin
    ClusterOptions cluster;

    @Spec
    CommandSpec spec;

    @Override
    public Integer call() throws Exception {
        PrintWriter out = spec.commandLine().getOut();
        PrintWriter err = spec.commandLine().getErr();
        if (broker != null) {
            return listCluster(out);
        }
        if (hosts.isEmpty()) {
            err.println("mw agents: give a HOST (rmi://host:port/name) or --cluster mqtt://BROKER");
            return 2;
        }
        OwedSelector drop = dropOwed == null ? null : selector(dropOwed);
        int unreachable = 0;
        try (HostClient client = new HostClient(cluster.keyOrTlsOnly(), cluster.tls() != null, 10_000)) {
            for (String host : hosts) {
                try {
                    if (drop != null) {
                        List<OwedDelivery> dropped = client.dropOwed(host, drop);
                        out.printf("%s dropped %d owed deliver%s (%s)%n", host, dropped.size(), dropped.size() == 1 ? "y" : "ies", drop);
                        printOwed(out, dropped);
                    } else {
                        printHost(out, host, client.agents(host), client.owed(host));
                    }
                } catch (IOException | IllegalArgumentException e) {
                    err.printf("mw agents: %s: %s%n", host, Mw.oneLine(e));
                    unreachable++;
                }
                out.flush();
            }
        }
        err.flush();
        return unreachable == 0 ? 0 : 1;
    }

    private int listCluster(PrintWriter out) {
        List<io.robomw.agents.messaging.PresenceRecord> all;
        try {
            all = io.robomw.agents.messaging.mqtt.BrokerDirectory.read(broker, java.time.Duration.ofMillis((long) (waitSeconds * 1000)));
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

    private static OwedSelector selector(String text) {
        if (text.equalsIgnoreCase("all")) {
            return OwedSelector.all();
        }
        if (text.startsWith("rmi://")) {
            return OwedSelector.home(text);
        }
        try {
            return OwedSelector.agent(UUID.fromString(text));
        } catch (IllegalArgumentException e) {
            throw new IllegalArgumentException("--drop-owed takes all, an agent id or a home address (rmi://host:port/name), not '" + text + "'");
        }
    }

    private static void printHost(PrintWriter out, String host, List<AgentInfo> agents, List<OwedDelivery> owed) {
        out.printf("%d agent%s at %s%n", agents.size(), agents.size() == 1 ? "" : "s", host);
        if (!agents.isEmpty()) {
            out.printf("  %-36s  %-10s  %4s  %-40s  %s%n", "ID", "STATUS", "HOP", "CLASS", "HOME");
            for (AgentInfo a : agents) {
                out.printf("  %-36s  %-10s  %4d  %-40s  %s%n", a.id(), a.status(), a.hop(), a.className(), a.home());
            }
        }
        out.printf("%d deliver%s owed by %s%n", owed.size(), owed.size() == 1 ? "y" : "ies", host);
        printOwed(out, owed);
    }

    private static void printOwed(PrintWriter out, List<OwedDelivery> owed) {
        if (owed.isEmpty()) {
            return;
        }
        out.printf("  %-36s  %5s  %-8s  %-9s  %5s  %-40s  %s%n", "AGENT", "EVENT", "KIND", "AGE", "TRIES", "HOME", "LAST ERROR");
        Instant now = Instant.now();
        for (OwedDelivery d : owed) {
            out.printf("  %-36s  %5d  %-8s  %-9s  %5d  %-40s  %s%n", d.agent(), d.seq(), d.kind(), age(Duration.between(d.owedSince(), now)), d.attempts(),
                    d.home(), TripSummary.flat(d.lastError()));
        }
    }

    /** @return a duration as people read it: 42s, 3m05s, 2h10m, 3d04h */
    static String age(Duration d) {
        long s = Math.max(0, d.toSeconds());
        if (s < 60) {
            return s + "s";
        }
        if (s < 3600) {
            return String.format("%dm%02ds", s / 60, s % 60);
        }
        if (s < 86_400) {
            return String.format("%dh%02dm", s / 3600, s % 3600 / 60);
        }
        return String.format("%dd%02dh", s / 86_400, s % 86_400 / 3600);
    }
}
