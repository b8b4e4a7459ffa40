package io.robomw.it.foxglove;

import com.fasterxml.jackson.databind.JsonNode;
import com.fasterxml.jackson.databind.ObjectMapper;
import io.robomw.it.StdoutLines;
import io.robomw.it.demo.MwProcess;

import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.TimeUnit;

import static org.junit.jupiter.api.Assertions.fail;

/**
 * The Python side of the Foxglove tests (src/test/python): the interpreter of the environment
 * {@code .ci/run} makes ({@code target/it-python}, from {@code requirements.txt}: foxglove-sdk
 * 0.30.3 and websockets), or the one {@code -Dit.python=...} names. A missing environment fails the
 * test saying how to make it; it is never skipped.
 */
final class PythonClients {

    static final Path SCRIPTS = MwProcess.CHECKOUT.resolve("src-it/src/test/python");
    private static final ObjectMapper JSON = new ObjectMapper();

    private PythonClients() {
    }

    /** @return the Python that has the requirements, checked */
    static Path python() throws IOException, InterruptedException {
        String given = System.getProperty("it.python");
        Path python = given != null ? Path.of(given) : MwProcess.CHECKOUT.resolve("target/it-python/bin/python");
        String make = "python3 -m venv target/it-python && target/it-python/bin/pip install -r src-it/src/test/python/requirements.txt"
                + " (what .ci/run does), or name a Python that has them with -Dit.python=PATH";
        if (!Files.isExecutable(python)) {
            fail("the Foxglove tests need Python with foxglove-sdk and websockets at " + python + ": " + make);
        }
        Process p = new ProcessBuilder(python.toString(), "-c", "import foxglove, websockets; print(foxglove.__name__)").redirectErrorStream(true).start();
        if (!p.waitFor(60, TimeUnit.SECONDS) || p.exitValue() != 0) {
            p.destroyForcibly();
            fail(python + " lacks foxglove-sdk or websockets (" + new String(p.getInputStream().readAllBytes()).strip() + "): " + make);
        }
        return python;
    }

    /**
     * Runs the probe (foxglove_probe.py) to its end.
     *
     * @param name for its log, target/it-logs/NAME.log
     * @param args the probe's arguments
     * @return what it printed, one JSON object per line
     */
    static List<JsonNode> probe(String name, String... args) throws IOException, InterruptedException {
        List<String> command = new ArrayList<>(List.of(python().toString(), SCRIPTS.resolve("foxglove_probe.py").toString()));
        command.addAll(List.of(args));
        Path logs = Files.createDirectories(Path.of("target", "it-logs"));
        Path out = logs.resolve(name + ".out");
        Process p = new ProcessBuilder(command).redirectOutput(out.toFile()).redirectError(logs.resolve(name + ".log").toFile()).start();
        try {
            if (!p.waitFor(2, TimeUnit.MINUTES)) {
                fail("the probe " + name + " did not finish within 2 minutes; it printed:\n" + Files.readString(out));
            }
            if (p.exitValue() != 0) {
                fail("the probe " + name + " failed (exit " + p.exitValue() + "): " + Files.readString(logs.resolve(name + ".log")) + "\nit printed:\n"
                        + Files.readString(out));
            }
        } finally {
            p.destroyForcibly();
        }
        List<JsonNode> lines = new ArrayList<>();
        for (String line : Files.readAllLines(out)) {
            lines.add(JSON.readTree(line));
        }
        return lines;
    }

    /** @return the first line with that field, its value */
    static JsonNode field(List<JsonNode> lines, String field) {
        return lines.stream().filter(l -> l.has(field)).findFirst().map(l -> l.get(field))
                .orElseGet(() -> fail("the probe printed no '" + field + "': " + lines));
    }

    /** foxglove-sdk's reference server (foxglove_reference_server.py), serving until closed. */
    static final class ReferenceServer implements AutoCloseable {
        private final Process process;
        private final int port;

        ReferenceServer(String topic) throws IOException, InterruptedException {
            Path schema = MwProcess.CHECKOUT.resolve("mw-console/src/main/resources/io/robomw/console/schemas/foxglove.PoseInFrame.json");
            Path logs = Files.createDirectories(Path.of("target", "it-logs"));
            this.process = new ProcessBuilder(python().toString(), SCRIPTS.resolve("foxglove_reference_server.py").toString(), topic, schema.toString())
                    .redirectError(logs.resolve("foxglove-reference-server.log").toFile()).start();
            StdoutLines lines = new StdoutLines(process, "it-foxglove-reference");
            String line = lines.next(System.nanoTime() + Duration.ofSeconds(60).toNanos());
            if (line == null || !line.startsWith("listening on ")) {
                close();
                fail("foxglove-sdk's server did not start (log: target/it-logs/foxglove-reference-server.log); it printed: " + line);
            }
            this.port = Integer.parseInt(line.substring("listening on ".length()).trim());
        }

        String url() {
            return "ws://127.0.0.1:" + port;
        }

        @Override
        public void close() throws InterruptedException {
            try {
                process.getOutputStream().close(); // its standard input ends: it stops
            } catch (IOException e) {
                // already gone
            }
            if (!process.waitFor(15, TimeUnit.SECONDS)) {
                process.destroyForcibly();
                process.waitFor(10, TimeUnit.SECONDS);
            }
        }
    }
}
