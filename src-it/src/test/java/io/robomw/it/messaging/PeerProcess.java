package io.robomw.it.messaging;

import io.robomw.it.StdoutLines;

import java.io.IOException;
import java.io.PrintStream;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.TimeUnit;

import static org.junit.jupiter.api.Assertions.fail;

/**
 * A {@link Peer} (or another main class) in its own JVM, started with this JVM's java and class
 * path. Commands go to its stdin; its stdout lines are read with deadlines; its stderr (the log)
 * goes to {@code target/it-logs/NAME.log}. {@link #close()} ends it, forcibly if need be, and
 * waits for it.
 */
public final class PeerProcess implements AutoCloseable {

    /** How long one command may take unless the caller says otherwise. */
    public static final Duration COMMAND = Duration.ofSeconds(30);

    private final String name;
    private final Process process;
    private final PrintStream in;
    private final StdoutLines lines;

    private PeerProcess(String name, Process process) {
        this.name = name;
        this.process = process;
        this.in = new PrintStream(process.getOutputStream(), true, StandardCharsets.UTF_8);
        this.lines = new StdoutLines(process, "it-peer-stdout-" + name);
    }

    /**
     * Starts a {@link Peer} (with options for a quick start: serial GC, C1 only) and waits for it
     * to be ready.
     *
     * @param name     its node name (and log file name)
     * @param jvmArgs  extra JVM options (system properties)
     * @param peerArgs extra arguments after the name
     * @return the running peer
     */
    public static PeerProcess peer(String name, List<String> jvmArgs, String... peerArgs) throws IOException {
        List<String> args = new ArrayList<>(List.of(name));
        args.addAll(List.of(peerArgs));
        List<String> options = new ArrayList<>(List.of("-XX:+UseSerialGC", "-XX:TieredStopAtLevel=1", "-Dorg.slf4j.simpleLogger.defaultLogLevel=info"));
        options.addAll(jvmArgs);
        PeerProcess p = start(name, Peer.class.getName(), options, args);
        p.expect("READY", COMMAND);
        return p;
    }

    /**
     * @param name      for the log file
     * @param mainClass the class to run
     * @param jvmArgs   JVM options (nothing else is added: benchmarks get the JVM's defaults)
     * @param args      program arguments
     * @return the started process
     */
    public static PeerProcess start(String name, String mainClass, List<String> jvmArgs, List<String> args) throws IOException {
        Path logs = Path.of("target", "it-logs");
        Files.createDirectories(logs);
        List<String> command = new ArrayList<>();
        command.add(Path.of(System.getProperty("java.home"), "bin", "java").toString());
        command.add("--enable-native-access=ALL-UNNAMED"); // as mw starts its JVMs: no JDK 24+ warning for ACCP's and JNA's native code
        command.addAll(jvmArgs);
        command.add("-cp");
        command.add(System.getProperty("java.class.path"));
        command.add(mainClass);
        command.addAll(args);
        Process process = new ProcessBuilder(command).redirectError(logs.resolve(name + ".log").toFile()).start();
        return new PeerProcess(name, process);
    }

    /**
     * Sends one command and returns the first answer line starting with {@code prefix}.
     *
     * @param command the command line
     * @param prefix  the answer expected
     * @param within  the deadline
     * @return the answer line
     */
    public String ask(String command, String prefix, Duration within) {
        in.println(command);
        return expect(prefix, within);
    }

    /** {@link #ask(String, String, Duration)} with {@link #COMMAND} as the deadline. */
    public String ask(String command, String prefix) {
        return ask(command, prefix, COMMAND);
    }

    /**
     * @param prefix the line expected
     * @param within the deadline
     * @return the line
     */
    public String expect(String prefix, Duration within) {
        long deadline = System.nanoTime() + within.toNanos();
        while (true) {
            String line;
            try {
                line = lines.next(deadline);
            } catch (InterruptedException e) {
                Thread.currentThread().interrupt();
                throw new AssertionError("interrupted waiting for " + prefix + " from " + name, e);
            }
            if (line == null) {
                fail("peer " + name + " did not answer '" + prefix + "' within " + within + " (log: target/it-logs/" + name + ".log)");
            }
            if (line.startsWith(prefix)) {
                return line;
            }
            if (line.startsWith("ERR") || StdoutLines.ended(line)) {
                fail("peer " + name + " answered '" + line + "' while '" + prefix + "' was expected (log: target/it-logs/" + name + ".log)");
            }
        }
    }

    /** @return the process */
    public Process process() {
        return process;
    }

    /** Asks the peer to exit; after 5 s ends it forcibly. Always waits for it to be gone. */
    @Override
    public void close() {
        try {
            in.println("exit");
            if (!process.waitFor(5, TimeUnit.SECONDS)) {
                process.destroyForcibly();
            }
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
            process.destroyForcibly();
        } finally {
            process.destroyForcibly();
            try {
                process.waitFor(10, TimeUnit.SECONDS);
            } catch (InterruptedException e) {
                Thread.currentThread().interrupt();
            }
        }
    }
}
