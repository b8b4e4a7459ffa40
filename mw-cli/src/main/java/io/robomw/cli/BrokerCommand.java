package io.robomw.cli;

import io.robomw.agents.messaging.mqtt.BrokerCredentials;
import io.robomw.cli.broker.BrokerUser;
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

    @Option(names = "--bind", defaultValue = "127.0.0.1", description = "address to listen on (default ${DEFAULT-VALUE}: this machine only)")
    String bind;

    @Option(names = "--credentials", paramLabel = "FILE", description = "the broker's user and password (username=, password=); generated on first"
            + " start, readable by you only (default: ~/.robomw/broker.credentials, which mw commands read for brokers on this machine)")
    Path credentials;

    @Option(names = "--anonymous", description = "let every client in, with no user and no access rules (as Mosquitto's allow_anonymous true):"
            + " for a closed lab network only")
    boolean anonymous;

    @Option(names = "--data", paramLabel = "DIR", description = "keep sessions and queued messages here, across restarts; default: a fresh directory removed at exit")
    Path data;

    @Spec
    CommandSpec spec;

    @Override
    public Integer call() throws Exception {
        PrintWriter out = spec.commandLine().getOut();
        PrintWriter err = spec.commandLine().getErr();
        if (anonymous && credentials != null) {
            err.println("mw broker: --anonymous and --credentials contradict each other; give one");
            return 2;
        }
        BrokerUser user = null;
        EmbeddedBroker broker;
        try {
            if (anonymous) {
                err.println("mw broker: WARNING: --anonymous: every client that reaches " + bind + " gets in and may read and write everything"
                        + (InetAddress.getByName(bind).isLoopbackAddress() ? " (every user of this machine)" : " (every machine that reaches it)"));
            } else {
                user = BrokerUser.loadOrGenerate(credentials != null ? credentials : BrokerCredentials.defaultFile());
            }
            broker = EmbeddedBroker.start(bind, port, data, user);
        } catch (IOException e) {
            err.println("mw broker: " + e.getMessage());
            return 2;
        }
        if (user != null && user.generated()) {
            out.printf("mqtt broker user %s, password %s: generated and saved in %s (readable by you only); mw commands on this machine read it,"
                    + " other clients give it (mosquitto_sub -u %s -P ...). It is printed this once.%n", user.name(), user.password(), user.file(), user.name());
        } else if (user != null) {
            out.printf("mqtt broker user %s (credentials in %s)%n", user.name(), user.file());
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
