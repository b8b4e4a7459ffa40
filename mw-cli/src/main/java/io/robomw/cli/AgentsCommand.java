package io.robomw.cli;

import io.robomw.agents.host.AgentInfo;
import io.robomw.agents.host.ClusterKey;
import io.robomw.agents.host.HostClient;
import io.robomw.agents.host.OwedDelivery;
import io.robomw.agents.host.OwedSelector;
import io.robomw.agents.messaging.PresenceRecord;
import io.robomw.agents.messaging.MessagingNode;
import io.robomw.agents.messaging.mqtt.BrokerDirectory;
import io.robomw.agents.messaging.security.ReplayStore;
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
import java.util.ArrayList;
import java.util.List;
import java.util.Optional;
import java.util.UUID;
import java.util.concurrent.Callable;

/**
 * {@code mw agents HOST...}: lists the agents at agent hosts and what each owes agents' homes
 * (reports and results not delivered yet, with their age); {@code --drop-owed} drops those.
 * {@code mw agents --cluster BROKER}: every host announced at an MQTT broker and its agents, and,
 * when the command has the cluster key, what each host online owes (asked of the host itself;
 * {@code --drop-owed} drops it at every one). Exit status 0 when every host asked answered, 1 when
 * one could not be reached, 2 on a usage error or a broker that cannot be read.
 */
@Command(name = "agents", mixinStandardHelpOptions = true,
        description = {"Lists the agents at agent hosts and the deliveries each owes agents' homes,",
                "or with --cluster mqtt://BROKER every host announced there (mw host --announce or --serve mqtt://...), its agents",
                "and, with the cluster key, the deliveries each host online owes.",
                "Example: mw agents rmi://127.0.0.1:1099/nxt rmi://127.0.0.1:1100/ft",
                "         mw agents --drop-owed rmi://127.0.0.1:41234/dispatch-4711 rmi://127.0.0.1:1099/nxt",
                "         mw agents --cluster mqtt://127.0.0.1:1883 --key-file cluster.key"})
final class AgentsCommand implements Callable<Integer> {

    @Parameters(arity = "0..*", paramLabel = "HOST", description = "the hosts' addresses, rmi://host:port/name")
    List<String> hosts = new ArrayList<>();

    @Option(names = "--cluster", paramLabel = "BROKER", description = "the hosts announced at this broker, mqtt://host:port[/prefix]")
    String broker;

