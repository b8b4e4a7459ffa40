package io.robomw.it.mavlink;

import io.robomw.it.StdoutLines;
import io.robomw.it.demo.MwProcess;

import java.io.IOException;
import java.net.DatagramSocket;
import java.net.InetAddress;
import java.net.InetSocketAddress;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.TimeUnit;

import static org.junit.jupiter.api.Assertions.fail;

/**
 * The Python side of the vehicle tests (src/test/python): MAVSDK 4.1.0 and pymavlink 2.4.50 from
 * the environment the build makes ({@code target/it-python}, from {@code requirements.txt}), or
 * the one {@code -Dit.python=...} names. A missing environment fails the test saying how to make
 * it; it is never skipped.
 */
final class VehiclePython implements AutoCloseable {

    static final Path SCRIPTS = MwProcess.CHECKOUT.resolve("src-it/src/test/python");

    private final String name;
    private final Process process;
    private final StdoutLines lines;

    private VehiclePython(String name, Process process) {
        this.name = name;
        this.process = process;
        this.lines = new StdoutLines(process, "it-py-" + name);
    }

    /** @return the Python that has mavsdk and pymavlink, checked */
    static Path python() throws IOException, InterruptedException {
        String given = System.getProperty("it.python");
        Path python = given != null ? Path.of(given) : MwProcess.CHECKOUT.resolve("target/it-python/bin/python");
        String make = "src-it/src/test/python/setup-venv (what the build and .ci/run do), or name a Python that has them with -Dit.python=PATH";
        if (!Files.isExecutable(python)) {
            fail("the vehicle tests need Python with mavsdk and pymavlink at " + python + ": " + make);
        }
        Process p = new ProcessBuilder(python.toString(), "-c", "import mavsdk, pymavlink; print(mavsdk.__version__)").redirectErrorStream(true).start();
        if (!p.waitFor(60, TimeUnit.SECONDS) || p.exitValue() != 0) {
            p.destroyForcibly();
            fail(python + " lacks mavsdk or pymavlink (" + new String(p.getInputStream().readAllBytes()).strip() + "): " + make);
        }
        return python;
    }

    /**
     * Starts a script.
     *
     * @param name   for its log, target/it-logs/NAME.log
     * @param script the script in src/test/python
     * @param args   its arguments
     * @return the running script
     */
    static VehiclePython start(String name, String script, String... args) throws IOException, InterruptedException {
        List<String> command = new ArrayList<>(List.of(python().toString(), "-u", SCRIPTS.resolve(script).toString()));
        command.addAll(List.of(args));
        Path logs = Files.createDirectories(Path.of("target", "it-logs"));
        Process p = new ProcessBuilder(command).redirectError(logs.resolve(name + ".log").toFile()).start();
        return new VehiclePython(name, p);
    }

    /**
     * Runs a script that says OK or FAIL per step and DONE at its end.
     *
     * @return every OK line
     */
    List<String> expectDone(Duration within) throws InterruptedException, IOException {
        long deadline = System.nanoTime() + within.toNanos();
        List<String> ok = new ArrayList<>();
        while (true) {
            String line = lines.next(deadline);
            if (line == null) {
                fail(name + " did not finish within " + within.toSeconds() + " s; it said:\n" + lines.transcript() + log());
            }
            if (StdoutLines.ended(line)) {
                fail(name + " ended without DONE; it said:\n" + lines.transcript() + log());
            }
            if (line.startsWith("FAIL")) {
                fail(name + ": " + line + "\nit said:\n" + lines.transcript() + log());
            }
            if (line.startsWith("OK")) {
                ok.add(line);
            }
            if (line.equals("DONE")) {
                return ok;
            }
        }
    }

    /**
     * @param prefix what the line starts with
     * @return the next line that does, waiting up to {@code within}
     */
    String await(String prefix, Duration within) throws InterruptedException, IOException {
        long deadline = System.nanoTime() + within.toNanos();
        while (true) {
            String line = lines.next(deadline);
            if (line == null || StdoutLines.ended(line)) {
                fail(name + " said no line starting '" + prefix + "' within " + within.toSeconds() + " s:\n" + lines.transcript() + log());
            }
            if (line.startsWith(prefix)) {
                return line;
            }
        }
    }

    /** @return every line it printed so far */
    List<String> transcript() {
        return List.of(lines.transcript().split("\n"));
    }

    private String log() throws IOException {
        Path log = Path.of("target", "it-logs", name + ".log");
        return Files.exists(log) ? "\nits stderr:\n" + Files.readString(log) : "";
    }

    /** @return a UDP port free on loopback now */
    static int freeUdpPort() throws IOException {
        try (DatagramSocket s = new DatagramSocket(new InetSocketAddress(InetAddress.getLoopbackAddress(), 0))) {
            return s.getLocalPort();
        }
    }

    @Override
    public void close() throws InterruptedException {
        process.destroy();
        if (!process.waitFor(10, TimeUnit.SECONDS)) {
            process.destroyForcibly().waitFor(10, TimeUnit.SECONDS);
        }
    }
}
