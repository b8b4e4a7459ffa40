package io.robomw.it.mqtt;

import io.robomw.testkit.Ports;
import io.robomw.testkit.Await;
import io.robomw.it.StdoutLines;
import org.junit.jupiter.api.Assumptions;

import java.io.IOException;
import java.net.InetAddress;
import java.net.InetSocketAddress;
import java.net.Socket;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.TimeUnit;

import static org.junit.jupiter.api.Assertions.fail;

/**
 * An MQTT 5 broker in its own process on 127.0.0.1, for the integration tests and the benchmark:
 * the embedded one ({@code mw broker}, this JVM's class path) or Mosquitto (Debian's
 * {@code mosquitto}, with a generated configuration). Both keep sessions and queued messages in
 * a directory of their own, so {@link #restart()} (a graceful stop, then a start on the same
 * port and directory) loses nothing a persistent session holds. {@link #close()} stops it.
 */
public final class Broker implements AutoCloseable {

    /** Which broker. */
    public enum Kind {
        /** {@code mw broker} (HiveMQ CE embedded). */
        EMBEDDED,
        /** Debian's Mosquitto. */
        MOSQUITTO
    }

    private static final Duration START = Duration.ofSeconds(60);
    private static final Path MOSQUITTO = Path.of("/usr/sbin/mosquitto");

    private final Kind kind;
    private final String name;
    private final Path dir;
    private String passwordFile;
    private String tlsPem;
    private int port;
    private Process process;

    private Broker(Kind kind, String name, Path dir) {
        this.kind = kind;
        this.name = name;
        this.dir = dir;
    }

    /**
     * Starts a broker on a free loopback port and waits until it accepts connections.
     *
     * @param kind which
     * @param name for its log, {@code target/it-logs/NAME.log}
     * @return the running broker
     */
    public static Broker start(Kind kind, String name) throws IOException {
        if (kind == Kind.MOSQUITTO) {
            Assumptions.assumeTrue(Files.isExecutable(mosquitto()),
                    "Mosquitto is not installed (" + MOSQUITTO + "): apt-get install mosquitto (.ci/run installs it)");
        }
        Path dir = Files.createDirectories(Path.of("target", "it-brokers")).resolve(name);
        deleteTree(dir);
        Files.createDirectories(dir);
        Broker b = new Broker(kind, name, dir.toAbsolutePath());
        b.port = Ports.free();
        b.launch();
        return b;
    }

    /**
     * Starts Mosquitto that lets in only one user (anonymous clients refused).
     *
     * @param name     for its log
     * @param user     the user's name
     * @param password the user's password
     * @return the running broker
     */
    public static Broker mosquittoWithUser(String name, String user, String password) throws IOException, InterruptedException {
        Assumptions.assumeTrue(Files.isExecutable(mosquitto()),
                "Mosquitto is not installed (" + MOSQUITTO + "): apt-get install mosquitto (.ci/run installs it)");
        Path dir = Files.createDirectories(Path.of("target", "it-brokers")).resolve(name);
        deleteTree(dir);
        Files.createDirectories(dir);
        Path passwords = dir.toAbsolutePath().resolve("passwords");
        Path tool = Files.isExecutable(Path.of("/usr/bin/mosquitto_passwd")) ? Path.of("/usr/bin/mosquitto_passwd")
                : mosquitto().resolveSibling("mosquitto_passwd");
        Process p = new ProcessBuilder(tool.toString(), "-b", "-c", passwords.toString(), user, password).redirectErrorStream(true).start();
        if (!p.waitFor(30, TimeUnit.SECONDS) || p.exitValue() != 0) {
            fail("mosquitto_passwd failed: " + new String(p.getInputStream().readAllBytes(), java.nio.charset.StandardCharsets.UTF_8));
        }
        Broker b = new Broker(Kind.MOSQUITTO, name, dir.toAbsolutePath());
        b.passwordFile = passwords.toString();
        b.port = Ports.free();
        b.launch();
        return b;
    }

    /**
     * Starts Mosquitto with a TLS listener.
     *
     * @param name its log's name
     * @param pem  a PEM file with the broker's certificate and private key
     * @return the running broker; its {@link #address()} is then {@code mqtts://127.0.0.1:PORT}
     */
    public static Broker mosquittoWithTls(String name, Path pem) throws IOException {
        Assumptions.assumeTrue(Files.isExecutable(mosquitto()),
                "Mosquitto is not installed (" + MOSQUITTO + "): apt-get install mosquitto (.ci/run installs it)");
        Path dir = Files.createDirectories(Path.of("target", "it-brokers")).resolve(name);
        deleteTree(dir);
        Files.createDirectories(dir);
        Broker b = new Broker(Kind.MOSQUITTO, name, dir.toAbsolutePath());
        b.tlsPem = pem.toAbsolutePath().toString();
        b.port = Ports.free();
        b.launch();
        return b;
    }

    /** @return {@code mqtt://127.0.0.1:PORT}, or {@code mqtts://...} for a TLS listener */
    public String address() {
        return (tlsPem == null ? "mqtt" : "mqtts") + "://127.0.0.1:" + port;
    }

    /** @return which broker */
    public Kind kind() {
        return kind;
    }

    /** Stops it gracefully (it saves its sessions) and starts it again on the same port and directory. */
    public void restart() throws IOException {
        stop();
        launch();
    }

    /**
     * Freezes the broker (SIGSTOP): its connections stay open but it reads, answers and
     * acknowledges nothing, as a broker that stalls does, until {@link #resume()}.
     */
    public void pause() throws IOException, InterruptedException {
        signal("STOP");
    }

