package io.robomw.cli;

import io.robomw.agents.messaging.MessagingNode;
import io.robomw.agents.messaging.discovery.BeaconRecord;
import picocli.CommandLine.Command;
import picocli.CommandLine.Mixin;
import picocli.CommandLine.Option;
import picocli.CommandLine.Parameters;
import picocli.CommandLine.Spec;
import picocli.CommandLine.Model.CommandSpec;

import java.io.PrintWriter;
import java.time.Duration;
import java.util.ArrayList;
import java.util.LinkedHashSet;
import java.util.List;
import java.util.Set;
import java.util.concurrent.Callable;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.Executors;
import java.util.concurrent.ScheduledExecutorService;
import java.util.concurrent.TimeUnit;

/**
 * {@code mw msg echo TOPIC}: prints a topic's messages and, every {@code --rate-period}, their
 * rate, like {@code ros2 topic echo} and {@code ros2 topic hz} together. The publishers are found
 * on the discovery group (their beacons say they publish TOPIC and where they receive), or given
 * with {@code --from}.
 */
@Command(mixinStandardHelpOptions = true, name = "echo", description = {"Print a topic's messages and their rate (like ros2 topic echo and hz).",
        "Publishers are found by their beacons (mw topics lists them), or given with --from ADDRESS."})
final class MsgEchoCommand implements Callable<Integer> {

    @Mixin
    private MsgCommand.Common common;

    @Mixin
    private BeaconOption beacon;

    @Parameters(index = "0", paramLabel = "TOPIC")
    private String topic;

    @Option(names = "--from", paramLabel = "ADDRESS", description = "a publisher's address (repeat for more); default: every node announced as publishing TOPIC")
    private List<String> from = new ArrayList<>();

    @Option(names = "--discover", defaultValue = "2500ms", description = "how long to listen for beacons when no --from is given (default ${DEFAULT-VALUE})")
    private Duration discover;

    @Option(names = "--count", defaultValue = "0", description = "exit after this many messages; 0 = until interrupted")
    private long count;

    @Option(names = "--timeout", defaultValue = "0", description = "exit with status 1 after this long (30s, 2m...); 0 = no limit")
    private Duration timeout;

    @Option(names = "--rate-period", defaultValue = "1s", description = "how often the rate is printed (default ${DEFAULT-VALUE})")
    private Duration ratePeriod;

    @Option(names = "--window", defaultValue = "100", description = "how many of the latest intervals the rate is over (default ${DEFAULT-VALUE})")
    private int window;

    @Option(names = "--no-messages", description = "print the rate only (ros2 topic hz)")
    private boolean noMessages;

    @Spec
    private CommandSpec spec;

    @Override
    public Integer call() throws Exception {
        PrintWriter out = spec.commandLine().getOut();
        PrintWriter err = spec.commandLine().getErr();
        Set<String> publishers = new LinkedHashSet<>(from);
        if (publishers.isEmpty()) {
            for (BeaconRecord n : NodesCommand.listen(beacon, discover)) {
                if (n.publishes().contains(topic)) {
                    n.messaging().stream().filter(a -> !a.startsWith("multicast")).findFirst().ifPresent(publishers::add);
                    n.messaging().stream().filter(a -> a.startsWith("multicast")).forEach(publishers::add);
                }
            }
            if (publishers.isEmpty()) {
                err.println("mw msg echo: no node announced on " + beacon.group + " publishes topic '" + topic + "' (mw topics lists what is announced);"
                        + " give --from ADDRESS");
                err.flush();
                return 1;
            }
        }
        RateMeter rate = new RateMeter(window);
        CountDownLatch done = new CountDownLatch(count == 0 ? 1 : (int) Math.min(count, Integer.MAX_VALUE));
        ScheduledExecutorService ticker = Executors.newSingleThreadScheduledExecutor(r -> {
            Thread t = new Thread(r, "mw-msg-echo-rate");
            t.setDaemon(true);
            return t;
        });
        try (MessagingNode node = MessagingNode.builder(common.name).settings(common.settings()).build();
             AutoCloseable announced = beacon.announce(node)) {
            node.addMessageListener(topic, common.password(), m -> {
                rate.arrived(System.nanoTime());
                if (!noMessages) {
                    synchronized (out) {
                        out.println(MsgCommand.describe(m));
                        out.flush();
                    }
                }
                if (count > 0) {
                    done.countDown();
                }
            });
            node.subscribeMessage(topic, common.password());
            for (String p : publishers) {
                if (MsgCommand.isGroup(p) || p.startsWith("mqtt")) {
                    node.bind(p);
                } else {
                    node.connect(p);
                }
            }
            synchronized (out) {
                out.println("echoing topic '" + topic + "' from " + String.join(" ", publishers));
                out.flush();
            }
            ticker.scheduleAtFixedRate(() -> {
                synchronized (out) {
                    out.println(rate.line());
                    out.flush();
                }
            }, ratePeriod.toMillis(), ratePeriod.toMillis(), TimeUnit.MILLISECONDS);
            boolean finished = timeout.isZero() ? await(done) : done.await(timeout.toNanos(), TimeUnit.NANOSECONDS);
            ticker.shutdownNow();
            synchronized (out) {
                out.println(rate.line());
                out.flush();
            }
            return finished ? 0 : 1;
        } finally {
            ticker.shutdownNow();
        }
    }

    private static boolean await(CountDownLatch done) throws InterruptedException {
        done.await();
        return true;
    }
}
