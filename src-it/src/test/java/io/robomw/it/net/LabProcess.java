package io.robomw.it.net;

import io.robomw.it.StdoutLines;

import java.io.IOException;
import java.io.PrintStream;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.List;
import java.util.concurrent.TimeUnit;

import static org.junit.jupiter.api.Assertions.fail;

/**
 * A JVM a {@link LabHost} started ({@code ip netns exec} replaces itself with the JVM, so this
 * process is the JVM). Its stdout lines are read with deadlines; commands go to its stdin; its
 * stderr (the log) goes to {@code target/it-logs/NAME.log}. {@link #close()} stops it as Ctrl-C
 * would (SIGTERM), then kills it, and waits.
 */
public final class LabProcess implements AutoCloseable {

    private final String name;
    private final Path log;
    private final Process process;
    private final PrintStream in;
    private final StdoutLines lines;

    private LabProcess(String name, Path log, Process process) {
        this.name = name;
        this.log = log;
        this.process = process;
        this.in = new PrintStream(process.getOutputStream(), true, StandardCharsets.UTF_8);
        this.lines = new StdoutLines(process, "it-lab-stdout-" + name);
    }

    static LabProcess start(String name, List<String> command, Path directory) throws IOException {
        Path logs = Files.createDirectories(Path.of("target", "it-logs"));
        Path log = logs.resolve(name + ".log").toAbsolutePath();
        Process p = new ProcessBuilder(command).directory(directory.toFile()).redirectError(ProcessBuilder.Redirect.appendTo(log.toFile())).start();
        return new LabProcess(name, log, p);
    }

    /**
     * @param prefix what the line starts with
     * @param within the deadline
     * @return the next line starting with it (lines before it are passed over)
     */
    public String expect(String prefix, Duration within) {
        long deadline = System.nanoTime() + within.toNanos();
        while (true) {
            String line;
            try {
                line = lines.next(deadline);
            } catch (InterruptedException e) {
                Thread.currentThread().interrupt();
                throw new AssertionError("interrupted waiting for '" + prefix + "' from " + name, e);
            }
            if (line == null || StdoutLines.ended(line)) {
                fail(name + " printed no line starting '" + prefix + "' within " + within + (line == null ? "" : " (it ended)") + "; it printed:\n"
                        + lines.transcript() + "\n(log: " + log + ")");
            }
            if (line.startsWith(prefix)) {
                return line;
            }
        }
    }

    /**
     * @param within the deadline
     * @return the next line, or {@code null} if none came within it
     */
    public String next(Duration within) {
        try {
            String line = lines.next(System.nanoTime() + within.toNanos());
            return line == null || StdoutLines.ended(line) ? null : line;
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
            throw new AssertionError("interrupted reading " + name, e);
        }
    }

    /**
     * Sends a command and waits for its answer.
     *
     * @param command one line to its stdin
     * @param prefix  what the answer starts with
     * @param within  the deadline
     * @return the answer
     */
    public String ask(String command, String prefix, Duration within) {
        send(command);
        return expect(prefix, within);
    }

    /** @param command one line to its stdin */
    public void send(String command) {
        in.println(command);
    }

    /** @return everything it printed on stdout so far */
    public String output() {
        return lines.transcript();
    }

    /** @return its log (stderr) so far */
    public String log() throws IOException {
        return Files.readString(log, StandardCharsets.UTF_8);
    }

    /** @return whether it runs */
    public boolean alive() {
        return process.isAlive();
    }

    /** kill -9: no shutdown hook, no flush. Waits until it is gone. */
    public void kill() throws InterruptedException {
        process.destroyForcibly();
        process.waitFor(30, TimeUnit.SECONDS);
    }

    /**
     * @param within how long it may take
     * @return its exit status once it ended by itself
     */
    public int waitFor(Duration within) throws InterruptedException {
        if (!process.waitFor(within.toMillis(), TimeUnit.MILLISECONDS)) {
            fail(name + " did not end within " + within + "; it printed:\n" + lines.transcript());
        }
        return process.exitValue();
    }

    @Override
    public void close() {
        if (!process.isAlive()) {
            return;
        }
        try {
            process.destroy();
            if (!process.waitFor(20, TimeUnit.SECONDS)) {
                process.destroyForcibly();
                process.waitFor(10, TimeUnit.SECONDS);
            }
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
            process.destroyForcibly();
        }
    }

    @Override
    public String toString() {
        return name + " (pid " + process.pid() + ")";
    }
}
