package io.robomw.it.demo;

import io.robomw.it.StdoutLines;

import java.io.File;
import java.io.IOException;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.ArrayList;
import java.util.Arrays;
import java.util.List;
import java.util.concurrent.TimeUnit;
import java.util.stream.Collectors;

import static org.junit.jupiter.api.Assertions.fail;

/**
 * One {@code mw} command in its own JVM, as the {@code ./mw} launcher runs it: the middleware's
 * class path only (no examples, no tests) and {@code mw.home} at the checkout. Its stdout lines
 * are kept and can be awaited; its stderr goes to {@code target/it-logs/NAME.log}. Closing it
 * stops it (SIGTERM, then SIGKILL) and waits.
 */
public final class MwProcess implements AutoCloseable {

    public static final Path CHECKOUT = Path.of("..").toAbsolutePath().normalize();

    /**
     * The JVM options mw demo gives its hosts (and the tests their short-lived processes): a small
     * collector and the quick compiler only, so that the many short mw commands of a test start in
     * less time and take less of a loaded machine.
     */
    public static final List<String> QUICK_JVM = List.of("-XX:+UseSerialGC", "-XX:TieredStopAtLevel=1");

    private final String name;
    private final Process process;
    private final StdoutLines lines;

    private MwProcess(String name, Process process) {
        this.name = name;
        this.process = process;
        this.lines = new StdoutLines(process, "it-mw-" + name);
    }

    public static MwProcess start(String name, String... args) throws IOException {
        return start(name, false, List.of(), args);
    }

    /**
     * Starts it with a home folder of its own ({@code user.home}): what it keeps across runs (its
     * replay windows in {@code ~/.robomw/replay}, one process at a time per file) is then the test's
     * alone, not shared with the other tests' processes running at the same time.
     *
     * @param name its name
     * @param home the home folder
     * @param args the command and its options
     * @return the process
     */
    public static MwProcess startWithHome(String name, Path home, String... args) throws IOException {
        return start(name, false, List.of("-Duser.home=" + home.toAbsolutePath()), args);
    }

    /**
     * Starts it with standard error merged into standard output, as a terminal shows them.
     *
     * @param name its name
     * @param args the command and its options
     * @return the process
     */
    public static MwProcess startAsOnATerminal(String name, String... args) throws IOException {
        return start(name, true, List.of(), args);
    }

    private static MwProcess start(String name, boolean merged, List<String> jvm, String... args) throws IOException {
        Path logs = Path.of("target", "it-logs");
        Files.createDirectories(logs);
        List<String> command = new ArrayList<>(List.of(Path.of(System.getProperty("java.home"), "bin", "java").toString(),
                "--enable-native-access=ALL-UNNAMED"));
        command.addAll(QUICK_JVM);
        command.addAll(jvm);
        command.addAll(List.of("-Dmw.home=" + CHECKOUT, "-cp", middlewareOnlyClassPath(), "io.robomw.cli.Mw"));
        command.addAll(List.of(args));
        ProcessBuilder pb = new ProcessBuilder(command).directory(CHECKOUT.toFile());
        if (merged) {
            pb.redirectErrorStream(true);
        } else {
            pb.redirectError(logs.resolve(name + ".log").toFile());
        }
        return new MwProcess(name, pb.start());
    }

    /** @return this JVM's class path without test classes, test jars, example agents and test libraries */
    public static String middlewareOnlyClassPath() {
        List<String> drop = List.of("examples", "test-classes", "-tests.jar", "junit", "opentest4j", "apiguardian", "jade", "jeromq");
        return Arrays.stream(System.getProperty("java.class.path").split(File.pathSeparator))
                .filter(e -> drop.stream().noneMatch(e::contains))
                .map(e -> Path.of(e).toAbsolutePath().toString())
                .collect(Collectors.joining(File.pathSeparator));
    }

    /** @return the first stdout line containing {@code text}, waiting up to {@code within} */
    public String await(String text, Duration within) throws InterruptedException {
        long deadline = System.nanoTime() + within.toNanos();
        while (true) {
            String line = lines.next(deadline);
            if (line == null || StdoutLines.ended(line)) {
                fail("mw " + name + " printed no line with '" + text + "' within " + within + " (log: target/it-logs/" + name + ".log); it printed:\n"
                        + lines.transcript());
            }
            if (line.contains(text)) {
                return line;
            }
        }
    }

    /** Waits for it to exit by itself. */
    public int waitFor(Duration within) throws InterruptedException {
        if (!process.waitFor(within.toMillis(), TimeUnit.MILLISECONDS)) {
            fail("mw " + name + " did not finish within " + within + "; it printed:\n" + lines.transcript());
        }
        return process.exitValue();
    }

    public String output() {
        return lines.transcript();
    }

    /** @return the processes it started and that still run */
    public java.util.List<ProcessHandle> children() {
        return process.children().toList();
    }

    /** kill -9: no shutdown hook; waits until it is gone. */
    public void kill() throws InterruptedException {
        process.destroyForcibly();
        process.waitFor(30, TimeUnit.SECONDS);
    }

    @Override
    public void close() throws InterruptedException {
        process.destroy();
        if (!process.waitFor(15, TimeUnit.SECONDS)) {
            process.destroyForcibly();
            process.waitFor(10, TimeUnit.SECONDS);
        }
    }
}
