package io.robomw.cli;

import io.robomw.agents.messaging.MessagingNode;
import picocli.CommandLine.Command;
import picocli.CommandLine.Mixin;
import picocli.CommandLine.Option;
import picocli.CommandLine.Parameters;
import picocli.CommandLine.Spec;
import picocli.CommandLine.Model.CommandSpec;

import java.io.PrintWriter;
import java.time.Duration;
import java.util.concurrent.Callable;
import java.util.concurrent.locks.LockSupport;

/**
 * {@code mw msg pub ADDRESS TOPIC TEXT}: publishes TEXT on TOPIC. A tcp, udp or rmi ADDRESS is
 * bound (subscribers connect to it: {@code mw msg sub ADDRESS TOPIC}); a multicast ADDRESS is
 * joined. Repeats at {@code --rate} until {@code --count} publications (0: until interrupted).
 */
@Command(name = "pub", mixinStandardHelpOptions = true, description = "Publish text on a topic (binds tcp/udp/rmi addresses, joins multicast groups).")
final class MsgPubCommand implements Callable<Integer> {

    @Mixin
    private MsgCommand.Common common;

    @Parameters(index = "0", paramLabel = "ADDRESS", description = "where to publish, e.g. tcp://127.0.0.1:7000 or multicast://239.1.2.3:7002")
    private String address;

    @Parameters(index = "1", paramLabel = "TOPIC")
    private String topic;

    @Parameters(index = "2", paramLabel = "TEXT", description = "the payload (text)")
    private String text;

    @Option(names = "--function", defaultValue = "data", description = "the message function (default: ${DEFAULT-VALUE})")
    private String function;

    @Option(names = "--count", defaultValue = "1", description = "how many to publish; 0 = until interrupted (default: ${DEFAULT-VALUE})")
    private long count;

    @Option(names = "--rate", defaultValue = "1", description = "publications per second (default: ${DEFAULT-VALUE})")
    private double rate;

    @Option(names = "--wait-subscribers", defaultValue = "0", description = "wait until this many peers subscribe before publishing (tcp, udp, rmi; not through a broker)")
    private int waitSubscribers;

    @Option(names = "--wait-timeout", defaultValue = "30", description = "seconds to wait for --wait-subscribers (default: ${DEFAULT-VALUE})")
    private double waitTimeout;

    @Spec
    private CommandSpec spec;

    @Override
    public Integer call() {
        PrintWriter out = spec.commandLine().getOut();
        if (rate <= 0) {
            spec.commandLine().getErr().println("--rate must be > 0, got " + rate);
            return 2;
        }
        if (waitSubscribers > 0 && address.startsWith("mqtt")) {
            spec.commandLine().getErr().println("--wait-subscribers counts peers connected to this publisher; through a broker (" + address
                    + ") subscribers connect to the broker, which does not say who they are: leave it out (a subscriber with a persistent"
                    + " session gets what was published while it was away)");
            return 2;
        }
        try (MessagingNode node = MsgCommand.bound(common, address)) {
            out.println("publishing on " + node.boundAddresses().get(0) + " topic '" + topic + "'");
            out.flush();
            long deadline = System.nanoTime() + Duration.ofMillis((long) (waitTimeout * 1000)).toNanos();
            while (node.subscriberCount(topic) < waitSubscribers) {
                if (System.nanoTime() > deadline) {
                    spec.commandLine().getErr().println("only " + node.subscriberCount(topic) + " of " + waitSubscribers + " subscribers came within " + waitTimeout + " s");
                    return 1;
                }
                LockSupport.parkNanos(10_000_000);
            }
            long period = (long) (1e9 / rate);
            long next = System.nanoTime();
            for (long i = 0; count == 0 || i < count; i++) {
                node.publishMessage(topic, text, function, common.password);
                out.println("published #" + (i + 1) + ": " + text);
                out.flush();
                next += period;
                if (count != 0 && i + 1 == count) {
                    break;
                }
                long wait = next - System.nanoTime();
                if (wait > 0) {
                    LockSupport.parkNanos(wait);
                }
                if (Thread.currentThread().isInterrupted()) {
                    break;
                }
            }
        }
        return 0;
    }
}
