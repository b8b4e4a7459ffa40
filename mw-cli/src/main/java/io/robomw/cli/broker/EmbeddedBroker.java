package io.robomw.cli.broker;

import com.hivemq.embedded.EmbeddedHiveMQ;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.io.IOException;
import java.io.UncheckedIOException;
import java.net.InetAddress;
import java.net.InetSocketAddress;
import java.net.ServerSocket;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.Comparator;
import java.util.concurrent.CompletionException;
import java.util.stream.Stream;

/**
 * An MQTT 5 broker in this JVM (HiveMQ Community Edition, embedded), for a single machine that
 * needs nothing else: {@code mw broker}, the tests and the benchmark. It listens on one address
 * (loopback unless told otherwise) and keeps sessions and queued messages in a data directory,
 * so a broker restarted on the same directory still has them.
 *
 * <p>Secure by default, as Mosquitto 2.0 is: it lets in only its user ({@link BrokerUser}, whose
 * credentials file {@code mw} commands on this machine read), with the access rules of
 * {@link BrokerAccess}; a broker started without a user lets every client in, and says so. For a
 * fleet, run a broker with users and access rules (Mosquitto, HiveMQ, EMQX; docs/messaging.md).
 *
 * <p>Not thread-safe: one thread starts and closes it.
 */
public final class EmbeddedBroker implements AutoCloseable {

    private static final Logger LOG = LoggerFactory.getLogger(EmbeddedBroker.class);
    private static final int FREE_PORT_TRIES = 3;
    /**
     * QoS 1 messages the broker holds for one client beyond those in flight to it: a slow subscriber's
     * backlog, or what waits for a persistent session that is away. As many as a RoboMW node queues for
     * the broker ({@code max-queued}); HiveMQ's own default, 1000, dropped the newest of a 2,000-message
     * burst to a subscriber in another JVM on a loaded machine. Past it the newest are dropped (HiveMQ's
     * {@code discard}), as Mosquitto does past its {@code max_queued_messages}.
     */
    static final int QUEUED_PER_CLIENT = 10_000;

    private final EmbeddedHiveMQ hivemq;
    private final String bind;
    private final int port;
    private final Path data;
    private final boolean ownsData;

    private EmbeddedBroker(EmbeddedHiveMQ hivemq, String bind, int port, Path data, boolean ownsData) {
        this.hivemq = hivemq;
        this.bind = bind;
        this.port = port;
        this.data = data;
        this.ownsData = ownsData;
    }

    /**
     * Starts a broker and waits until it listens.
     *
     * @param bind the address to listen on, for example {@code 127.0.0.1}
     * @param port the port; 0 picks a free one
     * @param data where sessions and queued messages are kept, or {@code null} for a fresh
     *             directory removed on close
     * @return the running broker
     * @throws IOException if it cannot listen there or cannot use the directory
     */
    public static EmbeddedBroker start(String bind, int port, Path data) throws IOException {
        return start(bind, port, data, null);
    }

    /**
     * Starts a broker that lets in only its user, and waits until it listens.
     *
     * @param bind the address to listen on, for example {@code 127.0.0.1}
     * @param port the port; 0 picks a free one
     * @param data where sessions and queued messages are kept, or {@code null} for a fresh directory removed on close
     * @param user the only user let in, or {@code null} to let every client in (anonymous access, logged as a warning)
     * @return the running broker
     * @throws IOException if it cannot listen there or cannot use the directory
     */
    public static EmbeddedBroker start(String bind, int port, Path data, BrokerUser user) throws IOException {
        boolean ownsData = data == null;
        Path dir = ownsData ? Files.createTempDirectory("mw-broker-") : Files.createDirectories(data);
        IOException last = null;
        for (int attempt = 0; attempt < (port == 0 ? FREE_PORT_TRIES : 1); attempt++) {
            int p = port == 0 ? freePort(bind) : port;
            try {
                return startOn(bind, p, dir, ownsData, user);
            } catch (IOException e) {
                last = e; // with a picked port, another program may have taken it meanwhile: pick again
            }
        }
        if (ownsData) {
            delete(dir);
        }
        throw last;
    }

