package io.robomw.it.agents;

import io.robomw.testkit.Ports;
import io.robomw.it.StdoutLines;

import java.io.IOException;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.TimeUnit;

import io.robomw.it.demo.MwProcess;

import static org.junit.jupiter.api.Assertions.fail;

/**
 * {@code mw host} in its own JVM, on a class path with the middleware only: no example agents, no
 * test classes, so every agent's code has to travel to it. Waits for its "ready at" line;
 * {@link #kill()} is kill -9; {@link #close()} stops it as Ctrl-C would and always waits for it.
 * Its log (stderr) is appended to {@code target/it-logs/NAME.log} and can be read back.
 */
public final class HostProcess implements AutoCloseable {

    static final Duration START = Duration.ofSeconds(60);

    private final String name;
    private final int port;
    private final List<String> hostArgs;
    private final List<String> jvmArgs;
    private final Path log;
    private Process process;
    private String messaging;
    private String wire;
    private String served;

    private HostProcess(String name, int port, List<String> jvmArgs, List<String> hostArgs) throws IOException {
        this.name = name;
        this.port = port;
        this.jvmArgs = jvmArgs;
        this.hostArgs = hostArgs;
        Path logs = Path.of("target", "it-logs");
        Files.createDirectories(logs);
        this.log = logs.resolve(name + ".log");
        Files.deleteIfExists(log);
    }

    /**
     * Starts a host.
     *
     * @param name  its name
     * @param extra {@code mw host} options besides --name and --port
     * @return the running host
     */
    public static HostProcess start(String name, String... extra) throws IOException {
        return start(name, List.of(), extra);
    }

    /**
     * Starts a host in a JVM with extra options.
     *
     * @param name    its name
     * @param jvmArgs options for its JVM (system properties: {@code -Dk=v}), before the main class
     * @param extra   {@code mw host} options besides --name and --port
     * @return the running host
     */
    public static HostProcess start(String name, List<String> jvmArgs, String... extra) throws IOException {
        HostProcess h = new HostProcess(name, Ports.free(), List.copyOf(jvmArgs), List.of(extra));
        h.launch();
        return h;
    }

    public String address() {
        return "rmi://127.0.0.1:" + port + "/" + name;
    }

    /** @return where its agent wire listens, as it printed it (HOST:PORT, or "none (--no-wire; ...)") */
    public String wire() {
        return wire;
    }

    /** @return the address its messaging node receives at, as it printed it ("none (--no-messaging)" without one) */
    public String messaging() {
        return messaging;
    }

    /** @return the address its robot is served at (with --serve), for Robots.remote */
    public String served() {
        return served;
    }

    /** Starts it again, same name, port and options (after {@link #kill()}). */
    public void restart() throws IOException {
        launch();
    }

    private void launch() throws IOException {
        boolean readyLine = false;
        messaging = null;
        served = null;
        // MarkSweepDeadRatio=0: every full collection compacts the whole heap. By default the serial
        // collector's full collection leaves up to 5% of the old generation's capacity of dead space in
        // place as filler arrays, which a class histogram counts as live int[] (JDK 17; from JDK 19
        // jdk.internal.vm.FillerArray / FillerElement[]): the soak's heap figures (jcmd GC.class_histogram)
        // would count up to 12 MiB of garbage as held (docs/reliability.md).
        List<String> command = new ArrayList<>(List.of(Path.of(System.getProperty("java.home"), "bin", "java").toString(),
                "-XX:+UseSerialGC", "-XX:MarkSweepDeadRatio=0", "-XX:TieredStopAtLevel=1", "--enable-native-access=ALL-UNNAMED"));
        command.addAll(jvmArgs);
        command.addAll(List.of("-cp", middlewareOnlyClassPath(), "io.robomw.cli.Mw", "host", "--name", name, "--port", String.valueOf(port)));
        command.addAll(hostArgs);
        process = new ProcessBuilder(command).redirectError(ProcessBuilder.Redirect.appendTo(log.toFile())).start();
        StdoutLines q = new StdoutLines(process, "it-host-stdout-" + name);
        long deadline = System.nanoTime() + START.toNanos();
        while (true) {
            String line;
            try {
                line = q.next(deadline);
            } catch (InterruptedException e) {
                Thread.currentThread().interrupt();
                throw new IOException("interrupted", e);
            }
            if (line == null || StdoutLines.ended(line)) {
                close();
                fail("agent host " + name + " did not start within " + START + " (log: " + log + ")");
            }
            if (line.startsWith("agent wire at ")) {
                wire = line.substring("agent wire at ".length()).strip();
            }
            if (line.startsWith("messaging at ")) {
                messaging = line.substring("messaging at ".length()).split(" ")[0];
            }
            if (line.contains(" served at ")) {
                served = line.substring(line.indexOf(" served at ") + " served at ".length()).strip();
            }
            if (line.contains(" ready at ")) {
                readyLine = true;
            }
            if (readyLine && messaging != null && (served != null || !hostArgs.contains("--serve"))) {
                return;
            }
        }
    }

    /** @return the process id of the host's JVM now (a restart gives a new one) */
    public long pid() {
        return process.pid();
    }

    /** @return whether the host's JVM is running */
    public boolean alive() {
        return process != null && process.isAlive();
    }

    /** kill -9: no shutdown hook, no flush. Waits until it is gone. */
    public void kill() throws InterruptedException {
        process.destroyForcibly();
        process.waitFor(30, TimeUnit.SECONDS);
    }

    /** @return the host's log so far */
    public String log() throws IOException {
        return Files.readString(log, StandardCharsets.UTF_8);
    }

    @Override
    public void close() {
        if (process == null) {
            return;
        }
        try {
            process.destroy();
            if (!process.waitFor(15, TimeUnit.SECONDS)) {
                process.destroyForcibly();
                process.waitFor(10, TimeUnit.SECONDS);
            }
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
            process.destroyForcibly();
        }
    }

    static String middlewareOnlyClassPath() {
        return MwProcess.middlewareOnlyClassPath();
    }
}
