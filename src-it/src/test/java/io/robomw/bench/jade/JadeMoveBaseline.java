package io.robomw.bench.jade;

import io.robomw.it.StdoutLines;

import java.io.File;
import java.io.IOException;
import java.io.PrintStream;
import java.net.InetAddress;
import java.net.ServerSocket;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.ArrayList;
import java.util.Arrays;
import java.util.Collections;
import java.util.List;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.TimeoutException;

/**
 * The JADE baseline for the mobile-agent benchmark: the round trip of a JADE agent that
 * {@code doMove}s from container A to container B and back, the two containers in two JVMs of
 * their own ({@link JadeContainerMain}) on loopback, with agent mobility on. One agent per
 * {@link #measure} call moves back and forth (warm case) and times each round trip itself on A
 * (see {@link JadeMoverAgent}).
 *
 * <p>The container JVMs are started with this JVM's java and class path, in {@code target/jade}
 * (JADE writes {@code APDescription.txt} into the working directory); their stderr (the JADE
 * log, warnings only) goes to {@code target/it-logs/jade-A.log} and {@code jade-B.log}.
 */
public final class JadeMoveBaseline implements AutoCloseable {

    /** How long a container JVM may take to start and join the platform. */
    private static final Duration START = Duration.ofSeconds(60);
    /** How long a single round trip may take before a measurement is given up. */
    private static final Duration IDLE = Duration.ofSeconds(30);

    private final List<Container> containers = new ArrayList<>();
    private Container a;

    private JadeMoveBaseline() {
    }

    /**
     * Starts both container JVMs and waits until both are in the platform.
     *
     * @return the running baseline; close it
     * @throws Exception if a container does not start (whatever was started is stopped)
     */
    public static JadeMoveBaseline start() throws Exception {
        JadeMoveBaseline baseline = new JadeMoveBaseline();
        try {
            int platformPort = freePort();
            baseline.a = baseline.launch("jade-A", "main", "A", String.valueOf(platformPort));
            baseline.a.expect("READY", START);
            Container b = baseline.launch("jade-B", "peripheral", "B", String.valueOf(platformPort), String.valueOf(freePort()));
            b.expect("READY", START);
            return baseline;
        } catch (Exception | Error e) {
            baseline.close();
            throw e;
        }
    }

    /**
     * Creates one agent with a {@code byte[payloadBytes]} on A and lets it go A→B→A
     * {@code warmup + iterations} times, keeping the last {@code iterations} round trips.
     *
     * @param payloadBytes size of the byte array the agent carries
     * @param warmup       round trips not kept
     * @param iterations   round trips kept
     * @return the kept round trips
     * @throws Exception if the measurement fails or stalls
     */
    public RoundTrips measure(int payloadBytes, int warmup, int iterations) throws Exception {
        if (payloadBytes < 0 || warmup < 0 || iterations < 1) {
            throw new IllegalArgumentException("payloadBytes " + payloadBytes + ", warmup " + warmup + ", iterations " + iterations);
        }
        int trips = warmup + iterations;
        // A gives up after IDLE without progress; this deadline only guards against A itself hanging.
        Duration deadline = IDLE.multipliedBy(2).plus(Duration.ofMillis(250).multipliedBy(trips));
        a.send("MEASURE " + payloadBytes + " " + warmup + " " + iterations + " B " + IDLE.toSeconds());
        String[] r = a.expect("RESULT", deadline).split(" ");
        if (Integer.parseInt(r[1]) != payloadBytes) {
            throw new IllegalStateException("result for payload " + r[1] + ", expected " + payloadBytes);
        }
        long[] nanos = Arrays.stream(r[2].split(",")).mapToLong(Long::parseLong).toArray();
        if (nanos.length != iterations) {
            throw new IllegalStateException(nanos.length + " round trips reported, expected " + iterations);
        }
        return new RoundTrips(payloadBytes, nanos);
    }

    /** Stops every container JVM it started (B first, so that it leaves the platform before A ends it), forcibly if need be. */
    @Override
    public void close() {
        List<Container> reversed = new ArrayList<>(containers);
        Collections.reverse(reversed);
        for (Container c : reversed) {
            c.closeStdin();
        }
        for (Container c : reversed) {
            c.stop();
        }
    }