    private static EmbeddedBroker startOn(String bind, int port, Path dir, boolean ownsData, BrokerUser user) throws IOException {
        Path conf = Files.createDirectories(dir.resolve("conf"));
        Path extensions = Files.createDirectories(dir.resolve("extensions"));
        Path store = Files.createDirectories(dir.resolve("data"));
        Files.writeString(conf.resolve("config.xml"), config(bind, port), StandardCharsets.UTF_8);
        var builder = EmbeddedHiveMQ.builder().withoutLoggingBootstrap()
                .withConfigurationFolder(conf).withDataFolder(store).withExtensionsFolder(extensions);
        if (user != null) {
            builder = builder.withEmbeddedExtension(BrokerAccess.extension(user));
        } else {
            LOG.warn("MQTT broker on {}:{} lets EVERY client in (no user, no access rules)", bind, port);
        }
        EmbeddedHiveMQ hivemq = builder.build();
        try {
            hivemq.start().join();
        } catch (CompletionException e) {
            closeQuietly(hivemq);
            throw new IOException("the MQTT broker could not start on " + bind + ":" + port + ": " + rootMessage(e), e);
        }
        if (!listening(bind, port)) {
            closeQuietly(hivemq);
            throw new IOException("the MQTT broker started but does not listen on " + bind + ":" + port + " (is the port taken?)");
        }
        LOG.info("MQTT broker listening on {}:{}, data in {}", bind, port, dir);
        return new EmbeddedBroker(hivemq, bind, port, dir, ownsData);
    }

    /** @return the address clients use, {@code mqtt://BIND:PORT} */
    public String address() {
        return "mqtt://" + (bind.contains(":") ? "[" + bind + "]" : bind) + ":" + port;
    }

    /** @return the port it listens on */
    public int port() {
        return port;
    }

    /** @return where it keeps sessions and queued messages */
    public Path dataDirectory() {
        return data;
    }

    /** Stops the broker (sessions and queued messages are saved in the data directory first). Idempotent. */
    @Override
    public void close() {
        try {
            hivemq.stop().join();
        } catch (CompletionException e) {
            LOG.warn("stopping the MQTT broker on port {}: {}", port, rootMessage(e));
        }
        closeQuietly(hivemq);
        if (ownsData) {
            delete(data);
        }
    }

    /** The broker's configuration: one TCP listener, {@link #QUEUED_PER_CLIENT} messages queued a client, no usage statistics sent anywhere. */
    static String config(String bind, int port) {
        return """
                <?xml version="1.0"?>
                <hivemq>
                    <listeners>
                        <tcp-listener>
                            <port>%d</port>
                            <bind-address>%s</bind-address>
                        </tcp-listener>
                    </listeners>
                    <mqtt>
                        <queued-messages>
                            <max-queue-size>%d</max-queue-size>
                            <strategy>discard</strategy>
                        </queued-messages>
                    </mqtt>
                    <anonymous-usage-statistics>
                        <enabled>false</enabled>
                    </anonymous-usage-statistics>
                </hivemq>
                """.formatted(port, bind, QUEUED_PER_CLIENT);
    }

    private static boolean listening(String bind, int port) {
        try (java.net.Socket s = new java.net.Socket()) {
            s.connect(new InetSocketAddress(InetAddress.getByName(bind.equals("0.0.0.0") ? "127.0.0.1" : bind), port), 2_000);
            return true;
        } catch (IOException e) {
            return false;
        }
    }

    private static int freePort(String bind) throws IOException {
        try (ServerSocket s = new ServerSocket()) {
            s.setReuseAddress(true);
            s.bind(new InetSocketAddress(InetAddress.getByName(bind), 0));
            return s.getLocalPort();
        }
    }

    private static void closeQuietly(EmbeddedHiveMQ hivemq) {
        try {
            hivemq.close();
        } catch (Exception e) {
            LOG.debug("closing the embedded broker: {}", e.toString());
        }
    }

    private static void delete(Path dir) {
        try (Stream<Path> files = Files.walk(dir)) {
            files.sorted(Comparator.reverseOrder()).forEach(f -> {
                try {
                    Files.deleteIfExists(f);
                } catch (IOException e) {
                    throw new UncheckedIOException(e);
                }
            });
        } catch (IOException | UncheckedIOException e) {
            LOG.warn("could not remove the broker's directory {}: {}", dir, e.getMessage());
        }
    }

    private static String rootMessage(Throwable t) {
        Throwable root = t;
        while (root.getCause() != null && root.getCause() != root) {
            root = root.getCause();
        }
        return root.getClass().getSimpleName() + (root.getMessage() == null ? "" : ": " + root.getMessage());
    }
}
