package io.robomw.cli;

import io.robomw.cli.broker.EmbeddedBroker;
import picocli.CommandLine.Command;
import picocli.CommandLine.Model.CommandSpec;
import picocli.CommandLine.Option;
import picocli.CommandLine.Spec;

import java.io.IOException;
import java.io.PrintWriter;
import java.net.InetAddress;
import java.nio.file.Path;
import java.util.concurrent.Callable;
import java.util.concurrent.CountDownLatch;

/**
 * {@code mw broker}: an embedded MQTT 5 broker until Ctrl-C (or SIGTERM), for a single machine.
 * Prints {@code mqtt broker ready at mqtt://127.0.0.1:PORT} on standard output once it listens.
 */
@Command(name = "broker", mixinStandardHelpOptions = true,
        description = {"Runs an MQTT 5 broker (embedded HiveMQ CE) for mqtt:// messaging, remote robots and presence on one machine.",
                "Example: mw broker --port 1883   (then mw msg sub mqtt://127.0.0.1:1883 news)"})
final class BrokerCommand implements Callable<Integer> {

    @Option(names = "--port", defaultValue = "1883", description = "port to listen on (default ${DEFAULT-VALUE}; 0 picks a free one)")
    int port;

    @Option(names = "--bind", defaultValue = "127.0.0.1", description = "address to listen on (default ${DEFAULT-VALUE}; this broker lets every client in)")
    String bind;

    @Option(names = "--data", paramLabel = "DIR", description = "keep sessions and queued messages here, across restarts; default: a fresh directory removed at exit")
    Path data;

    @Spec
    CommandSpec spec;

    @Override
    public Integer call() throws Exception {
        PrintWriter out = spec.commandLine().getOut();
        PrintWriter err = spec.commandLine().getErr();
        if (!InetAddress.getByName(bind).isLoopbackAddress()) {
            err.println("mw broker: listening on " + bind + ": every client that reaches it gets in (no passwords); for a network of robots,"
                    + " prefer a broker with users and access rules (docs/messaging.md)");
        }
        EmbeddedBroker broker;
        try {
            broker = EmbeddedBroker.start(bind, port, data);
        } catch (IOException e) {
            err.println("mw broker: " + e.getMessage());
            return 2;
        }
        out.printf("mqtt broker ready at %s (data: %s)%n", broker.address(), data == null ? "removed at exit" : broker.dataDirectory());
        out.flush();
        CountDownLatch stopped = new CountDownLatch(1);
        Runtime.getRuntime().addShutdownHook(new Thread(() -> {
            broker.close();
            stopped.countDown();
        }, "mw-broker-shutdown"));
        stopped.await();
        return 0;
    }
}