    /**
     * Round trips of one measurement.
     *
     * @param payloadBytes the size of the agent's byte array
     * @param nanos        each round trip A→B→A, nanoseconds, in the order measured
     */
    public record RoundTrips(int payloadBytes, long[] nanos) {

        /** @return the median round trip, microseconds */
        public double p50Micros() {
            return percentile(0.50);
        }

        /** @return the 99th percentile round trip, microseconds */
        public double p99Micros() {
            return percentile(0.99);
        }

        private double percentile(double q) {
            long[] sorted = nanos.clone();
            Arrays.sort(sorted);
            return sorted[Math.min(sorted.length - 1, (int) (sorted.length * q))] / 1000.0;
        }
    }

    // ---- processes ----

    private Container launch(String name, String... args) throws IOException {
        Path logs = Path.of("target", "it-logs").toAbsolutePath();
        Files.createDirectories(logs);
        // JADE's main container writes APDescription.txt into its working directory: keep it in target/.
        Path work = Path.of("target", "jade").toAbsolutePath();
        Files.createDirectories(work);
        List<String> command = new ArrayList<>();
        command.add(ProcessHandle.current().info().command().orElse(Path.of(System.getProperty("java.home"), "bin", "java").toString()));
        command.add("-Xmx1g");
        command.add("-cp");
        command.add(absoluteClassPath());
        command.add(JadeContainerMain.class.getName());
        command.addAll(List.of(args));
        Process process = new ProcessBuilder(command).directory(work.toFile()).redirectError(logs.resolve(name + ".log").toFile()).start();
        Container c = new Container(name, process);
        containers.add(c);
        return c;
    }

    /** This JVM's class path with every entry absolute, as the container JVMs run in another directory. */
    private static String absoluteClassPath() {
        StringBuilder cp = new StringBuilder();
        for (String entry : System.getProperty("java.class.path").split(File.pathSeparator)) {
            if (!entry.isEmpty()) {
                cp.append(cp.length() == 0 ? "" : File.pathSeparator).append(Path.of(entry).toAbsolutePath());
            }
        }
        return cp.toString();
    }

    private static int freePort() throws IOException {
        try (ServerSocket s = new ServerSocket(0, 1, InetAddress.getByName("127.0.0.1"))) {
            return s.getLocalPort();
        }
    }

    /** A container JVM: commands to its stdin, its stdout lines read with deadlines. */
    private static final class Container {
        private final String name;
        private final Process process;
        private final PrintStream in;
        private final StdoutLines lines;

        Container(String name, Process process) {
            this.name = name;
            this.process = process;
            this.in = new PrintStream(process.getOutputStream(), true, StandardCharsets.UTF_8);
            this.lines = new StdoutLines(process, "jade-bench-stdout-" + name);
        }

        void send(String command) {
            in.println(command);
        }

        String expect(String prefix, Duration within) throws TimeoutException, InterruptedException {
            long deadline = System.nanoTime() + within.toNanos();
            while (true) {
                String line = lines.next(deadline);
                if (line == null) {
                    throw new TimeoutException(name + " did not answer '" + prefix + "' within " + within + " (log: target/it-logs/" + name + ".log)");
                }
                if (line.startsWith(prefix)) {
                    return line;
                }
                if (line.startsWith("ERR") || StdoutLines.ended(line)) {
                    throw new IllegalStateException(name + " answered '" + line + "' while '" + prefix + "' was expected (log: target/it-logs/" + name + ".log)");
                }
            }
        }

        /** Closing stdin asks the JVM to end. */
        void closeStdin() {
            in.close();
        }

        /** Waits 10 s for the JVM to end, then destroys it, then after 5 s more destroys it forcibly; always waits for it to be gone. */
        void stop() {
            boolean interrupted = false;
            try {
                if (!waitFor(Duration.ofSeconds(10))) {
                    process.destroy();
                    if (!waitFor(Duration.ofSeconds(5))) {
                        process.destroyForcibly();
                        waitFor(Duration.ofSeconds(10));
                    }
                }
            } catch (InterruptedException e) {
                interrupted = true;
                process.destroyForcibly();
            } finally {
                if (process.isAlive()) {
                    process.destroyForcibly();
                }
                if (interrupted) {
                    Thread.currentThread().interrupt();
                }
            }
        }

        private boolean waitFor(Duration d) throws InterruptedException {
            return process.waitFor(d.toMillis(), TimeUnit.MILLISECONDS);
        }
    }
}
