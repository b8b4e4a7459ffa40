package io.robomw.cli;

import io.robomw.console.Console;
import io.robomw.console.observe.WorldMap;
import io.robomw.sim.world.WorldDescription;
import io.robomw.sim.world.WorldLoader;
import picocli.CommandLine.Command;
import picocli.CommandLine.Mixin;
import picocli.CommandLine.Model.CommandSpec;
import picocli.CommandLine.Option;
import picocli.CommandLine.Spec;

import java.io.PrintWriter;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.Callable;

/**
 * {@code mw console}: the live page for agent hosts and served robots, until Ctrl-C. Prints
 * {@code console at http://...} (the address with the access token its buttons need).
 */
@Command(name = "console", mixinStandardHelpOptions = true,
        description = {"A live web page of agent hosts (their agents, itineraries, reports) and robots served over messaging (pose on the map, sensors).",
                "Example: mw console --host rmi://127.0.0.1:1099/nxt --robot tcp://127.0.0.1:7000/nxt --world examples/worlds/arena.yaml --key-file cluster.key"})
final class ConsoleCommand implements Callable<Integer> {

    @Mixin
    WatchOptions watch;

    @Option(names = "--bind", defaultValue = "127.0.0.1", description = "address the page listens on (default ${DEFAULT-VALUE}: this machine only)")
    String bind;

    @Option(names = "--port", defaultValue = "8080", description = "the page's port (default ${DEFAULT-VALUE}, or a free one when it is taken; 0 picks a free one)")
    int port;

    @Option(names = "--record", paramLabel = "FILE.mcap", description = "also record what the console sees (Foxglove opens it; mw replay plays it)")
    Path record;

    @Mixin
    FoxgloveOption foxglove;

    @Spec
    CommandSpec spec;

    @Override
    public Integer call() throws Exception {
        PrintWriter out = spec.commandLine().getOut();
        Console.Builder b = foxglove.apply(watch.apply(Console.builder("mw " + String.join(" ", spec.commandLine().getParseResult().originalArgs())))
                .page(bind, PagePort.choose(bind, port, spec.commandLine().getParseResult().hasMatchedOption("--port"), spec.commandLine().getErr(),
                        "mw console")).record(record));
        return Waiting.runUntilStopped(b, out, spec.commandLine().getErr(), "mw console");
    }

    /** What {@code mw console} and {@code mw record} watch. */
    static final class WatchOptions {
        @Option(names = "--host", paramLabel = "ADDRESS", description = "an agent host to watch, rmi://HOST:PORT/NAME (repeat for more)")
        List<String> hosts = new ArrayList<>();

        @Option(names = "--robot", paramLabel = "ADDRESS", description = "a robot served with mw host --serve, e.g. tcp://127.0.0.1:7000/nxt (repeat for more)")
        List<String> robots = new ArrayList<>();

        @Option(names = "--world", paramLabel = "WORLD.yaml", description = "the world the robots live in, drawn as the map")
        Path world;

        @Option(names = "--discover", description = "also watch the hosts the watched hosts know (the cluster's directory, from each host's DESCRIBE)")
        boolean discover;

        @Option(names = "--period", defaultValue = "500ms", description = "how often hosts are asked: 500ms, 1s... (robots twice as often; default ${DEFAULT-VALUE})")
        java.time.Duration period;

        /** The option's former spelling, in milliseconds; still read. */
        @Option(names = "--period-ms", hidden = true)
        void periodMillis(long millis) {
            period = java.time.Duration.ofMillis(millis);
        }

        @Mixin
        ClusterOptions cluster;

        Console.Builder apply(Console.Builder b) throws java.io.IOException {
            if (world != null) {
                WorldDescription d = new WorldLoader().load(world);
                io.robomw.config.description.RobotDescriptionLoader loader = new io.robomw.config.description.RobotDescriptionLoader();
                b.world(WorldMap.of(d, d.robots().stream().map(r -> {
                    io.robomw.config.description.Body body = loader.load(r.description()).body();
                    return new WorldMap.RobotMark(r.name(), body.length(), body.width(), r.start().x(), r.start().y(), r.start().heading());
                }).toList()));
                b.about("world", world.toString());
            }
            if (period.toMillis() < 50 || period.toMillis() > 60_000) {
                throw new IllegalArgumentException("--period must be 50ms to 1m, got " + Durations.format(period));
            }
            b.hosts(hosts).robots(robots).period(period);
            if (discover) {
                b.discover();
            }
            if (!hosts.isEmpty()) {
                b.clusterKey(cluster.key(), cluster.tls() != null);
            } else {
                b.clusterKey(null, false);
            }
            return b;
        }
    }
}