    /** Lets a {@link #pause() paused} broker go on (SIGCONT). */
    public void resume() throws IOException, InterruptedException {
        signal("CONT");
    }

    private void signal(String name) throws IOException, InterruptedException {
        Process kill = new ProcessBuilder("kill", "-" + name, Long.toString(process.pid())).redirectErrorStream(true).start();
        if (!kill.waitFor(30, TimeUnit.SECONDS) || kill.exitValue() != 0) {
            kill.destroyForcibly();
            fail("kill -" + name + " " + process.pid() + " failed: " + new String(kill.getInputStream().readAllBytes()));
        }
    }

    /** Stops it gracefully (SIGTERM; forcibly after 30 s). */
    public void stop() {
        if (process == null) {
            return;
        }
        process.destroy();
        try {
            if (!process.waitFor(30, TimeUnit.SECONDS)) {
                process.destroyForcibly();
                process.waitFor(10, TimeUnit.SECONDS);
            }
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
            process.destroyForcibly();
        }
        process = null;
    }

    @Override
    public void close() {
        stop();
    }

    private void launch() throws IOException {
        Path log = Path.of("target", "it-logs", name + ".log");
        Files.createDirectories(log.getParent());
        List<String> command = new ArrayList<>();
        if (kind == Kind.EMBEDDED) {
            command.add(Path.of(System.getProperty("java.home"), "bin", "java").toString());
            command.addAll(List.of("-XX:+UseSerialGC", "-Xmx512m", "-cp", System.getProperty("java.class.path"), "io.robomw.cli.Mw",
                    "broker", "--port", Integer.toString(port), "--data", dir.resolve("embedded").toString()));
        } else {
            Path conf = dir.resolve("mosquitto.conf");
            String config = mosquittoConfig(port, dir);
            if (tlsPem != null) {
                config = config.replace("listener " + port + " 127.0.0.1", "listener " + port + " 127.0.0.1\ncertfile " + tlsPem + "\nkeyfile " + tlsPem);
            }
            if (passwordFile != null) {
                config = config.replace("allow_anonymous true", "allow_anonymous false\npassword_file " + passwordFile);
            }
            Files.writeString(conf, config);
            command.addAll(List.of(mosquitto().toString(), "-c", conf.toString()));
        }
        ProcessBuilder pb = new ProcessBuilder(command);
        if (kind == Kind.MOSQUITTO) {
            pb.redirectErrorStream(true);
        } else {
            pb.redirectError(ProcessBuilder.Redirect.appendTo(log.toFile()));
        }
        process = pb.start();
        if (kind == Kind.EMBEDDED) {
            StdoutLines lines = new StdoutLines(process, "it-broker-stdout-" + name);
            long deadline = System.nanoTime() + START.toNanos();
            try {
                String line;
                while ((line = lines.next(deadline)) != null && !line.startsWith("mqtt broker ready")) {
                    if (StdoutLines.ended(line)) {
                        break;
                    }
                }
                if (line == null || StdoutLines.ended(line)) {
                    stop();
                    fail("mw broker did not start within " + START + " (log: " + log + ")");
                }
            } catch (InterruptedException e) {
                Thread.currentThread().interrupt();
                throw new IOException("interrupted", e);
            }
        } else {
            Thread copy = new Thread(() -> {
                try (var in = process.getInputStream(); var out = Files.newOutputStream(log, java.nio.file.StandardOpenOption.CREATE,
                        java.nio.file.StandardOpenOption.APPEND)) {
                    in.transferTo(out);
                } catch (IOException e) {
                    // the broker ended
                }
            }, "it-broker-log-" + name);
            copy.setDaemon(true);
            copy.start();
            awaitListening(log);
        }
    }

    private void awaitListening(Path log) {
        try {
            Await.until("mosquitto listens on " + port + " (log: " + log + ")", START, () -> {
                try (Socket s = new Socket()) {
                    s.connect(new InetSocketAddress(InetAddress.getLoopbackAddress(), port), 500);
                    return true;
                } catch (IOException e) {
                    if (!process.isAlive()) {
                        fail("mosquitto ended at start (log: " + log + ")");
                    }
                    return false;
                }
            });
        } catch (AssertionError e) {
            stop();
            throw e;
        }
    }

    /**
     * Mosquitto on loopback only: anonymous clients (the tests' own), sessions and queued messages
     * saved on stop, Nagle off (request/reply would otherwise wait for delayed ACKs), and as root
     * (CI) it keeps running as root so it can write the directory.
     */
    static String mosquittoConfig(int port, Path dir) {
        return """
                listener %d 127.0.0.1
                allow_anonymous true
                set_tcp_nodelay true
                persistence true
                persistence_location %s/
                max_queued_messages 100000
                log_dest stderr
                log_type error
                log_type warning
                log_type notice
                %s
                """.formatted(port, dir, "root".equals(System.getProperty("user.name")) ? "user root" : "");
    }

    static Path mosquitto() {
        if (Files.isExecutable(MOSQUITTO)) {
            return MOSQUITTO;
        }
        for (String d : System.getenv().getOrDefault("PATH", "").split(":")) {
            Path p = Path.of(d, "mosquitto");
            if (!d.isEmpty() && Files.isExecutable(p)) {
                return p;
            }
        }
        return MOSQUITTO;
    }

    private static void deleteTree(Path dir) throws IOException {
        if (!Files.exists(dir)) {
            return;
        }
        try (var files = Files.walk(dir)) {
            for (Path p : files.sorted(java.util.Comparator.reverseOrder()).toList()) {
                Files.deleteIfExists(p);
            }
        }
    }
}
