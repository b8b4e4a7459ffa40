package io.robomw.cli;

import io.robomw.agents.messaging.discovery.BeaconRecord;
import picocli.CommandLine.Command;
import picocli.CommandLine.Mixin;
import picocli.CommandLine.Model.CommandSpec;
import picocli.CommandLine.Option;
import picocli.CommandLine.Spec;

import java.io.PrintWriter;
import java.time.Duration;
import java.util.List;
import java.util.Map;
import java.util.TreeMap;
import java.util.TreeSet;
import java.util.concurrent.Callable;

/**
 * {@code mw topics}: the topics the announced nodes publish on and listen to, with who does,
 * like {@code ros2 topic list -v}.
 */
@Command(mixinStandardHelpOptions = true, name = "topics", description = {"List the topics announced nodes publish on and listen to, and which nodes. Like ros2 topic list -v.",
        "Then: mw msg echo TOPIC."})
final class TopicsCommand implements Callable<Integer> {

    @Mixin
    BeaconOption beacon;

    @Option(names = "--wait", defaultValue = "2500ms", description = "how long to listen for beacons (default ${DEFAULT-VALUE})")
    Duration wait;

    @Spec
    CommandSpec spec;

    @Override
    public Integer call() {
        PrintWriter out = spec.commandLine().getOut();
        List<BeaconRecord> nodes = NodesCommand.listen(beacon, wait);
        Map<String, TreeSet<String>> publishers = new TreeMap<>();
        Map<String, TreeSet<String>> listeners = new TreeMap<>();
        for (BeaconRecord n : nodes) {
            n.publishes().forEach(t -> publishers.computeIfAbsent(t, k -> new TreeSet<>()).add(n.node()));
            n.listens().forEach(t -> listeners.computeIfAbsent(t, k -> new TreeSet<>()).add(n.node()));
        }
        TreeSet<String> topics = new TreeSet<>(publishers.keySet());
        topics.addAll(listeners.keySet());
        out.printf("%d topic%s on %s (%d node%s)%n", topics.size(), topics.size() == 1 ? "" : "s", beacon.group, nodes.size(), nodes.size() == 1 ? "" : "s");
        for (String t : topics) {
            out.printf("%s  published by %s; listened to by %s%n", t, String.join(",", publishers.getOrDefault(t, new TreeSet<>(List.of("nobody")))),
                    String.join(",", listeners.getOrDefault(t, new TreeSet<>(List.of("nobody")))));
        }
        out.flush();
        return 0;
    }
}