    @Option(names = "--wait", defaultValue = "3s", description = "how long to wait for the broker's answer with --cluster: 3, 500ms, 2m, ISO-8601... (default ${DEFAULT-VALUE})")
    Duration wait;

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
        OwedSelector drop = dropOwed == null ? null : selector(dropOwed);
        if (broker != null) {
            if (!hosts.isEmpty()) {
                err.println("mw agents: give HOST addresses or --cluster BROKER, not both");
                return 2;
            }
            return listCluster(out, err, drop);
        }
        if (hosts.isEmpty()) {
            err.println("mw agents: give a HOST (rmi://host:port/name) or --cluster mqtt://BROKER");
            return 2;
        }
        int unreachable = 0;
        try (HostClient client = client(cluster.keyOrTlsOnly())) {
            for (String host : hosts) {
                unreachable += askHost(client, host, null, drop, out, err) ? 0 : 1;
            }
        }
        err.flush();
        return unreachable == 0 ? 0 : 1;
    }

    private HostClient client(ClusterKey key) {
        return new HostClient(key, cluster.tls() != null, 10_000);
    }

    /**
     * Lists (or drops) what one host holds and owes; prints why not if it cannot be asked.
     *
     * @param indent {@code null} for a host given on the command line (its agents are listed too), or the
     *               indent under a host listed from its presence (its agents are listed from that)
     * @return whether the host answered
     */
    private boolean askHost(HostClient client, String host, String indent, OwedSelector drop, PrintWriter out, PrintWriter err) {
        String in = indent == null ? "" : indent;
        try {
            if (drop != null) {
                List<OwedDelivery> dropped = client.dropOwed(host, drop);
                out.printf("%s%s dropped %d owed deliver%s (%s)%n", in, host, dropped.size(), dropped.size() == 1 ? "y" : "ies", drop);
                printOwed(out, in, dropped);
            } else {
                if (indent == null) {
                    printAgents(out, host, client.agents(host));
                }
                List<OwedDelivery> owed = client.owed(host);
                out.printf("%s%d deliver%s owed by %s%n", in, owed.size(), owed.size() == 1 ? "y" : "ies", host);
                printOwed(out, in, owed);
            }
            return true;
        } catch (IOException | IllegalArgumentException e) {
            // One line per host that does not answer, with the listing: which, since when we know, and why.
            out.printf("%s%s  DOWN  (no answer at %s)  %s%n", in, host, Instant.now().truncatedTo(java.time.temporal.ChronoUnit.SECONDS), why(host, e));
            return false;
        } finally {
            out.flush();
        }
    }

    private int listCluster(PrintWriter out, PrintWriter err, OwedSelector drop) throws IOException {
        Optional<ClusterKey> key = cluster.keyIfAny();
        List<PresenceRecord> all;
        long ignored;
        long stale;
        // With the cluster key, only what the cluster's hosts signed is listed; anything else is ignored and counted, and so is
        // a signed presence older than one this user's mw agents took before (a replay: its window is kept across runs).
        try (BrokerDirectory d = BrokerDirectory.open(broker, wait, null, key.map(ClusterKey::presenceSeal).orElse(null),
                ReplayStore.fileFor(MessagingNode.defaultReplayDirectory(), "mw-agents.presence"))) {
            d.awaitQuiet(wait);
            all = d.records();
            ignored = d.ignored();
            stale = d.stale();
        } catch (IOException | IllegalArgumentException e) {
            err.println("mw agents: " + Mw.oneLine(e));
            return 2;
        }
        if (drop != null && key.isEmpty()) {
            err.println("mw agents: --drop-owed asks each host: give the cluster key (--key-file FILE or " + ClusterOptions.KEY_VARIABLE + ")");
            return 2;
        }
        List<PresenceRecord> agentHosts = all.stream().filter(p -> p.host() != null).toList();
        out.printf("%d agent host%s at %s%n", agentHosts.size(), agentHosts.size() == 1 ? "" : "s", broker);
        int unreachable = 0;
        try (HostClient client = key.map(this::client).orElse(null)) {
            for (PresenceRecord p : agentHosts) {
                out.printf("%s  %s  %s  robot %s%s%n", p.host(), p.online() ? "online" : "offline since " + p.time().truncatedTo(java.time.temporal.ChronoUnit.SECONDS),
                        p.hostAddress(), robot(client, p), p.online() ? "" : "  (it left the broker" + (p.agents().isEmpty() ? ")" : "; last listed agents below)"));
                for (String a : p.agents()) {
                    out.printf("    %s%n", a);
                }
                if (client != null && p.online()) {
                    unreachable += askHost(client, p.hostAddress(), "  ", drop, out, err) ? 0 : 1;
                }
            }
        }
        if (key.isEmpty() && !agentHosts.isEmpty()) {
            out.println("(unverified: give the cluster key, --key-file FILE or " + ClusterOptions.KEY_VARIABLE
                    + ", to list only what the cluster's hosts signed and the deliveries each host owes)");
        }
        if (ignored > 0) {
            out.printf("%d presence record%s ignored: unsigned, or not signed with this cluster key%n", ignored, ignored == 1 ? "" : "s");
        }
        if (stale > 0) {
            out.printf("%d signed presence record%s ignored: older than one taken before (replayed at the broker)%n", stale, stale == 1 ? "" : "s");
        }
        List<PresenceRecord> others = all.stream().filter(p -> p.host() == null && p.online()).toList();
        if (!others.isEmpty()) {
            out.printf("%d other node%s online:%n", others.size(), others.size() == 1 ? "" : "s");
            for (PresenceRecord p : others) {
                out.printf("    %s%s%n", p.node(), p.robots().isEmpty() ? "" : "  robots " + String.join(",", p.robots()));
            }
        }
        out.flush();
        err.flush();
        return unreachable == 0 ? 0 : 1;
    }

    /**
     * @return the robot a host drives: asked of the host (its DESCRIBE) when the command has the key
     *         and the host is online, else the robots its presence says it serves, else what is unknown
     */
    private static String robot(HostClient client, PresenceRecord p) {
        if (client != null && p.online()) {
            try {
                String r = client.describe(p.hostAddress()).robot();
                return r.isEmpty() ? "none" : r;
            } catch (IOException e) {
                // said below, when the host is asked what it owes
            }
        }
        if (!p.robots().isEmpty()) {
            return String.join(",", p.robots());
        }
        return client == null ? "? (served robots only; give the cluster key to ask the host)" : "?";
    }

    /** @return why a host did not answer, in words: the connection's own reason, without RMI's wrapping */
    private static String why(String host, Exception e) {
        String text = Mw.oneLine(e);
        String prefix = "cannot reach agent host " + host + ": ";
        return text.startsWith(prefix) ? text.substring(prefix.length()) : text;
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

    private static void printAgents(PrintWriter out, String host, List<AgentInfo> agents) {
        out.printf("%d agent%s at %s%n", agents.size(), agents.size() == 1 ? "" : "s", host);
        if (!agents.isEmpty()) {
            out.printf("  %-36s  %-25s  %4s  %-40s  %s%n", "ID", "STATUS", "HOP", "CLASS", "HOME");
            for (AgentInfo a : agents) {
                out.printf("  %-36s  %-25s  %4d  %-40s  %s%n", a.id(), a.state(), a.hop(), a.className(), a.home());
            }
        }
    }

    private static void printOwed(PrintWriter out, String indent, List<OwedDelivery> owed) {
        if (owed.isEmpty()) {
            return;
        }
        out.printf("%s  %-36s  %5s  %-8s  %-9s  %5s  %-40s  %s%n", indent, "AGENT", "EVENT", "KIND", "AGE", "TRIES", "HOME", "LAST ERROR");
        Instant now = Instant.now();
        for (OwedDelivery d : owed) {
            out.printf("%s  %-36s  %5d  %-8s  %-9s  %5d  %-40s  %s%n", indent, d.agent(), d.seq(), d.kind(), age(Duration.between(d.owedSince(), now)),
                    d.attempts(), d.home(), TripSummary.flat(d.lastError()));
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
