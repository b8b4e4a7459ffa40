package io.robomw.cli;

import io.robomw.agents.messaging.MessagingNode;
import picocli.CommandLine.Command;
import picocli.CommandLine.Mixin;
import picocli.CommandLine.Option;
import picocli.CommandLine.Parameters;
import picocli.CommandLine.Spec;
import picocli.CommandLine.Model.CommandSpec;

import java.io.PrintWriter;
import java.util.concurrent.Callable;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.TimeUnit;

/**
 * {@code mw msg sub ADDRESS TOPIC}: prints the messages of TOPIC. Connects to a tcp, udp or rmi
 * publisher (or, with {@code --bind}, listens there: then it also receives {@code mw msg send});
 * joins a multicast group. {@code --echo} answers each {@code send} with its own payload.
 */
@Command(name = "sub", mixinStandardHelpOptions = true, description = "Print the messages of a topic (connects to a publisher, or --bind; joins multicast groups).")
final class MsgSubCommand implements Callable<Integer> {

    @Mixin
    private MsgCommand.Common common;

    @Mixin
    private BeaconOption beacon;

    @Parameters(index = "0", paramLabel = "ADDRESS", description = "the publisher, e.g. tcp://127.0.0.1:7000; or where to listen with --bind")
    private String address;

    @Parameters(index = "1", paramLabel = "TOPIC")
    private String topic;

    @Option(names = "--bind", description = "listen at ADDRESS instead of connecting to it")
    private boolean bind;

    @Option(names = "--echo", description = "reply to each message sent with 'mw msg send' with its own payload")
    private boolean echo;

    @Option(names = "--count", defaultValue = "0", description = "exit after this many messages; 0 = until interrupted")
    private long count;

    @Option(names = "--timeout", defaultValue = "0", description = "exit with status 1 after this long (30, 500ms, 2m...); 0 = no limit")
    private java.time.Duration timeout;

    @Spec
    private CommandSpec spec;

    @Override
    public Integer call() throws Exception {
        PrintWriter out = spec.commandLine().getOut();
        CountDownLatch done = new CountDownLatch(count == 0 ? 1 : (int) Math.min(count, Integer.MAX_VALUE));
        try (MessagingNode node = MessagingNode.builder(common.name).settings(common.settings()).build();
             AutoCloseable announced = beacon.announce(node)) {
            node.addMessageListener(topic, common.password(), m -> {
                synchronized (out) {
                    out.println(MsgCommand.describe(m));
                    out.flush();
                }
                if (echo) {
                    try {
                        node.replyMessage(m, m.payload(), "echo");
                    } catch (RuntimeException e) {
                        // a publication: nothing to answer
                    }
                }
                if (count > 0) {
                    done.countDown();
                }
            });
            node.subscribeMessage(topic, common.password());
            if (bind || MsgCommand.isGroup(address)) {
                node.bind(address);
            } else {
                node.connect(address);
            }
            synchronized (out) {
                out.println("listening to topic '" + topic + "' " + (node.boundAddresses().isEmpty() ? "from " + address : "at " + node.boundAddresses().get(0)));
                out.flush();
            }
            if (!timeout.isZero()) {
                return done.await(timeout.toNanos(), TimeUnit.NANOSECONDS) ? 0 : 1;
            }
            done.await();
            return 0;
        }
    }
}
