package io.robomw.cli;

import io.robomw.agents.messaging.MessagingNode;
import io.robomw.api.Message;
import io.robomw.api.MessagingException;
import picocli.CommandLine.Command;
import picocli.CommandLine.Mixin;
import picocli.CommandLine.Option;
import picocli.CommandLine.Parameters;
import picocli.CommandLine.Spec;
import picocli.CommandLine.Model.CommandSpec;

import java.time.Duration;
import java.util.UUID;
import java.util.concurrent.Callable;

/**
 * {@code mw msg send ADDRESS NAME TOPIC TEXT}: sends one message to NAME at ADDRESS and prints the
 * reply (exit 1 when none comes within {@code --timeout}).
 */
@Command(name = "send", mixinStandardHelpOptions = true, description = "Send one message to a receiver and print its reply.")
final class MsgSendCommand implements Callable<Integer> {

    @Mixin
    private MsgCommand.Common common;

    @Parameters(index = "0", paramLabel = "ADDRESS", description = "the receiver's host, e.g. tcp://127.0.0.1:7000")
    private String address;

    @Parameters(index = "1", paramLabel = "NAME", description = "the receiver's name there ('*' for any)")
    private String receiver;

    @Parameters(index = "2", paramLabel = "TOPIC")
    private String topic;

    @Parameters(index = "3", paramLabel = "TEXT", description = "the payload (text)")
    private String text;

    @Option(names = "--function", defaultValue = "data", description = "the message function (default: ${DEFAULT-VALUE})")
    private String function;

    @Option(names = "--timeout", defaultValue = "5s", description = "how long to wait for the reply: 5, 500ms, 2m... (default: ${DEFAULT-VALUE})")
    private Duration timeout;

    @Option(names = "--no-reply", description = "do not wait for a reply")
    private boolean noReply;

    @Spec
    private CommandSpec spec;

    @Override
    public Integer call() {
        try (MessagingNode node = MessagingNode.builder(common.name).settings(common.settings()).build()) {
            UUID id = node.sendMessage(receiver, address, common.password(), topic, text, function);
            spec.commandLine().getOut().println("sent " + id + " to '" + receiver + "' at " + address);
            if (noReply) {
                return 0;
            }
            Message reply = node.waitForReply(id, timeout);
            spec.commandLine().getOut().println("reply " + MsgCommand.describe(reply));
            return 0;
        } catch (MessagingException e) {
            spec.commandLine().getErr().println("mw msg send: " + e.getMessage());
            return 1;
        } finally {
            spec.commandLine().getOut().flush();
            spec.commandLine().getErr().flush();
        }
    }
}
