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
 * Like {@code ros2 topic pub --times N}, a bound publisher first waits for a subscriber (up to
 * {@code --wait-timeout}), so the first publication is not lost; it says how many subscribers
 * each publication had, and when it had none.
 */
@Command(name = "pub", mixinStandardHelpOptions = true, description = "Publish text on a topic (binds tcp/udp/rmi addresses, joins multicast groups).")
final class MsgPubCommand implements Callable<Integer> {

    @Mixin
    private MsgCommand.Common common;

    @Mixin
    private BeaconOption beacon;

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

    @Option(names = "--wait-subscribers", paramLabel = "N", description = "wait until N peers subscribe before publishing (tcp, udp, rmi; default: 1 with a --count,"
            + " 0 with --count 0, multicast or a broker, which cannot tell who subscribes)")
    private Integer waitSubscribers;

    @Option(names = "--wait-timeout", defaultValue = "60s", description = "how long to wait for them: 10, 500ms, 2m... (default: ${DEFAULT-VALUE})")
    private Duration waitTimeout;

    @Spec
    private CommandSpec spec;

    @Override
    public Integer call() throws Exception {
        PrintWriter out = spec.commandLine().getOut();
        PrintWriter err = spec.commandLine().getErr();
        if (rate <= 0) {
            err.println("mw msg pub: --rate must be > 0, got " + rate);
            return 2;
        }
        boolean countable = !address.startsWith("mqtt") && !MsgCommand.isGroup(address);
        if (waitSubscribers != null && waitSubscribers > 0 && !countable) {
            err.println(address.startsWith("mqtt")
                    ? "mw msg pub: --wait-subscribers counts peers connected to this publisher; through a broker (" + address
                    + ") subscribers connect to the broker, which does not say who they are: leave it out (a subscriber with a persistent"
                    + " session gets what was published while it was away)"
                    : "mw msg pub: --wait-subscribers cannot count the members of a multicast group (" + address + "): leave it out");
            return 2;
        }
        int wanted = waitSubscribers != null ? waitSubscribers : countable && count > 0 ? 1 : 0;
        try (MessagingNode node = MsgCommand.bound(common, address);
             AutoCloseable announced = beacon.announce(node)) {
            node.advertise(topic);
            String where = node.boundAddresses().get(0).toString();
            out.println("publishing on " + where + " topic '" + topic + "'");
            if (wanted > 0 && node.subscriberCount(topic) < wanted) {
                out.println("waiting up to " + Durations.format(waitTimeout) + " for " + (wanted == 1 ? "a subscriber" : wanted + " subscribers")
                        + " (mw msg sub " + where + " " + topic + ")");
            }
            out.flush();
            long deadline = System.nanoTime() + waitTimeout.toNanos();
            while (node.subscriberCount(topic) < wanted) {
                if (System.nanoTime() - deadline > 0) {
                    int came = node.subscriberCount(topic);
                    err.println("mw msg pub: " + (came == 0 ? "no subscriber" : "only " + came + " of " + wanted + " subscribers") + " came to " + where
                            + " within " + Durations.format(waitTimeout) + "; nothing was published (start mw msg sub " + where + " " + topic
                            + " first, a longer --wait-timeout, or --wait-subscribers 0 to publish to whoever is there)");
                    return 1;
                }
                LockSupport.parkNanos(10_000_000);
            }
            String password = common.password();
            long period = (long) (1e9 / rate);
            long next = System.nanoTime();
            long reached = 0;
            for (long i = 0; count == 0 || i < count; i++) {
                int subscribers = node.subscriberCount(topic);
                node.publishMessage(topic, text, function, password);
                reached += subscribers;
                out.println("published #" + (i + 1) + ": " + text + (countable ? " (" + (subscribers == 1 ? "1 subscriber" : subscribers + " subscribers") + ")" : ""));
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
            if (countable && reached == 0) {
                err.println("mw msg pub: no subscriber was connected, so nobody received it");
                err.flush();
            }
        }
        return 0;
    }
}
